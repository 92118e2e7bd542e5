// The checksum's FNV-1a 64 (io/fnv1a.hpp), which skips runs of zero bytes
// arithmetically: the published test vectors, and byte-for-byte agreement
// with the plain definition on data with zero runs of every length and
// alignment, added in one piece and in pieces.
#include <gtest/gtest.h>

#include <cstdint>
#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "io/fnv1a.hpp"

namespace gs {
namespace {

// The definition: h = (h xor byte) * prime, for every byte.
std::uint64_t reference(const std::vector<unsigned char>& bytes) {
  std::uint64_t h = 14695981039346656037ull;
  for (unsigned char b : bytes) h = (h ^ b) * 1099511628211ull;
  return h;
}

std::uint64_t of_text(const std::string& s) {
  Fnv1a64 h;
  h.add(s.data(), s.size());
  return h.value();
}

TEST(Fnv1a64, PublishedTestVectors) {  // from the FNV reference (isthe.com/chongo/tech/comp/fnv)
  EXPECT_EQ(of_text(""), 0xcbf29ce484222325ull);
  EXPECT_EQ(of_text("a"), 0xaf63dc4c8601ec8cull);
  EXPECT_EQ(of_text("foobar"), 0x85944171f73967e8ull);
}

TEST(Fnv1a64, ZeroRunsAgreeWithTheDefinition) {
  std::mt19937 random(7);
  std::vector<unsigned char> bytes;
  for (int run = 0; run < 400; ++run) {
    const std::size_t zeros = random() % 300, others = random() % 12;
    bytes.insert(bytes.end(), zeros, 0);
    for (std::size_t k = 0; k < others; ++k) bytes.push_back(static_cast<unsigned char>(random() % 256));
  }
  bytes.insert(bytes.end(), 1000, 0);  // ends in zeros
  for (std::size_t offset : {0, 1, 3, 7}) {
    const std::vector<unsigned char> part(bytes.begin() + std::ptrdiff_t(offset), bytes.end());
    Fnv1a64 whole;
    whole.add(part.data(), part.size());
    EXPECT_EQ(whole.value(), reference(part)) << "offset " << offset;
    Fnv1a64 pieces;
    for (std::size_t at = 0; at < part.size(); at += 37) pieces.add(part.data() + at, std::min<std::size_t>(37, part.size() - at));
    EXPECT_EQ(pieces.value(), reference(part)) << "offset " << offset;
  }
}

}  // namespace
}  // namespace gs
