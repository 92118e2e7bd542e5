#pragma once
// Counter-based random numbers: the value for (seed, stream, index, draw) is a
// hash of those four words, computed alone. Anyone (any rank, any batch, a
// restarted run) gets the same number for the same counter without having
// drawn the numbers before it, which a sequential generator (mt19937) cannot
// give. The mixer is SplitMix64's finaliser (Steele, Lea, Flood 2014), whose
// outputs pass BigCrush for consecutive inputs.
#include <cstdint>

namespace gs {

inline std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

inline std::uint64_t counter_hash(std::uint64_t seed, std::uint64_t stream, std::uint64_t index, std::uint64_t draw) {
  std::uint64_t h = splitmix64(seed);
  h = splitmix64(h ^ stream);
  h = splitmix64(h ^ index);
  return splitmix64(h ^ draw);
}

// Uniform in [0, 1), 53 random bits.
inline double counter_uniform(std::uint64_t seed, std::uint64_t stream, std::uint64_t index, std::uint64_t draw) {
  return double(counter_hash(seed, stream, index, draw) >> 11) * 0x1.0p-53;
}

}  // namespace gs
