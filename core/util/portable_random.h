// Random numbers that are the same on every platform and standard library: std::mt19937_64
// is specified bit for bit, but std::uniform_int_distribution and std::shuffle are not.
#pragma once

#include <cstdint>
#include <random>
#include <string_view>
#include <vector>

namespace handlab::util {

class PortableRandom {
 public:
  explicit PortableRandom(std::uint64_t seed) : engine_(seed) {}

  // Uniform in [0, n) by rejection sampling (no modulo bias). n > 0.
  std::uint64_t below(std::uint64_t n);
  // Uniform in [0, 1) with 53 random bits.
  double uniform();
  // Standard normal, by Box-Muller from two uniforms (one draw per call, no spare kept).
  double normal();
  // Fisher-Yates shuffle.
  template <typename T>
  void shuffle(std::vector<T>& items) {
    for (std::size_t i = items.size(); i > 1; --i) std::swap(items[i - 1], items[below(i)]);
  }

 private:
  std::mt19937_64 engine_;
};

// SplitMix64's finaliser: a well-mixed 64-bit value from a seed and a counter combined.
std::uint64_t splitmix64(std::uint64_t x);

// FNV-1a 64-bit hash of text, to derive per-participant seeds from their ids.
std::uint64_t fnv1a64(std::string_view text);

}  // namespace handlab::util
