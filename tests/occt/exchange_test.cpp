// Round trips of every builder solid through STEP and BREP, and OpenCASCADE's own
// validity check on our bodies.
#include "invariants/topology_check.h"
#include "io/occt/exchange.h"
#include "invariants/assemble.h"
#include "kernel/builders.h"
#include "kernel/euler.h"
#include "tests/occt/compare.h"

#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <sstream>

namespace kintsugi {
namespace {

using io::CadFormat;

struct Named {
  std::string name;
  std::function<Body()> make;
};

std::vector<Named> builder_solids() {
  return {
      {"box", [] { return build::box(1, 2, 3); }},
      {"hexagonal_prism", [] { return build::prism(build::regular_polygon(6, 1.5), 2.0); }},
      {"l_prism", [] {
         return build::prism({{0, 0}, {3, 0}, {3, 1}, {1, 1}, {1, 2}, {0, 2}}, 0.5);
       }},
      {"square_pyramid", [] { return build::pyramid(build::regular_polygon(4, 1.0), 1.0); }},
      {"cylinder", [] { return build::cylinder(1.5, 4.0); }},
      {"cone", [] { return build::cone(2.0, 3.0); }},
      {"sphere", [] { return build::sphere(2.5); }},
      {"torus", [] { return build::torus(3.0, 1.0); }},
  };
}

std::string problems(const io::OcctVerdict& v) {
  std::string s;
  for (const std::string& p : v.problems) s += "\n  " + p;
  return s;
}

void expect_valid_topology(const Body& b) {
  for (const Violation& v : check_topology(b)) ADD_FAILURE() << to_string(v);
}

class BuilderRoundTrip : public ::testing::TestWithParam<std::tuple<int, CadFormat>> {};

TEST_P(BuilderRoundTrip, CountsAdjacencyAndGeometrySurvive) {
  auto [i, f] = GetParam();
  Named n = builder_solids()[std::size_t(i)];
  Body b = n.make();
  io::OcctVerdict v = io::occt_check(b);
  EXPECT_TRUE(v.valid) << n.name << problems(v);
  Body r = test::round_trip(b, f, n.name);
  expect_valid_topology(r);
  EXPECT_EQ(test::compare_bodies(b, r), "") << n.name;
  EXPECT_EQ(test::compare_bodies(r, b), "") << n.name;
  io::OcctVerdict v2 = io::occt_check(r);
  EXPECT_TRUE(v2.valid) << n.name << " after the round trip" << problems(v2);
}

INSTANTIATE_TEST_SUITE_P(All, BuilderRoundTrip,
                         ::testing::Combine(::testing::Range(0, 8), ::testing::Values(CadFormat::step, CadFormat::brep)),
                         [](const auto& info) {
                           return builder_solids()[std::size_t(std::get<0>(info.param))].name +
                                  (std::get<1>(info.param) == CadFormat::step ? "_step" : "_brep");
                         });

Body open_box() {
  Body b = build::box(2, 2, 1);
  FaceH top;
  for (FaceH f : b.faces())
    if (const auto* p = std::get_if<geo::Plane>(&b.surface(f)); p && p->frame.z.z() > 0.5) top = f;
  EXPECT_TRUE(euler::kfmb(b, top));
  b.clear_journal();
  return b;
}

TEST(OpenShell, BoxWithoutItsTopRoundTripsWithOneBorderCycle) {
  Body b = open_box();
  ASSERT_EQ(b.counts().border_cycles, 1u);
  io::OcctVerdict v = io::occt_check(b);
  EXPECT_TRUE(v.valid) << problems(v);
  for (CadFormat f : {CadFormat::step, CadFormat::brep}) {
    Body r = test::round_trip(b, f, "open_box");
    expect_valid_topology(r);
    EXPECT_EQ(r.counts().shells, 1u);
    EXPECT_EQ(r.counts().border_cycles, 1u);
    EXPECT_EQ(r.counts().faces, 5u);
    EXPECT_EQ(test::compare_bodies(b, r), "");
  }
}

TEST(OpenShell, AStepFileOfAnOpenShellHoldsAShellNotASolid) {
  std::string path = test::temp_path("open_box_kind.step");
  std::string err;
  ASSERT_TRUE(io::export_cad(open_box(), path, CadFormat::step, &err)) << err;
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_EQ(ss.str().find("MANIFOLD_SOLID_BREP"), std::string::npos);
  EXPECT_NE(ss.str().find("SHELL"), std::string::npos);
}

// Two bodies side by side as one body of two shells (describe both, renumber the
// second after the first, assemble).
Body two_shells(const Body& a, const Body& c) {
  BodyDescription da = describe(a), dc = describe(c);
  const auto v = std::uint32_t(da.vertices.size()), e = std::uint32_t(da.edges.size()),
             l = std::uint32_t(da.loops.size()), f = std::uint32_t(da.faces.size()),
             s = std::uint32_t(da.shells.size());
  for (auto& x : dc.vertices) x.id += v;
  for (auto& x : dc.edges) {
    x.id += e;
    for (auto& h : x.he) h = {h.origin + v, h.next + 2 * e, h.loop + l};
  }
  for (auto& x : dc.loops) {
    x.id += l;
    if (x.face) *x.face += f;
    if (x.first) *x.first += 2 * e;
    if (x.lone) *x.lone += v;
  }
  for (auto& x : dc.faces) {
    x.id += f;
    x.shell += s;
    for (auto& l2 : x.loops) l2 += l;
  }
  for (auto& x : dc.shells) x.id += s;
  for (auto& x : dc.vertices) da.vertices.push_back(x);
  for (auto& x : dc.edges) da.edges.push_back(x);
  for (auto& x : dc.loops) da.loops.push_back(x);
  for (auto& x : dc.faces) da.faces.push_back(x);
  for (auto& x : dc.shells) da.shells.push_back(x);
  AssembleError ae;
  std::optional<Body> both = assemble(da, &ae);
  EXPECT_TRUE(both) << ae.element << ": " << ae.message;
  return both ? std::move(*both) : Body{};
}

TEST(TwoShells, TwoSolidsRoundTripAsTwoShells) {
  Body a = build::box(1, 1, 1), c = build::cylinder(0.5, 1);
  test::transform(c, Eigen::Matrix3d::Identity(), Eigen::Vector3d(5, 0, 0));
  Body both = two_shells(a, c);
  ASSERT_EQ(both.counts().shells, 2u);
  EXPECT_TRUE(io::occt_check(both).valid);
  for (CadFormat f : {CadFormat::step, CadFormat::brep}) {
    Body r = test::round_trip(both, f, "two_shells");
    EXPECT_EQ(r.counts().shells, 2u);
    EXPECT_EQ(test::compare_bodies(both, r), "");
  }
}

TEST(TwoShells, TouchingSolidsKeepTheirOwnVerticesAndFaces) {
  // Two unit boxes sharing the square x = 1 (as solids that touch in an assembly): four
  // pairs of coincident vertices, the two faces at x = 1 on one plane facing opposite
  // ways, and four pairs of coplanar faces facing the same way (y = 0, y = 1, z = 0,
  // z = 1). Each shell keeps its own elements; the comparison pairs them by shell.
  Body a = build::box(1, 1, 1), c = build::box(1, 1, 1);
  test::transform(c, Eigen::Matrix3d::Identity(), Eigen::Vector3d(1, 0, 0));
  Body both = two_shells(a, c);
  ASSERT_EQ(both.counts().shells, 2u);
  io::OcctVerdict v = io::occt_check(both);
  EXPECT_TRUE(v.valid) << problems(v);
  for (CadFormat f : {CadFormat::step, CadFormat::brep}) {
    Body r = test::round_trip(both, f, "touching_boxes");
    expect_valid_topology(r);
    EXPECT_EQ(r.counts().shells, 2u);
    EXPECT_EQ(r.counts().vertices, 16u);
    EXPECT_EQ(test::compare_bodies(both, r), "");
    EXPECT_EQ(test::compare_bodies(r, both), "");
  }
}

TEST(Compare, SeesAnArcTakenTheOtherWayRound) {
  // The sphere's seam turned to the other half of its circle: the same end points (the
  // poles), the same circle, the same faces, but a different edge.
  Body b = build::sphere(2.0), c = build::sphere(2.0);
  EdgeH e = c.edges()[0];
  geo::Circle ci = std::get<geo::Circle>(c.curve(e));
  ci.frame.z = -ci.frame.z;
  c.set_curve(e, ci);
  EXPECT_NE(test::compare_bodies(b, c), "");
  EXPECT_NE(test::compare_bodies(c, b), "");
  EXPECT_EQ(test::compare_bodies(b, b), "");
}

TEST(WholeSphere, KeepsItsSeamThroughStep) {
  // OpenCASCADE writes a whole sphere (a face bounded by its seam only) to STEP as a
  // face with a vertex loop, and its reader puts the seam back at u = 0. Our seam is on
  // some other meridian: it must come back there, for every meridian.
  for (double turn : {0.0, 1.0, 2.5, M_PI, 4.0}) {
    Body b = build::sphere(1.5);
    Eigen::Matrix3d r = Eigen::AngleAxisd(turn, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    EdgeH e = b.edges()[0];
    geo::Circle ci = std::get<geo::Circle>(b.curve(e));
    ci.frame.x = r * ci.frame.x;
    ci.frame.z = r * ci.frame.z;
    b.set_curve(e, ci);
    b.clear_journal();
    Body s = test::round_trip(b, CadFormat::step, "whole_sphere");
    EXPECT_EQ(test::compare_bodies(b, s), "") << "turn " << turn;
    EXPECT_EQ(test::compare_bodies(s, b), "") << "turn " << turn;
  }
}

TEST(OcctCheck, FlaggsAFaceTurnedInsideOut) {
  // A box with one face's sense flipped: its wire now runs the wrong way round for
  // OpenCASCADE, and the shell is no longer orientable consistently.
  Body b = build::box(1, 1, 1);
  FaceH f = b.faces()[0];
  b.set_surface(f, b.surface(f), !b.same_sense(f));
  io::OcctVerdict v = io::occt_check(b);
  EXPECT_FALSE(v.valid);
  EXPECT_FALSE(v.problems.empty());
}

TEST(OcctCheck, FlagsGeometryThatMissesTheVertices) {
  // A face plane moved away from its vertices: the edges are not on the face.
  Body b = build::box(1, 1, 1);
  FaceH f = b.faces()[0];
  geo::Plane p = std::get<geo::Plane>(b.surface(f));
  p.frame.origin += 0.2 * p.frame.z;
  b.set_surface(f, p, b.same_sense(f));
  io::OcctVerdict v = io::occt_check(b);
  EXPECT_FALSE(v.valid);
  ASSERT_FALSE(v.problems.empty());
}

TEST(OcctCheck, RefusesABodyWithoutGeometry) {
  Body b = build::box(1, 1, 1);
  b.set_surface(b.faces()[2], std::monostate{});
  io::OcctVerdict v = io::occt_check(b);
  EXPECT_FALSE(v.valid);
  ASSERT_EQ(v.problems.size(), 1u);
  EXPECT_NE(v.problems[0].find("face f2: no surface"), std::string::npos) << v.problems[0];
}

TEST(Units, InchesAreDeclaredAndNotScaled) {
  Body b = build::box(1, 2, 3);
  std::string path = test::temp_path("box_in.step");
  std::string err;
  ASSERT_TRUE(io::export_cad(b, path, CadFormat::step, &err, "in")) << err;
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_NE(ss.str().find("INCH"), std::string::npos);
  std::optional<io::CadImport> r = io::import_cad(path, CadFormat::step, &err);
  ASSERT_TRUE(r) << err;
  EXPECT_EQ(r->units, "in");
  EXPECT_DOUBLE_EQ(r->unit_in_mm, 25.4);
  EXPECT_EQ(test::compare_bodies(b, r->body), "");
}

TEST(Units, MetresAndMillimetres) {
  for (const char* u : {"m", "mm", "cm"}) {
    Body b = build::cylinder(0.25, 0.5);
    std::string path = test::temp_path(std::string("cyl_") + u + ".step");
    std::string err;
    ASSERT_TRUE(io::export_cad(b, path, CadFormat::step, &err, u)) << err;
    std::optional<io::CadImport> r = io::import_cad(path, CadFormat::step, &err);
    ASSERT_TRUE(r) << err;
    EXPECT_EQ(r->units, u);
    EXPECT_EQ(test::compare_bodies(b, r->body), "") << u;
  }
}

TEST(Units, UnknownUnitIsRefused) {
  std::string err;
  EXPECT_FALSE(io::export_cad(build::box(), test::temp_path("x.step"), CadFormat::step, &err, "furlong"));
  EXPECT_NE(err.find("furlong"), std::string::npos) << err;
}

TEST(Export, UnwritablePathFailsWithAMessage) {
  std::string err;
  EXPECT_FALSE(io::export_cad(build::box(), "/nonexistent-dir/x.brep", CadFormat::brep, &err));
  EXPECT_NE(err.find("/nonexistent-dir/x.brep"), std::string::npos) << err;
}

}  // namespace
}  // namespace kintsugi
