// STEP files written by other systems (tests/data/step/README.md: sources and licences)
// import with the expected topology and survive a round trip.
//
// Expected counts are derived from the files themselves (their entity counts, worked
// out in the comments) and cross-checked against OpenCASCADE's own reading of the file
// (TopExp maps of the shape STEPControl_Reader gives), never taken from our importer.
#include "geometry/curve.h"
#include "invariants/geometry_check.h"
#include "invariants/topology_check.h"
#include "io/occt/exchange.h"
#include "tests/occt/compare.h"

#include <BRep_Tool.hxx>
#include <STEPControl_Reader.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace kintsugi {
namespace {

using io::CadFormat;

const std::string kDir = std::string(KINTSUGI_TEST_DATA_DIR) + "/step/";

std::string problems(const io::OcctVerdict& v) {
  std::string s;
  for (const std::string& p : v.problems) s += "\n  " + p;
  return s;
}

using test::counts;

// OpenCASCADE's own reading of the file, without kintsugi: vertices, edges (less the
// degenerated ones, which kintsugi does not keep), faces, wires and shells of the shape
// STEPControl_Reader transfers. For closed shells without lone vertices these are our
// vertex, edge, face, loop and shell counts.
Counts occt_counts(const std::string& path) {
  STEPControl_Reader reader;
  EXPECT_EQ(reader.ReadFile(path.c_str()), IFSelect_RetDone) << path;
  reader.TransferRoots();
  TopoDS_Shape s = reader.OneShape();
  TopTools_IndexedMapOfShape v, e, f, w, sh;
  TopExp::MapShapes(s, TopAbs_VERTEX, v);
  TopExp::MapShapes(s, TopAbs_EDGE, e);
  TopExp::MapShapes(s, TopAbs_FACE, f);
  TopExp::MapShapes(s, TopAbs_WIRE, w);
  TopExp::MapShapes(s, TopAbs_SHELL, sh);
  std::size_t degenerated = 0;
  for (int i = 1; i <= e.Extent(); ++i) degenerated += BRep_Tool::Degenerated(TopoDS::Edge(e(i))) ? 1 : 0;
  return counts(std::size_t(v.Extent()), std::size_t(e.Extent()) - degenerated, std::size_t(f.Extent()),
                std::size_t(w.Extent()), std::size_t(sh.Extent()));
}

std::string str(const Counts& c) {
  return "V " + std::to_string(c.vertices) + " E " + std::to_string(c.edges) + " F " + std::to_string(c.faces) +
         " L " + std::to_string(c.loops) + " S " + std::to_string(c.shells) + " B " + std::to_string(c.border_cycles);
}

int warnings_with(const io::CadImport& in, const std::string& text) {
  int n = 0;
  for (const std::string& w : in.warnings) n += w.find(text) != std::string::npos ? 1 : 0;
  return n;
}

std::map<std::string, int> surface_types(const Body& b) {
  std::map<std::string, int> n;
  for (FaceH f : b.faces()) n[geo::surface_type_name(b.surface(f))]++;
  return n;
}

// Imports the file and checks what every third-party part must satisfy: the expected
// counts (also OpenCASCADE's), the unit, our topology and geometry checks, BRepCheck,
// and the STEP and BREP round trips, compared both ways.
io::CadImport import_part(const std::string& file, const Counts& expect, const std::string& units, double unit_in_mm) {
  std::string err;
  std::optional<io::CadImport> in = io::import_cad(kDir + file, CadFormat::step, &err);
  if (!in) {
    ADD_FAILURE() << err;
    return io::CadImport{};
  }
  EXPECT_EQ(in->units, units) << file;
  EXPECT_DOUBLE_EQ(in->unit_in_mm, unit_in_mm) << file;
  const Body& b = in->body;
  EXPECT_EQ(str(b.counts()), str(expect)) << file;
  EXPECT_EQ(str(occt_counts(kDir + file)), str(expect)) << file << ": OpenCASCADE's own count";
  for (const Violation& v : check_topology(b)) ADD_FAILURE() << file << ": " << to_string(v);
  // Every face of these parts is analytic, so every edge is a parameter line of one of
  // its faces (or was written as a line, circle or ellipse): none is approximated.
  for (EdgeH e : b.edges())
    EXPECT_FALSE(std::holds_alternative<geo::Polyline>(b.curve(e))) << file << ": " << e.str() << " is a polyline";
  GeometryReport g = check_geometry(b, 1e-7);
  for (const Violation& v : g.violations) ADD_FAILURE() << file << ": " << to_string(v);
  io::OcctVerdict v = io::occt_check(b);
  EXPECT_TRUE(v.valid) << file << problems(v);
  for (CadFormat f : {CadFormat::step, CadFormat::brep}) {
    const char* fmt = f == CadFormat::step ? " (STEP)" : " (BREP)";
    Body r = test::round_trip(b, f, file);
    EXPECT_EQ(test::compare_bodies(b, r), "") << file << fmt;
    EXPECT_EQ(test::compare_bodies(r, b), "") << file << fmt;
    for (const Violation& x : check_topology(r)) ADD_FAILURE() << file << fmt << ": " << to_string(x);
    io::OcctVerdict v2 = io::occt_check(r);
    EXPECT_TRUE(v2.valid) << file << fmt << problems(v2);
  }
  return std::move(*in);
}

TEST(ThirdParty, RedCubeBlueCylinder) {
  // Cube: 8 V, 12 E, 6 F. The cylinder's side is seamless in the file (two circles, an
  // annulus), but OpenCASCADE's STEP reader runs ShapeFix, whose FixMissingSeam adds a
  // seam edge: 2 V, 3 E, 3 F, one loop per face, as OpenCASCADE's own cylinders. The
  // seam's 3D curve is a B-spline; it runs along the cylinder's axis, so it is a line.
  io::CadImport in = import_part("red_cube_blue_cylinder.step", counts(10, 15, 9, 9, 2), "m", 1000.0);
  const Body& b = in.body;
  EXPECT_EQ(warnings_with(in, "recognised as a line (a parameter line of its face)"), 1);
  int cylinders = 0;
  for (FaceH f : b.faces())
    if (const auto* cyl = std::get_if<geo::Cylinder>(&b.surface(f))) {
      ++cylinders;
      EXPECT_NEAR(cyl->radius, 0.005, 1e-12) << "geometry stays in the file's unit (metres)";
      EXPECT_TRUE(b.same_sense(f));
    }
  EXPECT_EQ(cylinders, 1);
}

// trimesh's base_interface part, written by SolidWorks 2018 in inches, once as AP203
// (CONFIG_CONTROL_DESIGN) and once as AP214 (AUTOMOTIVE_DESIGN). Each file has 56
// VERTEX_POINTs, 84 EDGE_CURVEs, 30 ADVANCED_FACEs (8 PLANEs, 22 CYLINDRICAL_SURFACEs,
// every periodic face with its seam already written), 30 FACE_OUTER_BOUNDs and 10
// FACE_BOUNDs (40 loops), one CLOSED_SHELL. Euler–Poincaré: 56 − 84 + 30 − 10 rings =
// −8 = 2(1 − g), genus 5: five through holes, each a ring on both faces it passes.
void check_base_interface(const std::string& file) {
  io::CadImport in = import_part(file, counts(56, 84, 30, 40, 1), "in", 25.4);
  const Body& b = in.body;
  if (b.counts().shells != 1) return;
  EXPECT_EQ(b.shell_genus(b.shells()[0]), 5u);
  std::map<std::string, int> types = surface_types(b);
  EXPECT_EQ(types["plane"], 8);
  EXPECT_EQ(types["cylinder"], 22);
  EXPECT_TRUE(in.warnings.empty()) << in.warnings.front();
}

TEST(ThirdParty, TrimeshBaseInterfaceAP203) { check_base_interface("base_interface_AP203.STEP"); }
TEST(ThirdParty, TrimeshBaseInterfaceAP214) { check_base_interface("base_interface_AP214.STEP"); }

TEST(ThirdParty, TwoSchemasOfTheSamePartGiveTheSameBody) {
  std::string err;
  std::optional<io::CadImport> a = io::import_cad(kDir + "base_interface_AP203.STEP", CadFormat::step, &err);
  ASSERT_TRUE(a) << err;
  std::optional<io::CadImport> b = io::import_cad(kDir + "base_interface_AP214.STEP", CadFormat::step, &err);
  ASSERT_TRUE(b) << err;
  EXPECT_EQ(test::compare_bodies(a->body, b->body), "");
  EXPECT_EQ(test::compare_bodies(b->body, a->body), "");
}

// Zoo's (KittyCAD) kcl-samples pipe, exported by the zoo.dev engine in metres: a tube
// with a 30° conical step between two diameters. The file has 8 VERTEX_POINTs and 16
// EDGE_CURVEs, of which only the 8 circles bound faces (the 8 lines are unused); 8
// ADVANCED_FACEs, each bounded by two circles (two FACE_BOUNDs): 2 PLANEs (annuli), 4
// CYLINDRICAL_SURFACEs and 2 rational B-spline surfaces that are cones (control points
// at radius 0.0206375 and 0.0279698 m, 0.0127 m apart along z: tan α = 1/√3). The six
// periodic faces have no seam in the file; OpenCASCADE's reader adds one each
// (ShapeFix), which joins the two circles into one loop: 8 + 6 = 14 edges, 2 × 2 + 6 = 10
// loops. 8 − 14 + 8 − 2 rings = 0: genus 1, as a tube is.
TEST(ThirdParty, ZooPipeWithConicalStep) {
  io::CadImport in = import_part("zoo_pipe.step", counts(8, 14, 8, 10, 1), "m", 1000.0);
  const Body& b = in.body;
  if (b.counts().shells != 1) return;
  EXPECT_EQ(b.shell_genus(b.shells()[0]), 1u);
  std::map<std::string, int> types = surface_types(b);
  EXPECT_EQ(types["plane"], 2);
  EXPECT_EQ(types["cylinder"], 4);
  EXPECT_EQ(types["cone"], 2);
  for (FaceH f : b.faces()) {
    if (const auto* c = std::get_if<geo::Cone>(&b.surface(f))) {
      EXPECT_NEAR(std::abs(c->half_angle), M_PI / 6, 1e-9);
    }
  }
  EXPECT_EQ(warnings_with(in, "B-spline surface recognised as a cone"), 2);
  // The six seams ShapeFix adds have B-spline 3D curves: on the four cylinders they are
  // parameter lines (lines); on the two B-spline cones, B-splines whose poles are on a
  // line. All six are lines.
  EXPECT_EQ(warnings_with(in, "recognised as a line (a parameter line of its face)"), 4);
  EXPECT_EQ(warnings_with(in, "recognised as a line (its poles are on one)"), 2);
  int lines = 0;
  for (EdgeH e : b.edges()) lines += std::holds_alternative<geo::Line>(b.curve(e)) ? 1 : 0;
  EXPECT_EQ(lines, 6);
}

// Zoo's (KittyCAD) kcl-samples pipe with a bend: a quarter of a torus tube, in metres.
// The file has 4 ADVANCED_FACEs, each bounded by two closed circles (one vertex each): 2
// TOROIDAL_SURFACEs (major radius 0.762, minor 0.254 outside and 0.127 inside) and 2
// PLANEs (annular ends). Only 4 of its 6 EDGE_CURVEs bound faces, on 4 of its VERTEX_POINTs.
// The torus faces have no seam in the file; OpenCASCADE's reader adds one each: 4 + 2 = 6
// edges, 2 × 2 + 2 = 6 loops. 4 − 6 + 4 − 2 rings = 0: genus 1.
TEST(ThirdParty, ZooPipeWithBendIsTwoTorusFaces) {
  io::CadImport in = import_part("zoo_pipe_with_bend.step", counts(4, 6, 4, 6, 1), "m", 1000.0);
  const Body& b = in.body;
  if (b.counts().shells != 1) return;
  EXPECT_EQ(b.shell_genus(b.shells()[0]), 1u);
  std::vector<double> minor;
  for (FaceH f : b.faces())
    if (const auto* t = std::get_if<geo::Torus>(&b.surface(f))) {
      EXPECT_NEAR(t->major_radius, 0.762, 1e-12);
      minor.push_back(t->minor_radius);
      // The outer tube faces away from its axis circle, the bore towards it (the
      // file's ADVANCED_FACE sense flags: .T. and .F.; both frames are right-handed).
      EXPECT_EQ(b.same_sense(f), t->minor_radius > 0.2);
    }
  std::sort(minor.begin(), minor.end());
  ASSERT_EQ(minor.size(), 2u);
  EXPECT_NEAR(minor[0], 0.127, 1e-12);
  EXPECT_NEAR(minor[1], 0.254, 1e-12);
  // The seams ShapeFix adds run along the bend (a quarter of a circle about the y axis,
  // from angle 0 to 90°); their B-spline curves are recognised as those circles, and
  // each edge is the quarter inside the part (x ≥ 0, z ≤ 0), not the rest of the circle.
  EXPECT_EQ(warnings_with(in, "recognised as a circle (a parameter line of its face)"), 2);
  int arcs = 0;
  for (EdgeH e : b.edges()) {
    HalfedgeH h = halfedge_of(e, 0);
    if (b.origin(h) == b.target(h)) continue;  // the closed circles at the ends
    ASSERT_TRUE(std::holds_alternative<geo::Circle>(b.curve(e))) << e.str();
    ++arcs;
    geo::ParameterRange r = geo::parameter_range(b.curve(e), b.point(b.origin(h)), b.point(b.target(h)));
    geo::Vec3 mid = geo::evaluate(b.curve(e), 0.5 * (r.t0 + r.t1));
    EXPECT_GT(mid.x(), 0.1) << e.str();
    EXPECT_LT(mid.z(), -0.1) << e.str();
    EXPECT_NEAR(std::abs(mid.x()), std::abs(mid.z()), 1e-9) << e.str() << ": halfway along the bend";
  }
  EXPECT_EQ(arcs, 2);
}

}  // namespace
}  // namespace kintsugi
