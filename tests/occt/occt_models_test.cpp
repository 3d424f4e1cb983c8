// Models made by OpenCASCADE itself import with the right counts and pass our check.
#include "invariants/topology_check.h"
#include "io/occt/exchange.h"
#include "tests/occt/compare.h"

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_NurbsConvert.hxx>
#include <BRepFilletAPI_MakeFillet.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <GeomAPI_PointsToBSplineSurface.hxx>
#include <Geom_BSplineSurface.hxx>
#include <STEPControl_Writer.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Shell.hxx>
#include <gp_Ax2.hxx>

#include <gtest/gtest.h>

#include <cmath>

namespace kintsugi {
namespace {

using io::CadFormat;

std::string write_shape(const TopoDS_Shape& s, const std::string& name, CadFormat f) {
  std::string path = test::temp_path(name + (f == CadFormat::step ? ".step" : ".brep"));
  if (f == CadFormat::brep) {
    EXPECT_TRUE(BRepTools::Write(s, path.c_str()));
  } else {
    STEPControl_Writer w;
    EXPECT_EQ(w.Transfer(s, STEPControl_AsIs), IFSelect_RetDone);
    EXPECT_EQ(w.Write(path.c_str()), IFSelect_RetDone);
  }
  return path;
}

Counts counts(std::size_t v, std::size_t e, std::size_t f, std::size_t l, std::size_t s = 1, std::size_t bc = 0) {
  Counts c;
  c.vertices = v;
  c.edges = e;
  c.faces = f;
  c.loops = l;
  c.shells = s;
  c.border_cycles = bc;
  return c;
}

// Imports the shape through both formats; checks counts, our topology check and
// OpenCASCADE's verdict on the result. Returns the BREP import.
Body import_both(const TopoDS_Shape& s, const std::string& name, const Counts& expect) {
  Body out;
  for (CadFormat f : {CadFormat::step, CadFormat::brep}) {
    std::string err;
    std::optional<io::CadImport> in = io::import_cad(write_shape(s, name, f), f, &err);
    if (!in) {
      ADD_FAILURE() << name << ": " << err;
      continue;
    }
    EXPECT_EQ(in->body.counts(), expect) << name << (f == CadFormat::step ? " (STEP)" : " (BREP)");
    for (const Violation& v : check_topology(in->body)) ADD_FAILURE() << name << ": " << to_string(v);
    io::OcctVerdict verdict = io::occt_check(in->body);
    std::string why;
    for (const std::string& p : verdict.problems) why += "\n  " + p;
    EXPECT_TRUE(verdict.valid) << name << why;
    if (f == CadFormat::brep) out = std::move(in->body);
  }
  return out;
}

TEST(OcctModels, Box) { import_both(BRepPrimAPI_MakeBox(10, 20, 30).Shape(), "occt_box", counts(8, 12, 6, 6)); }

TEST(OcctModels, Cylinder) {
  Body b = import_both(BRepPrimAPI_MakeCylinder(2, 5).Shape(), "occt_cylinder", counts(2, 3, 3, 3));
  int cylinders = 0;
  for (FaceH f : b.faces())
    if (const auto* c = std::get_if<geo::Cylinder>(&b.surface(f))) {
      ++cylinders;
      EXPECT_NEAR(c->radius, 2, 1e-12);
      EXPECT_TRUE(b.same_sense(f));
    }
  EXPECT_EQ(cylinders, 1);
}

TEST(OcctModels, ConeWithApex) {
  Body b = import_both(BRepPrimAPI_MakeCone(3, 0, 4).Shape(), "occt_cone", counts(2, 2, 2, 2));
  for (FaceH f : b.faces()) {
    if (const auto* c = std::get_if<geo::Cone>(&b.surface(f))) {
      EXPECT_NEAR(std::abs(std::tan(c->half_angle)), 0.75, 1e-12);
    }
  }
}

TEST(OcctModels, TruncatedCone) {
  import_both(BRepPrimAPI_MakeCone(3, 1, 4).Shape(), "occt_frustum", counts(2, 3, 3, 3));
}

TEST(OcctModels, Sphere) {
  Body b = import_both(BRepPrimAPI_MakeSphere(5).Shape(), "occt_sphere", counts(2, 1, 1, 1));
  ASSERT_EQ(b.faces().size(), 1u);
  EXPECT_TRUE(std::holds_alternative<geo::Sphere>(b.surface(b.faces()[0])));
}

TEST(OcctModels, Torus) {
  Body b = import_both(BRepPrimAPI_MakeTorus(5, 1).Shape(), "occt_torus", counts(1, 2, 1, 1));
  EXPECT_EQ(b.shell_genus(b.shells()[0]), 1u);
}

TEST(OcctModels, BoxMinusCylinderHasAThroughHole) {
  TopoDS_Shape box = BRepPrimAPI_MakeBox(10, 10, 10).Shape();
  TopoDS_Shape cyl = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(5, 5, -5), gp::DZ()), 2, 20).Shape();
  BRepAlgoAPI_Cut cut(box, cyl);
  ASSERT_TRUE(cut.IsDone());
  // 8 + 2 vertices; 12 + 2 circles + 1 seam; 7 faces with 2 rings.
  Body b = import_both(cut.Shape(), "occt_cut", counts(10, 15, 7, 9));
  EXPECT_EQ(b.shell_genus(b.shells()[0]), 1u);
  int holes = 0;
  for (FaceH f : b.faces())
    if (const auto* c = std::get_if<geo::Cylinder>(&b.surface(f))) {
      ++holes;
      EXPECT_NEAR(c->radius, 2, 1e-12);
      EXPECT_FALSE(b.same_sense(f)) << "the hole's outward normal points at its axis";
    }
  EXPECT_EQ(holes, 1);
}

