#include "invariants/element_geometry.h"
#include "invariants/geometry_check.h"
#include "kernel/builders.h"
#include "kernel/euler.h"

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

namespace kintsugi {
namespace {

constexpr double kPrecision = 1e-9;

std::vector<Body> solids() {
  std::vector<Body> out;
  out.push_back(build::box(1, 2, 3));
  out.push_back(build::prism(build::regular_polygon(7, 2), 1));
  out.push_back(build::pyramid(build::regular_polygon(4, 1), 1));
  out.push_back(build::cylinder(1, 2));
  out.push_back(build::cone(1, 2));
  out.push_back(build::sphere(2));
  out.push_back(build::torus(3, 1));
  out.push_back(build::grid_box(96));
  return out;
}

TEST(GeometryCheck, BuilderSolidsAreConsistent) {
  for (const Body& b : solids()) {
    GeometryReport r = check_geometry(b, kPrecision);
    for (const auto& v : r.violations) ADD_FAILURE() << to_string(v);
    EXPECT_LE(r.max_deviation, kPrecision);
  }
}

TEST(GeometryCheck, AVertexMovedByTenTimesThePrecisionIsNamed) {
  for (Body b : solids()) {
    VertexH v = b.vertices().back();
    geo::Vec3 p = b.point(v);
    // Move it off every surface: along the direction away from the body's centre.
    geo::Vec3 dir = p.norm() > 0 ? p.normalized() : geo::Vec3::UnitZ();
    b.set_point(v, p + 10 * kPrecision * dir + 10 * kPrecision * geo::Vec3(0.3, -0.2, 0.1));
    GeometryReport r = check_geometry(b, kPrecision);
    ASSERT_FALSE(r.violations.empty());
    bool named = false;
    for (const auto& x : r.violations)
      for (const auto& el : x.elements) named = named || el == v.str();
    EXPECT_TRUE(named) << "no violation names " << v;
    EXPECT_GT(r.max_deviation, kPrecision);
    EXPECT_EQ(r.max_elements.front(), v.str());
  }
}

TEST(GeometryCheck, MissingGeometryAndWrongSenseAreReported) {
  Body b = build::box();
  FaceH f = b.faces()[0];
  geo::Surface s = b.surface(f);
  b.set_surface(f, s, false);  // outward normal now opposite to the loop's turn
  GeometryReport r = check_geometry(b, kPrecision);
  ASSERT_FALSE(r.violations.empty());
  EXPECT_EQ(r.violations.front().invariant, "face_sense");
  b.set_surface(f, geo::Surface{});
  r = check_geometry(b, kPrecision);
  EXPECT_EQ(r.violations.front().invariant, "face_without_surface");
}

// Scaling a model by k moves every measured deviation by k: the same decisions at the same
// relative precision.
RC_GTEST_PROP(GeometryCheck, ScaleInvariance, ()) {
  const double k = *rc::gen::element(1e-3, 0.5, 7.0, 1e3);
  const int which = *rc::gen::inRange(0, 4);
  Body b = which == 0 ? build::box(k, 2 * k, 3 * k)
         : which == 1 ? build::cylinder(k, 2 * k)
         : which == 2 ? build::torus(3 * k, k)
                      : build::cone(k, k);
  RC_ASSERT(check_geometry(b, kPrecision * k).violations.empty());
  VertexH v = b.vertices().front();
  b.set_point(v, b.point(v) + geo::Vec3(5, 5, 5) * kPrecision * k);
  RC_ASSERT(!check_geometry(b, kPrecision * k).violations.empty());
}

}  // namespace
}  // namespace kintsugi

namespace kintsugi {
namespace {

// A short arc of a circle on a cylinder: its chord is a sagitta away from the surface,
// the arc itself is on it. The check must probe the arc.
TEST(GeometryCheck, ShortArcsAreProbedOnTheCurveNotTheChord) {
  Body b = build::cylinder(3, 1);
  for (EdgeH e : b.edges()) {
    if (!std::holds_alternative<geo::Circle>(b.curve(e))) continue;
    HalfedgeH h = halfedge_of(e, 0);
    const auto& c = std::get<geo::Circle>(b.curve(e));
    // Cut the circle at 0.05 rad: a short arc from the seam vertex to the new vertex.
    geo::Vec3 p = c.frame.origin + c.radius * (std::cos(0.05) * c.frame.x + std::sin(0.05) * c.frame.y());
    ASSERT_TRUE(euler::semv(b, h, p));
    break;
  }
  GeometryReport r = check_geometry(b, 3e-7);
  for (const auto& v : r.violations) ADD_FAILURE() << to_string(v);
}

}  // namespace
}  // namespace kintsugi
