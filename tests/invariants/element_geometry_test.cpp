// Measures on kernel elements against closed forms.
#include "geometry/curve.h"
#include "geometry/transform.h"
#include "kernel/euler.h"
#include "invariants/element_geometry.h"
#include "kernel/builders.h"

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <cmath>

namespace kintsugi {
namespace {

// Fine enough for the closed forms below (the inscribed polygon of a circle of radius r
// loses about 4/3·chordal/r of the area), coarse enough to stay fast.
constexpr double kChordal = 1e-6;

double total_area(const Body& b) {
  double a = 0;
  for (FaceH f : b.faces()) {
    auto m = face_measure(b, f, kChordal);
    EXPECT_TRUE(m.ok()) << f << ": " << m.problem;
    a += m.area;
  }
  return a;
}

TEST(ElementGeometry, BoxAreasAndLengths) {
  Body b = build::box(1, 2, 3);
  EXPECT_NEAR(total_area(b), 2 * (2 + 3 + 6), 1e-9);
  double len = 0;
  for (EdgeH e : b.edges()) len += edge_length(b, e);
  EXPECT_NEAR(len, 4 * (1 + 2 + 3), 1e-12);
  EXPECT_NEAR(model_size(b), std::sqrt(14.0), 1e-12);
}

// The model size covers what the faces cover, not only the edges: a sphere's seam is a
// half circle, its box a cube.
TEST(ElementGeometry, ModelSizeCoversSpheresBeyondTheirSeams) {
  EXPECT_NEAR(model_size(build::sphere(2)), 4 * std::sqrt(3.0), 1e-2);
  EXPECT_NEAR(model_size(build::cylinder(1, 2)), std::sqrt(4.0 + 4.0 + 4.0), 1e-2);
}

TEST(ElementGeometry, CurvedSolidsMatchClosedForms) {
  const double r = 1.5, h = 2.0, R = 3.0;
  auto near = [](double got, double want) { EXPECT_NEAR(got, want, 2e-6 * want); };
  near(total_area(build::cylinder(r, h)), 2 * M_PI * r * r + 2 * M_PI * r * h);
  near(total_area(build::cone(r, h)), M_PI * r * r + M_PI * r * std::sqrt(r * r + h * h));
  near(total_area(build::sphere(r)), 4 * M_PI * r * r);
  near(total_area(build::torus(R, r * 0.5)), 4 * M_PI * M_PI * R * r * 0.5);
}

TEST(ElementGeometry, EdgeLengthsOfCircles) {
  Body c = build::cylinder(2, 1);
  double circles = 0, lines = 0;
  for (EdgeH e : c.edges()) {
    if (std::holds_alternative<geo::Circle>(c.curve(e)))
      circles += edge_length(c, e);
    else
      lines += edge_length(c, e);
  }
  EXPECT_NEAR(circles, 2 * 2 * M_PI * 2, 1e-12);
  EXPECT_NEAR(lines, 1, 1e-12);
  Body s = build::sphere(2);
  EXPECT_NEAR(edge_length(s, s.edges()[0]), M_PI * 2, 1e-12);  // a meridian from pole to pole
}

// A torus has one vertex: its size comes from its circles, sampled at a scale taken from
// their radii (it was taken from the vertices' extent, zero here, and sampling then ran
// to tens of millions of points).
TEST(ElementGeometry, ModelSizeOfATorusFromItsCircles) {
  EXPECT_NEAR(model_size(build::torus(3, 1)), std::sqrt(8.0 * 8.0 + 8.0 * 8.0 + 2.0 * 2.0), 1e-2);
  // However small the error asked for, sampling a curve is bounded.
  geo::Circle c;
  c.radius = 5;
  EXPECT_LE(geo::sample_curve(c, 0, 2 * M_PI, 1e-300).size(), std::size_t((1 << 20) + 1));
}

TEST(ElementGeometry, Distances) {
  Body b = build::box();
  // Two opposite edges of the top face are 1 apart; a vertex is 0 from its own edges.
  VertexH v = b.vertices()[0];
  HalfedgeH h = b.out(v);
  EXPECT_NEAR(vertex_edge_distance(b, v, edge_of(h), kChordal), 0, 1e-15);
  double best = 1e9;
  for (EdgeH e : b.edges())
    if (e != edge_of(h)) best = std::min(best, edge_edge_distance(b, edge_of(h), e, kChordal));
  EXPECT_NEAR(best, 0, 1e-15);  // adjacent edges touch
}

RC_GTEST_PROP(ElementGeometry, AreaAndLengthScaleWithTheModel, ()) {
  const double k = *rc::gen::element(1e-3, 0.25, 4.0, 1e3);
  Body a = build::cylinder(1, 2), b = build::cylinder(k, 2 * k);
  double area_a = 0, area_b = 0;
  // Sampling scaled with the model: similar polygons, so the areas agree to rounding.
  for (FaceH f : a.faces()) area_a += face_measure(a, f, 1e-4).area;
  for (FaceH f : b.faces()) area_b += face_measure(b, f, 1e-4 * k).area;
  RC_ASSERT(std::abs(area_b / (k * k) - area_a) < 1e-6 * area_a);
  double len_a = 0, len_b = 0;
  for (EdgeH e : a.edges()) len_a += edge_length(a, e);
  for (EdgeH e : b.edges()) len_b += edge_length(b, e);
  RC_ASSERT(std::abs(len_b / k - len_a) < 1e-9 * len_a);
}

// halfedge_box holds every point of halfedge_polyline, whatever the curve and however
// the solid is turned: full circles, arcs cut from them, lines, and the sampled rest.
// (Detection's pinch search pairs sides by these boxes before sampling them: a box too
// small would lose a pinch.)
RC_GTEST_PROP(ElementGeometry, HalfedgeBoxHoldsTheHalfedgesPolyline, ()) {
  const int kind = *rc::gen::inRange(0, 5);
  Body b = kind == 0 ? build::cylinder(1.5, 2)
         : kind == 1 ? build::cone(1.5, 2)
         : kind == 2 ? build::sphere(1.5)
         : kind == 3 ? build::torus(3, 1)
                     : build::box(1, 2, 3);
  // Cut every curved edge at a random place on it: arcs, not only full circles.
  for (EdgeH e : b.edges()) {
    const geo::Curve& c = b.curve(e);
    if (std::holds_alternative<geo::Line>(c) || std::holds_alternative<std::monostate>(c)) continue;
    const double at = double(*rc::gen::inRange(1, 1000)) / 1000.0;
    const HalfedgeH h = halfedge_of(e, 0);
    const std::vector<geo::Vec3> poly = halfedge_polyline(b, h, 1e-3);
    const geo::Vec3 p = geo::closest_point(c, poly[std::size_t(at * double(poly.size() - 1))]).point;
    if (!euler::semv(b, h, p)) RC_FAIL("semv refused");
  }
  Eigen::Quaterniond q(double(*rc::gen::inRange(-100, 101)), double(*rc::gen::inRange(-100, 101)),
                       double(*rc::gen::inRange(-100, 101)), double(*rc::gen::inRange(-100, 101)));
  RC_PRE(q.norm() > 1.0);
  q.normalize();
  geo::Similarity s;
  s.rotation = q.toRotationMatrix();
  s.scale = *rc::gen::element(0.01, 1.0, 300.0);
  s.translation = geo::Vec3(*rc::gen::inRange(-500, 500), *rc::gen::inRange(-500, 500), 7.0);
  for (VertexH v : b.vertices()) b.set_point(v, s.point(b.point(v)));
  for (EdgeH e : b.edges()) b.set_curve(e, geo::transformed(b.curve(e), s));
  for (FaceH f : b.faces()) b.set_surface(f, geo::transformed(b.surface(f), s), b.same_sense(f));
  const double chordal = *rc::gen::element(1e-4, 1e-2, 0.3) * s.scale;
  for (EdgeH e : b.edges())
    for (unsigned k = 0; k < 2; ++k) {
      const HalfedgeH h = halfedge_of(e, k);
      const geo::Box box = halfedge_box(b, h, chordal);
      for (const geo::Vec3& p : halfedge_polyline(b, h, chordal))
        RC_ASSERT(box.contains(p, 1e-12 * s.scale));
    }
}

}  // namespace
}  // namespace kintsugi
