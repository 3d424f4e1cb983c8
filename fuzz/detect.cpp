// Detection on random defective bodies: a planar builder solid, up to three defects injected by
// the zoo, then up to eight vertex moves of up to a few tolerances (what a careless fit
// does: the geometry is no longer consistent, the topology still valid). What must hold:
//   - detect is read-only: the body equals its copy from before, journal included;
//   - every element of every problem is alive (a dead handle would crash a repair);
//   - the counts agree with the list;
//   - detect_near over a neighbourhood holding the whole body finds exactly what detect
//     finds (spec/problems.md, "Detecting near a repair": it finds every problem anchored
//     in the neighbourhood, and here every problem is);
//   - detect on a copy gives the same result (no hidden state).
// A violation aborts (the fuzzer reports it).
#include "fuzz/die.h"
#include "invariants/element_geometry.h"
#include "kernel/builders.h"
#include "repair/detect.h"
#include "zoo/zoo.h"

#include <cstring>
#include <string>

using namespace kintsugi;

using fuzz::die;

namespace {

std::string listing(const Detection& d) {
  std::string s;
  for (const Problem& p : d.problems) {
    s += problem_name(p.type);
    for (const std::string& n : element_names(p)) s += " " + n;
    s += "\n";
  }
  return s;
}

bool same(const Detection& a, const Detection& b) {
  if (a.counts != b.counts || a.problems.size() != b.problems.size()) return false;
  for (std::size_t i = 0; i < a.problems.size(); ++i)
    if (!a.problems[i].same_identity(b.problems[i])) return false;
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2 || size > 96) return 0;
  Body b;
  // Planar solids only: under ASan a curved face's area (triangulated to 1e-3 t) takes
  // detect about 30 s on a cylinder, cone or torus, which would leave a handful of runs
  // a minute; curved faces are fuzzed by fuzz_beautify.
  switch (data[0] % 4) {
    case 0: b = build::box(1, 2, 3); break;
    case 1: b = build::prism(build::regular_polygon(5 + data[1] % 4, 1), 1); break;
    case 2: b = build::pyramid(build::regular_polygon(4 + data[1] % 3, 1), 1); break;
    default: b = build::grid_box(12); break;
  }
  const double t = 0.01 + 0.01 * (data[1] % 4);
  std::size_t i = 2;
  std::string what;
  // Defects: a 0xff byte ends them, else up to three of 5 bytes (type, seed).
  for (int k = 0; k < 3 && i + 5 <= size && data[i] != 0xff; ++k, i += 5) {
    ProblemType type = kAllProblemTypes[data[i] % kAllProblemTypes.size()];
    std::uint32_t seed;
    std::memcpy(&seed, data + i + 1, 4);
    if (auto inj = zoo::inject(b, type, seed, std::nullopt, t, nullptr)) what += inj->description + "\n";
  }
  if (i < size && data[i] == 0xff) ++i;
  // Vertex moves: 4 bytes each (vertex, and dx, dy, dz in steps of t/32 up to ±4t).
  const std::vector<VertexH> vs = b.vertices();
  for (int k = 0; k < 8 && i + 4 <= size && !vs.empty(); ++k, i += 4) {
    VertexH v = vs[data[i] % vs.size()];
    auto step = [&](std::uint8_t c) { return (int(c) - 128) * t / 32.0; };
    b.set_point(v, b.point(v) + geo::Vec3(step(data[i + 1]), step(data[i + 2]), step(data[i + 3])));
    what += "moved " + element_name(v) + "\n";
  }

  const geo::Tolerances tol = geo::Tolerances::for_model(t, model_size(b));
  const Body before = b.clone();
  const std::size_t journal_size = b.journal().size();
  const Detection d = detect(b, tol);
  std::string why;
  if (!b.equals(before, &why)) die("detect changed the body: " + why + "\n" + what);
  if (b.journal().size() != journal_size) die("detect wrote to the journal\n" + what);

  std::array<int, 11> counted{};
  for (const Problem& p : d.problems) {
    ++counted[std::size_t(problem_order(p.type) - 1)];
    for (const Element& e : p.elements)
      if (!std::visit([&](auto h) { return b.alive(h); }, e))
        die(std::string(problem_name(p.type)) + " names a dead element " + element_name(e) + "\n" + what);
  }
  if (counted != d.counts) die("the counts do not match the list of problems\n" + what);

  Neighbourhood all;
  for (FaceH f : b.faces()) all.faces.insert(f);
  for (EdgeH e : b.edges()) all.edges.insert(e);
  for (VertexH v : b.vertices()) all.vertices.insert(v);
  for (LoopH l : b.border_cycles()) all.borders.insert(l);
  const Detection near = detect_near(b, tol, all);
  if (!same(near, d))
    die("detect_near over the whole body differs from detect\ndetect:\n" + listing(d) + "detect_near:\n" +
        listing(near) + what);
  if (!same(detect(before, tol), d)) die("detect on a copy gives another result\n" + what);
  return 0;
}
