// FNV-1a over the bits of doubles, for keys of exact values: points that must be
// bit-identical to be one (view/tessellate.cpp) and fingerprints of a solve's input
// (repair/region_solve.cpp remembers failed solves by it).
#pragma once

#include <cstdint>
#include <cstring>

namespace kintsugi::geo {

inline constexpr std::uint64_t kFnvOffsetBasis = 14695981039346656037ull;

// h with the 64 bits of `bits` mixed in.
inline std::uint64_t fnv_mix(std::uint64_t h, std::uint64_t bits) { return (h ^ bits) * 1099511628211ull; }

// h with the bits of x mixed in (so -0.0 and +0.0 differ: callers that want them alike
// fold them first).
inline std::uint64_t fnv_mix(std::uint64_t h, double x) {
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  return fnv_mix(h, bits);
}

}  // namespace kintsugi::geo
