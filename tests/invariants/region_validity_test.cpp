// The validity gate's check (invariants/region_validity.h): valid solids pass, and each
// kind of invalidity OpenCASCADE's checker finds — a vertex or edge off its geometry, a
// loop crossing itself or another in the face's parameter domain, a loop turning the
// wrong way, an edge between two vertices at one point — is found and named.
#include "invariants/region_validity.h"
#include "kernel/builders.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace kintsugi {
namespace {

const geo::Tolerances kTol{1e-3, 1e-9};

bool has(const std::vector<Violation>& v, const std::string& code) {
  return std::any_of(v.begin(), v.end(), [&](const Violation& x) { return x.invariant == code; });
}

std::string list(const std::vector<Violation>& v) {
  std::string s;
  for (const Violation& x : v) s += x.invariant + ": " + x.detail + "\n";
  return s;
}

TEST(RegionValidity, BuilderSolidsAreValid) {
  for (const Body& b : {build::box(1, 2, 3), build::prism(build::regular_polygon(7, 2), 1), build::cylinder(1, 2),
                        build::cone(1, 2), build::sphere(2), build::torus(3, 1), build::grid_box(24)}) {
    auto v = region_violations(b, whole_body(b), kTol, kTol.precision);
    EXPECT_TRUE(v.empty()) << list(v);
  }
}

// The top face of a box with two neighbouring corners swapped: its loop is a bow tie.
TEST(RegionValidity, ASelfCrossingLoopIsFound) {
  Body b = build::box(1, 1, 1);
  FaceH top;
  for (FaceH f : b.faces()) {
    bool all_up = true;
    for (VertexH v : b.loop_vertices(b.outer_loop(f))) all_up = all_up && b.point(v).z() > 0.5;
    if (all_up) top = f;
  }
  ASSERT_TRUE(top.valid());
  std::vector<VertexH> vs = b.loop_vertices(b.outer_loop(top));
  const geo::Vec3 p1 = b.point(vs[1]), p2 = b.point(vs[2]);
  b.set_point(vs[1], p2);
  b.set_point(vs[2], p1);
  for (HalfedgeH h : b.loop_halfedges(b.outer_loop(top))) {
    const geo::Vec3 a = b.point(b.origin(halfedge_of(edge_of(h), 0))), c = b.point(b.target(halfedge_of(edge_of(h), 0)));
    b.set_curve(edge_of(h), geo::Line{a, (c - a).normalized()});
  }
  auto loops = loop_violations(b, {top}, kTol);
  EXPECT_TRUE(has(loops, "loop_self_intersection")) << list(loops);
  // The whole region also finds the side faces' vertices off their planes.
  Region r;
  r.vertices = {vs[1], vs[2]};
  auto all = region_violations(b, r, kTol, kTol.precision);
  EXPECT_TRUE(has(all, "loop_self_intersection")) << list(all);
  EXPECT_TRUE(has(all, "vertex_on_surface")) << list(all);
  EXPECT_NE(region_validity(b, r, kTol, kTol.precision), "");
}

TEST(RegionValidity, AWrongSenseIsFoundOnPlanesAndCylinders) {
  for (Body b : {build::box(1, 1, 1), build::cylinder(1, 2)}) {
    for (FaceH f : b.faces()) {
      Body c = b;
      c.set_surface(f, c.surface(f), !c.same_sense(f));
      auto v = loop_violations(c, {f}, kTol);
      // A cylinder's band (two loops winding around) has no closed loop to judge.
      if (std::holds_alternative<geo::Cylinder>(c.surface(f))) continue;
      EXPECT_TRUE(has(v, "loop_orientation")) << f.str() << "\n" << list(v);
    }
  }
}

TEST(RegionValidity, AVertexOffItsCurveAndSurfacesIsFound) {
  Body b = build::box(1, 1, 1);
  VertexH v = b.vertices().front();
  b.set_point(v, b.point(v) + geo::Vec3(1e-6, 2e-6, -1e-6));
  Region r;
  r.vertices = {v};
  auto found = region_violations(b, r, kTol, kTol.precision);
  EXPECT_TRUE(has(found, "vertex_on_curve")) << list(found);
  EXPECT_TRUE(has(found, "vertex_on_surface")) << list(found);
  // Within what the input already had, it passes.
  EXPECT_TRUE(region_violations(b, r, kTol, lies_on_limit(kTol, 1e-5)).empty());
}

TEST(RegionValidity, TwoVerticesAtOnePointOnAnEdgeAreFound) {
  Body b = build::box(1, 1, 1);
  EdgeH e = b.edges().front();
  HalfedgeH h = halfedge_of(e, 0);
  b.set_point(b.target(h), b.point(b.origin(h)));
  Region r;
  r.edges = {e};
  EXPECT_TRUE(has(region_violations(b, r, kTol, kTol.precision), "degenerate_edge"));
}

TEST(RegionValidity, TheExternalCheckIsAsked) {
  Body b = build::box(1, 1, 1);
  set_external_region_check([](const Body&, const Region&) { return std::string("no, says the external check"); });
  std::string why = region_validity(b, whole_body(b), kTol, kTol.precision);
  set_external_region_check(nullptr);
  EXPECT_NE(why.find("no, says the external check"), std::string::npos) << why;
  EXPECT_EQ(region_validity(b, whole_body(b), kTol, kTol.precision), "");
}

}  // namespace
}  // namespace kintsugi
