#pragma once
// FNV-1a, 64 bit: the checksum of checkpoint data and the scene hash that ties
// a checkpoint or snapshot to the scene file it came from. Not cryptographic;
// it catches torn writes, flipped bytes and the wrong scene, not tampering.
#include <cinttypes>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace gs {

class Fnv1a64 {
 public:
  static constexpr std::uint64_t kOffsetBasis = 14695981039346656037ull;
  static constexpr std::uint64_t kPrime = 1099511628211ull;

  // Byte for byte the FNV-1a of the bytes, but a zero byte leaves h ^ 0 = h,
  // so a run of k zero bytes multiplies by kPrime^k (mod 2^64), taken in
  // log k steps: checkpoints are mostly empty history slots, all zeros, and
  // the byte loop (one multiply's latency per byte) is the slow part.
  void add(const void* bytes, std::size_t count) {
    const auto* p = static_cast<const unsigned char*>(bytes);
    std::uint64_t h = hash_;
    std::size_t i = 0, zeros = 0;  // zeros: a run of zero bytes not yet applied
    for (; i + 8 <= count; i += 8) {
      std::uint64_t word;
      std::memcpy(&word, p + i, 8);
      if (word == 0) {
        zeros += 8;
        continue;
      }
      h *= prime_power(zeros);
      zeros = 0;
      for (std::size_t k = 0; k < 8; ++k) h = (h ^ p[i + k]) * kPrime;
    }
    h *= prime_power(zeros);
    for (; i < count; ++i) h = (h ^ p[i]) * kPrime;
    hash_ = h;
  }
  // The value's bytes as they lie in memory (little-endian on every target we build for).
  template <class T>
  void add_value(const T& value) { add(&value, sizeof(T)); }
  template <class T>
  void add_array(const std::vector<T>& values) { add(values.data(), values.size() * sizeof(T)); }

  std::uint64_t value() const { return hash_; }

 private:
  static std::uint64_t prime_power(std::size_t k) {  // kPrime^k mod 2^64
    std::uint64_t result = 1, base = kPrime;
    for (; k > 0; k >>= 1, base *= base)
      if (k & 1) result *= base;
    return result;
  }
  std::uint64_t hash_ = kOffsetBasis;
};

// "0x" and 16 hex digits: how hashes, checksums and digests are printed.
inline std::string hex64(std::uint64_t value) {
  char text[24];
  std::snprintf(text, sizeof(text), "0x%016" PRIx64, value);
  return text;
}

// FNV-1a 64 of the scene file's text, byte for byte: any edit changes it.
inline std::uint64_t scene_hash(const std::string& scene_file_text) {
  Fnv1a64 h;
  h.add(scene_file_text.data(), scene_file_text.size());
  return h.value();
}

}  // namespace gs
