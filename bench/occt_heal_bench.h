// kintsugi-bench occt-heal (bench/occt_heal_bench.cpp): built only with OpenCASCADE.
#pragma once

#include <string>

namespace kintsugi::bench {

// Writes the family with `faces` faces (defect rate, seed) to STEP in `dir`, then heals it
// with kintsugi and with OpenCASCADE's ShapeFix_Shape + UnifySameDomain, each in a child
// process; prints both and the ratio of the heal times. Returns 0, or 1 when a side failed.
int bench_occt_heal(long long faces, double rate, long long seed, const std::string& dir);

}  // namespace kintsugi::bench
