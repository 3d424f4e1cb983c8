// The validity gate on a face with many loops (invariants/region_validity.h): a plate with
// a hole per feature is checked near what a repair changed only. One repair beside the
// plate of a 100,000-face family took 88 minutes when OpenCASCADE classified every wire of
// the plate against every other (issue 18). These tests hold the gate to what it must
// still do there: find a crossing the change makes, by our loop check and by
// OpenCASCADE's, leave out loops far away, and let repairs on the plate through.
#include "invariants/element_geometry.h"
#include "invariants/region_validity.h"
#include "invariants/topology_check.h"
#include "io/occt/exchange.h"
#include "repair/beautify.h"
#include "zoo/zoo.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace kintsugi {
namespace {

bool has(const std::vector<Violation>& v, const std::string& code) {
  return std::any_of(v.begin(), v.end(), [&](const Violation& x) { return x.invariant == code; });
}

FaceH face_with_most_loops(const Body& b) {
  FaceH best;
  std::size_t most = 0;
  for (FaceH f : b.faces())
    if (std::size_t n = b.loops_of(f).size(); n > most) most = n, best = f;
  return best;
}

geo::Vec3 centroid(const Body& b, LoopH l) {
  geo::Vec3 c = geo::Vec3::Zero();
  std::vector<VertexH> vs = b.loop_vertices(l);
  for (VertexH v : vs) c += b.point(v);
  return c / double(vs.size());
}

// A ring of the plate with four corners (a block's or a pyramid's base), the nearest
// other such ring, and one far from both.
struct Rings {
  LoopH moved, near, far;
};

Rings pick_rings(const Body& b, FaceH plate) {
  std::vector<LoopH> squares;
  for (LoopH l : b.loops_of(plate))
    if (!b.is_outer(l) && !b.is_lone(l) && b.loop_vertices(l).size() == 4) squares.push_back(l);
  Rings r;
  if (squares.size() < 3) return r;
  r.moved = squares.front();
  const geo::Vec3 c = centroid(b, r.moved);
  double nearest = HUGE_VAL, farthest = 0.0;
  for (std::size_t i = 1; i < squares.size(); ++i) {
    double d = (centroid(b, squares[i]) - c).norm();
    if (d < nearest) nearest = d, r.near = squares[i];
    if (d > farthest) farthest = d, r.far = squares[i];
  }
  return r;
}

// Moves v (in the plate's plane) to `to`, with straight edges through its new place.
void move_corner(Body& b, VertexH v, const geo::Vec3& to) {
  b.set_point(v, to);
  for (HalfedgeH h : b.outgoing(v)) {
    EdgeH e = edge_of(h);
    const geo::Vec3 a = b.point(b.origin(halfedge_of(e, 0))), c = b.point(b.target(halfedge_of(e, 0)));
    b.set_curve(e, geo::Line{a, (c - a).normalized()});
  }
}

TEST(PlateGate, ACrossingMadeNearTheChangeIsFoundAndOneFarAwayIsNotChargedToIt) {
  zoo::ZooModel m = zoo::family(400, 0.0, 7);
  Body b = m.body;
  const geo::Tolerances tol = geo::Tolerances::for_model(m.tolerance, model_size(b));
  const FaceH plate = face_with_most_loops(b);
  const std::size_t all = b.loops_of(plate).size();
  ASSERT_GT(all, 4 * kManyLoops);
  const Rings rings = pick_rings(b, plate);
  ASSERT_TRUE(rings.far.valid());
  ASSERT_NE(rings.near, rings.far);

  // One corner of a block's base moved into the middle of the next base: its two edges
  // on the plate now cross that base's loop.
  const VertexH v = b.loop_vertices(rings.moved).front();
  move_corner(b, v, centroid(b, rings.near));

  Region here;
  here.vertices = {v};
  here.surfaces_set = std::set<FaceH>{};
  auto found = region_violations(b, here, tol, tol.precision);
  EXPECT_TRUE(has(found, "loops_cross"));

  // What loops_near keeps: the outer loop, the moved ring and its neighbour, not the far
  // one, and far fewer than all.
  geo::Box box;
  for (VertexH w : b.loop_vertices(rings.moved)) box.add(b.point(w));
  box = geo::Box{box.min.array() - tol.length, box.max.array() + tol.length};
  std::vector<LoopH> near = loops_near(b, plate, box);
  EXPECT_EQ(near.front(), b.outer_loop(plate));
  EXPECT_NE(std::find(near.begin(), near.end(), rings.moved), near.end());
  EXPECT_NE(std::find(near.begin(), near.end(), rings.near), near.end());
  EXPECT_EQ(std::find(near.begin(), near.end(), rings.far), near.end());
  EXPECT_LT(near.size(), all / 4);

  // A region at the far ring: the crossing is the face's, from before that repair, and
  // not charged to it. Only when the caller cannot say the plate's surface is unchanged
  // is the whole plate grown in, and then the moved corner is found off the block's sides.
  Region far;
  far.vertices = {b.loop_vertices(rings.far).front()};
  far.surfaces_set = std::set<FaceH>{};
  auto elsewhere = region_violations(b, far, tol, tol.precision);
  EXPECT_TRUE(elsewhere.empty()) << elsewhere.front().invariant << ": " << elsewhere.front().detail;
  far.surfaces_set.reset();
  auto whole = region_violations(b, far, tol, tol.precision);
  EXPECT_TRUE(has(whole, "vertex_on_surface"));
  EXPECT_FALSE(has(whole, "loops_cross"));
}

// OpenCASCADE's check of the plate, given only the loops near the change, finds the
// crossing too (our own check is bypassed here, as it runs first in region_violations)
// and passes the plate as it was.
TEST(PlateGate, OpenCascadeChecksTheLoopsNearTheChange) {
  zoo::ZooModel m = zoo::family(400, 0.0, 11);
  Body b = m.body;
  const Body original = b;
  const geo::Tolerances tol = geo::Tolerances::for_model(m.tolerance, model_size(b));
  const FaceH plate = face_with_most_loops(b);
  const Rings rings = pick_rings(b, plate);
  ASSERT_TRUE(rings.near.valid());

  auto region_of = [&](const Body& body) {
    Region g;
    g.faces = {plate};
    geo::Box box;
    for (VertexH w : body.loop_vertices(rings.moved)) box.add(body.point(w));
    box = geo::Box{box.min.array() - tol.length, box.max.array() + tol.length};
    g.near[plate] = {box, loops_near(body, plate, box)};
    return g;
  };
  io::register_occt_region_check(original, tol.precision);
  ExternalRegionCheck occt = external_region_check();
  ASSERT_NE(occt, nullptr);
  EXPECT_EQ(occt(b, region_of(b)), "");

  move_corner(b, b.loop_vertices(rings.moved).front(), centroid(b, rings.near));
  EXPECT_NE(occt(b, region_of(b)), "");
  set_external_region_check(nullptr);
}

// Defects on the plate itself, repaired with OpenCASCADE's check on every repair: each
// is repaired (the designer's counts come back) and the result is valid by both checks.
TEST(PlateGate, RepairsOnThePlatePassTheGate) {
  zoo::ZooModel clean = zoo::family(400, 0.0, 3);
  Body b = clean.body;
  const FaceH plate = face_with_most_loops(b);
  int injected = 0;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    const ProblemType t = seed % 2 ? ProblemType::short_edge_chain : ProblemType::mergeable_edges;
    std::string why;
    if (zoo::inject(b, t, seed, plate.str(), clean.tolerance, &why)) ++injected;
  }
  ASSERT_GE(injected, 6);
  const geo::Tolerances tol = geo::Tolerances::for_model(clean.tolerance, model_size(b));
  io::register_occt_region_check(b, tol.precision);
  BeautifyReport r = beautify(b, tol);
  set_external_region_check(nullptr);
  EXPECT_EQ(r.not_repaired(), 0);
  EXPECT_EQ(b.counts(), clean.body.counts());
  EXPECT_TRUE(check_topology(b).empty());
  auto ours = region_violations(b, whole_body(b), tol, tol.precision);
  EXPECT_TRUE(ours.empty()) << ours.front().invariant << ": " << ours.front().detail;
  io::OcctVerdict theirs = io::occt_check(b, tol.precision);
  EXPECT_TRUE(theirs.valid) << (theirs.problems.empty() ? "" : theirs.problems.front());
}

}  // namespace
}  // namespace kintsugi
