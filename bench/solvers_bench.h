// kintsugi-bench solvers (bench/solvers_bench.cpp).
#pragma once

namespace kintsugi::bench {
// Prints the cost per call of geo::meet_point and geo::fit_surface_like on fixed random
// cases, with checksums of their answers; 0 when every case was solved.
int bench_solvers();
}  // namespace kintsugi::bench
