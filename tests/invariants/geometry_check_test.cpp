#include "invariants/element_geometry.h"
#include "invariants/geometry_check.h"
#include "kernel/builders.h"
#include "kernel/euler.h"
#include "tests/invariants/spec_codes.h"

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <functional>
#include <set>

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

// ---- every violation code, alone -----------------------------------------------------
//
// For each code of check_geometry (spec/invariants.md, "Geometric consistency"), a valid
// body with exactly that invariant broken: the report names it, and only it.

namespace kintsugi {
namespace {

// An edge of f with both of its faces planar and different (a box edge).
EdgeH edge_between_two_faces(const Body& b) {
  for (EdgeH e : b.edges())
    if (b.face(halfedge_of(e, 0)) != b.face(halfedge_of(e, 1))) return e;
  return EdgeH{};
}

struct GeometryCase {
  std::string name;
  std::string code;
  std::function<Body()> make;
  std::function<void(Body&)> breaks;
};

void PrintTo(const GeometryCase& c, std::ostream* os) { *os << c.name; }

std::vector<GeometryCase> geometry_cases() {
  const double p = kPrecision;
  return {
      {"FaceWithoutSurface", "face_without_surface", [] { return build::box(); },
       [](Body& b) { b.set_surface(b.faces()[0], geo::Surface{}); }},
      {"EdgeWithoutCurve", "edge_without_curve", [] { return build::box(); },
       [](Body& b) { b.set_curve(b.edges()[0], geo::Curve{}); }},
      {"VertexOnCurveLineMovedSideways", "vertex_on_curve", [] { return build::box(); },
       [p](Body& b) {
         // The line moves off its vertices; the edge's probes are on the chord between
         // the vertices, which stays on both faces.
         EdgeH e = edge_between_two_faces(b);
         geo::Line l = std::get<geo::Line>(b.curve(e));
         geo::Vec3 side = l.direction.unitOrthogonal();
         l.origin += 10 * p * side;
         b.set_curve(e, l);
       }},
      {"VertexOnSurfaceLoneVertexAbovePlane", "vertex_on_surface",
       [] {
         Body b;
         auto m = euler::mvfs(b, geo::Vec3(1, 2, 0));
         b.set_surface(m->face, geo::Plane{});
         return b;
       },
       [p](Body& b) { b.set_point(b.vertices()[0], geo::Vec3(1, 2, 10 * p)); }},
      {"EdgeOnSurfaceArcBulgesOutOfOneFace", "edge_on_surface", [] { return build::box(); },
       [](Body& b) {
         // A flat arc through the edge's two vertices, in the plane of one face: on that
         // face's surface, 1e-4 off the other face's, and through both vertices.
         EdgeH e = edge_between_two_faces(b);
         HalfedgeH h = halfedge_of(e, 0);
         const geo::Vec3 p0 = b.point(b.origin(h)), p1 = b.point(b.target(h));
         const geo::Vec3 n = std::get<geo::Plane>(b.surface(b.face(h))).frame.z.normalized();
         const geo::Vec3 along = (p1 - p0).normalized(), across = n.cross(along);
         const double half = (p1 - p0).norm() / 2, sag = 1e-4, r = (half * half + sag * sag) / (2 * sag);
         const geo::Vec3 centre = (p0 + p1) / 2 - (r - sag) * across;
         geo::Circle c;
         c.frame.origin = centre;
         c.frame.x = (p0 - centre).normalized();
         c.frame.z = (p0 - centre).cross(p1 - centre).normalized();  // p0 to p1 the short way
         c.radius = r;
         b.set_curve(e, c);
       }},
      {"FaceSenseFlipped", "face_sense", [] { return build::box(); },
       [](Body& b) {
         FaceH f = b.faces()[0];
         b.set_surface(f, b.surface(f), !b.same_sense(f));
       }},
  };
}

class BrokenGeometry : public ::testing::TestWithParam<GeometryCase> {};

TEST_P(BrokenGeometry, IsNamedAndNothingElseIs) {
  const GeometryCase& c = GetParam();
  Body b = c.make();
  GeometryReport before = check_geometry(b, kPrecision);
  for (const Violation& v : before.violations) ADD_FAILURE() << c.name << ": before the edit: " << to_string(v);
  c.breaks(b);
  GeometryReport r = check_geometry(b, kPrecision);
  ASSERT_FALSE(r.violations.empty()) << c.name << ": the broken " << c.code << " went unnoticed";
  for (const Violation& v : r.violations) EXPECT_EQ(v.invariant, c.code) << c.name << ": " << to_string(v);
}

INSTANTIATE_TEST_SUITE_P(Geometry, BrokenGeometry, ::testing::ValuesIn(geometry_cases()),
                         [](const auto& info) { return info.param.name; });

// Every code in the spec's geometric table has a case above.
TEST(GeometryCheck, EverySpecCodeHasABreakingCase) {
  std::set<std::string> have;
  for (const GeometryCase& c : geometry_cases()) have.insert(c.code);
  std::set<std::string> spec = test::spec_codes(KINTSUGI_SPEC_DIR "/invariants.md", "## Geometric consistency", "");
  EXPECT_FALSE(spec.empty());
  for (const std::string& code : spec) EXPECT_TRUE(have.count(code)) << code << " has no case that breaks it alone";
  for (const std::string& code : have) EXPECT_TRUE(spec.count(code)) << code << " is not in spec/invariants.md";
}

// A large body is checked in blocks on several threads (check_geometry's `threads`): the
// same report as one thread — every violation, in the same order, and the same largest
// deviation at the same elements, also when several elements in different blocks share
// it exactly (the first one is named).
TEST(GeometryCheck, CheckOnTwoThreadsIsTheSame) {
  Body b = build::grid_box(30000);
  ASSERT_GE(b.edges().size(), 4096u);  // above the size where threads start
  const std::vector<VertexH> vs = b.vertices();
  // Vertices lifted off their faces by amounts that repeat, spread over the body; the
  // largest amount appears three times, in different blocks.
  for (std::size_t i = 0; i < vs.size(); i += 97) {
    const double by = (i % 5 == 0 ? 4.0 : double(1 + i % 3)) * 1e-4;
    b.set_point(vs[i], b.point(vs[i]) + geo::Vec3(by, -by, by));
  }
  auto listing = [](const GeometryReport& r) {
    std::string s;
    char buf[64];
    for (const Violation& v : r.violations) {
      std::snprintf(buf, sizeof buf, " %a\n", v.distance);
      s += to_string(v) + buf;
    }
    std::snprintf(buf, sizeof buf, "max %a at", r.max_deviation);
    s += buf;
    for (const std::string& e : r.max_elements) s += " " + e;
    return s;
  };
  const std::string one = listing(check_geometry(b, kPrecision, 1));
  EXPECT_GT(check_geometry(b, kPrecision, 1).violations.size(), 100u);
  EXPECT_EQ(listing(check_geometry(b, kPrecision, 2)), one);
  EXPECT_EQ(listing(check_geometry(b, kPrecision, 3)), one);
}

}  // namespace
}  // namespace kintsugi
