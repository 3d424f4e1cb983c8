// Beautify on random defective models: a builder solid, up to four defects injected by
// the zoo (any of the eleven types, sizes and places from the input), then the whole
// pipeline. The result must pass check_topology, and no Euler operator — in the injector
// or in any repair — may refuse with postcondition (a kernel bug, which the repairs would
// otherwise take for an ordinary refusal); a violation aborts (the fuzzer reports it).
#include "fuzz/die.h"
#include "invariants/element_geometry.h"
#include "invariants/topology_check.h"
#include "kernel/builders.h"
#include "kernel/euler.h"
#include "repair/beautify.h"
#include "zoo/zoo.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>

using namespace kintsugi;

using fuzz::die;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2 || size > 64) return 0;
  Body b;
  switch (data[0] % 6) {
    case 0: b = build::box(1, 2, 3); break;
    case 1: b = build::prism(build::regular_polygon(5 + data[1] % 4, 1), 1); break;
    case 2: b = build::pyramid(build::regular_polygon(4 + data[1] % 3, 1), 1); break;
    case 3: b = build::cylinder(1, 2); break;
    case 4: b = build::cone(1, 2); break;
    default: b = build::grid_box(24); break;
  }
  const double t = 0.01 + 0.01 * (data[1] % 4);
  std::string injected;
  for (std::size_t i = 2; i + 4 < size && i < 2 + 5 * 4; i += 5) {
    ProblemType type = kAllProblemTypes[data[i] % kAllProblemTypes.size()];
    std::uint32_t seed;
    std::memcpy(&seed, data + i + 1, 4);
    std::string err;
    if (auto inj = zoo::inject(b, type, seed, std::nullopt, t, &err)) injected += inj->description + "\n";
  }
  geo::Tolerances tol = geo::Tolerances::for_model(t, model_size(b));
  beautify(b, tol);
  auto v = check_topology(b);
  if (!v.empty()) die("check_topology after beautify: " + to_string(v.front()) + "\ninjected:\n" + injected);
  if (euler::postcondition_failures() != 0)
    die("an Euler operator refused with postcondition (a kernel bug)\ninjected:\n" + injected);
  return 0;
}
