// The paper's test objects (zoo::paper_object, docs/paper-objects.md), defective and
// clean, exported to STEP and BREP and read back: equal to the original (counts,
// adjacency, geometry within modelling precision) and valid for BRepCheck_Analyzer.
// Defective objects have gaps (border cycles): they are open shells and are written as
// shells, not solids. Also the bosses of object 10 on their own: a spherical dome (a
// sphere face bounded by one circle and a seam arc from the circle's vertex to the
// pole) and a conical frustum (a cone face with a straight seam and a flat top disc).
#include "invariants/geometry_check.h"
#include "invariants/topology_check.h"
#include "io/occt/exchange.h"
#include "kernel/builders.h"
#include "tests/occt/compare.h"
#include "zoo/local_ops.h"
#include "zoo/zoo.h"

#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <stdexcept>

namespace kintsugi {
namespace {

using io::CadFormat;
using geo::Vec3;

std::string problems(const io::OcctVerdict& v) {
  std::string s;
  for (const std::string& p : v.problems) s += "\n  " + p;
  return s;
}

std::string str(const Counts& c) {
  return "V " + std::to_string(c.vertices) + " E " + std::to_string(c.edges) + " F " + std::to_string(c.faces) +
         " L " + std::to_string(c.loops) + " S " + std::to_string(c.shells) + " B " + std::to_string(c.border_cycles);
}

// Exports, reads back, and checks the copy against the original both ways, our topology
// check on the copy, and BRepCheck on both.
void expect_round_trips(const Body& b, const std::string& name) {
  io::OcctVerdict v = io::occt_check(b);
  EXPECT_TRUE(v.valid) << name << problems(v);
  for (CadFormat f : {CadFormat::step, CadFormat::brep}) {
    std::string what = name + (f == CadFormat::step ? " (STEP)" : " (BREP)");
    Body r = test::round_trip(b, f, name);
    EXPECT_EQ(test::compare_bodies(b, r), "") << what;
    EXPECT_EQ(test::compare_bodies(r, b), "") << what;
    for (const Violation& x : check_topology(r)) ADD_FAILURE() << what << ": " << to_string(x);
    io::OcctVerdict v2 = io::occt_check(r);
    EXPECT_TRUE(v2.valid) << what << " after the round trip" << problems(v2);
  }
}

class PaperObjectRoundTrip : public ::testing::TestWithParam<std::tuple<int, bool>> {};

TEST_P(PaperObjectRoundTrip, EqualsTheOriginalAndPassesBRepCheck) {
  auto [n, clean] = GetParam();
  zoo::ZooModel m;
  try {
    m = zoo::paper_object(n, clean);
  } catch (const std::exception& e) {
    FAIL() << "paper object " << n << " could not be built: " << e.what();  // every object 1-10 builds
  }
  const Body& b = m.body;
  // The zoo promises a valid body; a gap is a border cycle (an open shell).
  for (const Violation& x : check_topology(b)) ADD_FAILURE() << m.source << ": " << to_string(x);
  if (clean) {
    EXPECT_EQ(b.counts().border_cycles, 0u) << m.source;
  }
  expect_round_trips(b, "paper_object_" + std::to_string(n) + (clean ? "_clean" : "_defective"));
}

INSTANTIATE_TEST_SUITE_P(All, PaperObjectRoundTrip, ::testing::Combine(::testing::Range(1, 11), ::testing::Bool()),
                         [](const auto& info) {
                           return "object_" + std::to_string(std::get<0>(info.param)) +
                                  (std::get<1>(info.param) ? "_clean" : "_defective");
                         });

// ---- object 10's bosses on their own ---------------------------------------------------

FaceH top_face(const Body& b) {
  for (FaceH f : b.faces())
    if (const auto* p = std::get_if<geo::Plane>(&b.surface(f)); p && zoo::outward_normal(b, f).z() > 0.5) return f;
  return FaceH{};
}

// A 20 x 10 x 4 box with, on its top face, a spherical dome (base radius 3, 1.5 tall)
// centred at (5, 5) and a conical frustum (radius 3 to 1.5, 2 tall) centred at (15, 5),
// built as paper object 10 builds them.
//   box                              8 V  12 E  6 F   6 L
//   disc on the top face (strut, kemr, mef on the lone vertex): +1 V, +1 E, +1 F, +2 L
//     (a ring in the top face and the disc's loop), once per boss
//   dome: the seam from the circle's vertex to the pole (mev): +1 V, +1 E
//   frustum: the seam (mev) and the top circle cutting off the top disc (mef): +1 V,
//     +2 E, +1 F, +1 L
//   total                           12 V  17 E  9 F  11 L;  12 − 17 + 9 − 2 rings = 2.
Body bosses() {
  Body b = build::box(20, 10, 4);
  b.clear_journal();
  FaceH disc = zoo::add_circle_face(b, top_face(b), Vec3(5, 5, 4), 3);
  zoo::raise_dome(b, disc, Vec3(5, 5, 4), 3, 1.5);
  disc = zoo::add_circle_face(b, top_face(b), Vec3(15, 5, 4), 3);
  zoo::raise_cone(b, disc, Vec3(15, 5, 4), 3, 1.5, 2);
  b.clear_journal();
  return b;
}

Counts boss_counts() {
  Counts c;
  c.vertices = 12;
  c.edges = 17;
  c.faces = 9;
  c.loops = 11;
  c.shells = 1;
  return c;
}

// The sphere face of b: one loop [circle, seam up, seam down]; the pole is the seam's
// end with no other edge.
void expect_dome_structure(const Body& b, const std::string& what) {
  int spheres = 0;
  for (FaceH f : b.faces()) {
    if (!std::holds_alternative<geo::Sphere>(b.surface(f))) continue;
    ++spheres;
    std::vector<LoopH> ls = b.loops_of(f);
    ASSERT_EQ(ls.size(), 1u) << what;
    std::vector<HalfedgeH> hs = b.loop_halfedges(ls[0]);
    ASSERT_EQ(hs.size(), 3u) << what;
    int seam_sides = 0, poles = 0;
    for (HalfedgeH h : hs) {
      bool seam = b.loop(twin(h)) == ls[0];
      seam_sides += seam ? 1 : 0;
      if (seam && std::holds_alternative<geo::Circle>(b.curve(edge_of(h)))) {
        // The seam is a meridian arc; its upper end is the pole, a vertex of degree 1.
        VertexH v = b.degree(b.origin(h)) == 1 ? b.origin(h) : b.target(h);
        poles += b.degree(v) == 1 ? 1 : 0;
      }
    }
    EXPECT_EQ(seam_sides, 2) << what << ": both sides of the seam are in the sphere face's loop";
    EXPECT_EQ(poles, 2) << what << ": the seam ends at the pole, which has no other edge";
  }
  EXPECT_EQ(spheres, 1) << what;
}

TEST(PaperBosses, DomeAndFrustumAreConsistentAndRoundTrip) {
  Body b = bosses();
  EXPECT_EQ(str(b.counts()), str(boss_counts()));
  for (const Violation& x : check_topology(b)) ADD_FAILURE() << to_string(x);
  for (const Violation& x : check_geometry(b, 1e-9).violations) ADD_FAILURE() << to_string(x);
  expect_dome_structure(b, "built");
  expect_round_trips(b, "bosses");
  for (CadFormat f : {CadFormat::step, CadFormat::brep}) {
    Body r = test::round_trip(b, f, "bosses_structure");
    expect_dome_structure(r, f == CadFormat::step ? "read back from STEP" : "read back from BREP");
    for (const Violation& x : check_geometry(r, 1e-9).violations) ADD_FAILURE() << to_string(x);
  }
}

TEST(PaperBosses, OpenCascadeSeesOnePoleEdgeAndOurTopologyOtherwise) {
  // Read the BREP we write with OpenCASCADE alone: every vertex, edge, face and loop is
  // ours one to one, plus the degenerated edge OpenCASCADE needs at the sphere's pole
  // (the frustum has no apex, so none there).
  Body b = bosses();
  std::string path = test::temp_path("bosses_occt.brep"), err;
  ASSERT_TRUE(io::export_cad(b, path, CadFormat::brep, &err)) << err;
  TopoDS_Shape s;
  BRep_Builder bb;
  ASSERT_TRUE(BRepTools::Read(s, path.c_str(), bb));
  TopTools_IndexedMapOfShape v, e, f, w;
  TopExp::MapShapes(s, TopAbs_VERTEX, v);
  TopExp::MapShapes(s, TopAbs_EDGE, e);
  TopExp::MapShapes(s, TopAbs_FACE, f);
  TopExp::MapShapes(s, TopAbs_WIRE, w);
  int degenerated = 0;
  for (int i = 1; i <= e.Extent(); ++i) degenerated += BRep_Tool::Degenerated(TopoDS::Edge(e(i))) ? 1 : 0;
  Counts c = boss_counts();
  EXPECT_EQ(degenerated, 1);
  EXPECT_EQ(std::size_t(v.Extent()), c.vertices);
  EXPECT_EQ(std::size_t(e.Extent() - degenerated), c.edges);
  EXPECT_EQ(std::size_t(f.Extent()), c.faces);
  EXPECT_EQ(std::size_t(w.Extent()), c.loops);
}

TEST(PaperBosses, RoundTripUnderRigidMotions) {
  // Off the axes: the seams, the pole and the cone's axis in general position.
  const Eigen::Vector3d axes[] = {Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(-0.3, 1, 0.1), Eigen::Vector3d(0, 0, 1)};
  const double angles[] = {0.7, 2.9, -1.2};
  for (int i = 0; i < 3; ++i) {
    Body b = bosses();
    Eigen::Matrix3d r = Eigen::AngleAxisd(angles[i], axes[i].normalized()).toRotationMatrix();
    test::transform(b, r, Eigen::Vector3d(3.5 * i - 2, 11.0 * i, -7.25));
    for (const Violation& x : check_geometry(b, 1e-9).violations)
      ADD_FAILURE() << "motion " << i << ": " << to_string(x);
    expect_round_trips(b, "bosses_moved_" + std::to_string(i));
  }
}

TEST(PaperBosses, ADomeOnTheUnderside) {
  // The dome pointing down (the sphere's z along −z of the world), on the bottom face.
  Body b = build::box(10, 10, 4);
  b.clear_journal();
  FaceH bottom;
  for (FaceH f : b.faces())
    if (std::holds_alternative<geo::Plane>(b.surface(f)) && zoo::outward_normal(b, f).z() < -0.5) bottom = f;
  ASSERT_TRUE(bottom.valid());
  FaceH disc = zoo::add_circle_face(b, bottom, Vec3(5, 5, 0), 4);
  zoo::raise_dome(b, disc, Vec3(5, 5, 0), 4, 3.5);
  b.clear_journal();
  for (const Violation& x : check_topology(b)) ADD_FAILURE() << to_string(x);
  for (const Violation& x : check_geometry(b, 1e-9).violations) ADD_FAILURE() << to_string(x);
  expect_dome_structure(b, "built");
  expect_round_trips(b, "underside_dome");
}

}  // namespace
}  // namespace kintsugi