TEST(OcctModels, FilletOnABoxEdgeIsACylinder) {
  TopoDS_Shape box = BRepPrimAPI_MakeBox(10, 10, 10).Shape();
  BRepFilletAPI_MakeFillet fillet(box);
  TopTools_IndexedMapOfShape edges;
  TopExp::MapShapes(box, TopAbs_EDGE, edges);
  fillet.Add(2.0, TopoDS::Edge(edges(1)));
  fillet.Build();
  ASSERT_TRUE(fillet.IsDone());
  Body b = import_both(fillet.Shape(), "occt_fillet", counts(10, 15, 7, 7));
  int cylinders = 0;
  for (FaceH f : b.faces())
    if (const auto* c = std::get_if<geo::Cylinder>(&b.surface(f))) {
      ++cylinders;
      EXPECT_NEAR(c->radius, 2, 1e-9);
      EXPECT_TRUE(b.same_sense(f)) << "a convex fillet faces away from its axis";
    }
  EXPECT_EQ(cylinders, 1);
}

TEST(OcctModels, ShellWithAFaceRemovedHasOneBorderCycle) {
  TopoDS_Shape box = BRepPrimAPI_MakeBox(10, 10, 10).Shape();
  TopoDS_Shell shell;
  BRep_Builder bb;
  bb.MakeShell(shell);
  int n = 0;
  for (TopExp_Explorer ex(box, TopAbs_FACE); ex.More(); ex.Next())
    if (n++ != 3) bb.Add(shell, ex.Current());
  Body b = import_both(shell, "occt_open_shell", counts(8, 12, 5, 5, 1, 1));
}

TEST(OcctModels, BSplinePlanesAreRecognised) {
  BRepBuilderAPI_NurbsConvert nurbs(BRepPrimAPI_MakeBox(10, 20, 30).Shape());
  std::string err;
  std::optional<io::CadImport> in =
      io::import_cad(write_shape(nurbs.Shape(), "nurbs_box", CadFormat::brep), CadFormat::brep, &err);
  ASSERT_TRUE(in) << err;
  std::optional<io::CadImport> plain =
      io::import_cad(write_shape(BRepPrimAPI_MakeBox(10, 20, 30).Shape(), "plain_box", CadFormat::brep),
                     CadFormat::brep, &err);
  ASSERT_TRUE(plain) << err;
  EXPECT_EQ(test::compare_bodies(plain->body, in->body), "");
  int recognised = 0;
  for (const std::string& w : in->warnings) recognised += w.find("recognised as a plane") != std::string::npos;
  EXPECT_EQ(recognised, 6);
}

TEST(OcctModels, BSplineCylinderIsRecognised) {
  BRepBuilderAPI_NurbsConvert nurbs(BRepPrimAPI_MakeCylinder(2, 5).Shape());
  std::string err;
  std::optional<io::CadImport> in =
      io::import_cad(write_shape(nurbs.Shape(), "nurbs_cylinder", CadFormat::brep), CadFormat::brep, &err);
  ASSERT_TRUE(in) << err;
  std::optional<io::CadImport> plain =
      io::import_cad(write_shape(BRepPrimAPI_MakeCylinder(2, 5).Shape(), "plain_cylinder", CadFormat::brep),
                     CadFormat::brep, &err);
  ASSERT_TRUE(plain) << err;
  // The B-spline edges come back as polylines; the faces as the analytic surfaces.
  EXPECT_EQ(in->body.counts(), plain->body.counts());
  int cylinders = 0;
  for (FaceH f : in->body.faces())
    if (const auto* c = std::get_if<geo::Cylinder>(&in->body.surface(f))) {
      ++cylinders;
      EXPECT_NEAR(c->radius, 2, 1e-6);
      EXPECT_TRUE(in->body.same_sense(f));
    }
  EXPECT_EQ(cylinders, 1);
  for (const Violation& v : check_topology(in->body)) ADD_FAILURE() << to_string(v);
  io::OcctVerdict verdict = io::occt_check(in->body);
  EXPECT_TRUE(verdict.valid) << (verdict.problems.empty() ? "" : verdict.problems[0]);
}

TEST(OcctModels, FreeFormFaceIsRefusedWithItsLocator) {
  TColgp_Array2OfPnt pts(1, 5, 1, 5);
  for (int i = 1; i <= 5; ++i)
    for (int j = 1; j <= 5; ++j) pts(i, j) = gp_Pnt(i, j, std::sin(i) * std::cos(1.7 * j));
  Handle(Geom_BSplineSurface) s = GeomAPI_PointsToBSplineSurface(pts).Surface();
  TopoDS_Face face = BRepBuilderAPI_MakeFace(s, 1e-7).Face();
  std::string err;
  std::optional<io::CadImport> in = io::import_cad(write_shape(face, "wavy", CadFormat::step), CadFormat::step, &err);
  EXPECT_FALSE(in);
  EXPECT_NE(err.find("wavy.step"), std::string::npos) << err;
  EXPECT_NE(err.find("1 B-spline surface"), std::string::npos) << err;
  EXPECT_NE(err.find("face #1 (STEP entity #"), std::string::npos) << err;
  EXPECT_NE(err.find("not within precision"), std::string::npos) << err;
}

}  // namespace
}  // namespace kintsugi
