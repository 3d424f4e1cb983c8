// Deterministic random numbers for the zoo. std::mt19937_64's output sequence is fixed
// by the standard, but std::uniform_real_distribution and friends are not (libstdc++,
// libc++ and MSVC give different values), so the distributions are our own.
#pragma once

#include <cstdint>
#include <random>

namespace kintsugi::zoo {

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : g_(seed) {}
  // Uniform in [0, 1): the top 53 bits of one draw.
  double unit() { return double(g_() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * unit(); }
  // Uniform in [0, n) for n > 0 (multiply-shift; the bias is below 2^-64 * n).
  std::uint64_t below(std::uint64_t n) {
    return std::uint64_t((static_cast<unsigned __int128>(g_()) * n) >> 64);
  }
  double sign() { return (g_() >> 63) ? 1.0 : -1.0; }
  std::uint64_t raw() { return g_(); }

 private:
  std::mt19937_64 g_;
};

}  // namespace kintsugi::zoo
