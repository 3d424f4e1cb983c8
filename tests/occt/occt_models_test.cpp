// Models made by OpenCASCADE itself import with the right counts and pass our check.
#include "geometry/curve.h"
#include "invariants/topology_check.h"
#include "io/occt/exchange.h"
#include "tests/occt/compare.h"

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepBuilderAPI_Copy.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepBuilderAPI_NurbsConvert.hxx>
#include <BRepFilletAPI_MakeFillet.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>
#include <BRepTools.hxx>
#include <BRepTools_ReShape.hxx>
#include <BRep_Tool.hxx>
#include <BRep_Builder.hxx>
#include <GeomAPI_PointsToBSplineSurface.hxx>
#include <GeomConvert.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_Line.hxx>
#include <Geom_CylindricalSurface.hxx>
#include <Geom_TrimmedCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <STEPControl_Writer.hxx>
#include <ShapeFix_Wire.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Vertex.hxx>
#include <TopoDS_Wire.hxx>
#include <TopoDS_Shell.hxx>
#include <gp_Ax2.hxx>
#include <gp_Trsf.hxx>

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

using test::counts;

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
  // The faces come back as the analytic surfaces. Of the B-spline edges, the seam (a
  // degree-1 B-spline whose poles are on a line) is a line; the two circles, whose
  // faces are B-spline surfaces, come back as they are: exact B-spline curves.
  EXPECT_EQ(in->body.counts(), plain->body.counts());
  int lines = 0, bsplines = 0;
  for (EdgeH e : in->body.edges()) {
    lines += std::holds_alternative<geo::Line>(in->body.curve(e)) ? 1 : 0;
    bsplines += std::holds_alternative<geo::BSplineCurve>(in->body.curve(e)) ? 1 : 0;
  }
  EXPECT_EQ(lines, 1);
  EXPECT_EQ(bsplines, 2);
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

// The shape with every edge's 3D curve replaced by a B-spline (GeomConvert of the
// curve trimmed to the edge; the pcurves are kept), as some writers and OpenCASCADE's
// ShapeFix (the seams it adds) give them.
TopoDS_Shape with_bspline_edges(const TopoDS_Shape& original) {
  TopoDS_Shape s = BRepBuilderAPI_Copy(original).Shape();
  TopTools_IndexedMapOfShape edges;
  TopExp::MapShapes(s, TopAbs_EDGE, edges);
  BRep_Builder bb;
  for (int i = 1; i <= edges.Extent(); ++i) {
    TopoDS_Edge e = TopoDS::Edge(edges(i));
    if (BRep_Tool::Degenerated(e)) continue;
    double f = 0, l = 0;
    Handle(Geom_Curve) c = BRep_Tool::Curve(e, f, l);
    if (c.IsNull()) continue;
    Handle(Geom_BSplineCurve) bs = GeomConvert::CurveToBSplineCurve(new Geom_TrimmedCurve(c, f, l));
    EXPECT_FALSE(bs.IsNull());
    bb.UpdateEdge(e, bs, BRep_Tool::Tolerance(e));
    bb.Range(e, bs->FirstParameter(), bs->LastParameter(), Standard_True);  // the 3D curve's range only
    bb.SameParameter(e, Standard_False);
  }
  return s;
}

// Imports the shape and its copy with B-spline edge curves: on elementary faces every
// edge runs along a parameter line of a face, so it comes back as that line or circle
// (running the edge's way), and the two bodies are equal.
void expect_bspline_edges_recognised(const TopoDS_Shape& s, const std::string& name) {
  std::string err;
  std::optional<io::CadImport> plain = io::import_cad(write_shape(s, name, CadFormat::brep), CadFormat::brep, &err);
  ASSERT_TRUE(plain) << err;
  std::optional<io::CadImport> in =
      io::import_cad(write_shape(with_bspline_edges(s), name + "_bspline_edges", CadFormat::brep), CadFormat::brep,
                     &err);
  ASSERT_TRUE(in) << err;
  const Body& b = in->body;
  int recognised = 0;
  for (const std::string& w : in->warnings) recognised += w.find("(a parameter line of its face)") != std::string::npos;
  EXPECT_EQ(std::size_t(recognised), b.counts().edges) << name;
  for (EdgeH e : b.edges()) {
    EXPECT_FALSE(std::holds_alternative<geo::Polyline>(b.curve(e))) << name << " " << e.str();
    EXPECT_EQ(b.curve(e).index(), plain->body.curve(e).index()) << name << " " << e.str();
  }
  EXPECT_EQ(test::compare_bodies(plain->body, b), "") << name;
  EXPECT_EQ(test::compare_bodies(b, plain->body), "") << name;
  for (const Violation& v : check_topology(b)) ADD_FAILURE() << name << ": " << to_string(v);
  io::OcctVerdict verdict = io::occt_check(b);
  EXPECT_TRUE(verdict.valid) << name << (verdict.problems.empty() ? "" : ": " + verdict.problems[0]);
}

TEST(OcctModels, BSplineEdgesAlongParameterLinesAreLinesAndCircles) {
  // A quarter torus: its seam is an open arc of a circle (a quarter), so the circle's
  // direction decides which arc the edge is. Then the same mirrored: OpenCASCADE's
  // surface frame becomes left-handed and its iso-circles run against the faces' u.
  TopoDS_Shape quarter = BRepPrimAPI_MakeTorus(5, 1, M_PI / 2).Shape();
  expect_bspline_edges_recognised(quarter, "quarter_torus");
  gp_Trsf mirror;
  mirror.SetMirror(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(1, 0, 0)));
  expect_bspline_edges_recognised(BRepBuilderAPI_Transform(quarter, mirror, Standard_True).Shape(),
                                  "mirrored_quarter_torus");
  expect_bspline_edges_recognised(BRepPrimAPI_MakeCylinder(2, 5, 2.0).Shape(), "cylinder_sector");
  expect_bspline_edges_recognised(BRepPrimAPI_MakeSphere(3, -0.5, 1.0, 4.0).Shape(), "sphere_zone");
}

// The face of the cylinder of radius 2 about z between angles 0 and 1 and heights 0 and
// 3. With `bspline`, its two arcs are replaced by edges whose curves are B-splines
// running the other way (against the surface's u, as a writer may give them), whose
// pcurves ShapeFix then projects as B-splines.
TopoDS_Face cylinder_patch(bool bspline) {
  TopoDS_Face f = BRepBuilderAPI_MakeFace(new Geom_CylindricalSurface(gp_Ax3(gp::XOY()), 2), 0, 1, 0, 3, 1e-7);
  if (!bspline) return f;
  BRepTools_ReShape reshape;
  for (TopExp_Explorer ex(f, TopAbs_EDGE); ex.More(); ex.Next()) {
    TopoDS_Edge e = TopoDS::Edge(ex.Current().Oriented(TopAbs_FORWARD));
    double a = 0, b = 0;
    Handle(Geom_Curve) c = BRep_Tool::Curve(e, a, b);
    if (c.IsNull() || c->IsKind(STANDARD_TYPE(Geom_Line))) continue;
    Handle(Geom_BSplineCurve) reversed = GeomConvert::CurveToBSplineCurve(new Geom_TrimmedCurve(c, a, b));
    reversed->Reverse();
    TopoDS_Vertex v0, v1;
    TopExp::Vertices(e, v0, v1);
    TopoDS_Edge from_v1 = BRepBuilderAPI_MakeEdge(reversed, v1, v0);
    reshape.Replace(e, from_v1.Reversed());
  }
  TopoDS_Face g = TopoDS::Face(reshape.Apply(f));
  for (TopExp_Explorer ex(g, TopAbs_WIRE); ex.More(); ex.Next()) {
    ShapeFix_Wire fix(TopoDS::Wire(ex.Current()), g, 1e-7);
    fix.FixEdgeCurves();
  }
  return g;
}

TEST(OcctModels, BSplineArcRunningAgainstItsSurfaceIsTheRightArc) {
  std::string err;
  std::optional<io::CadImport> plain =
      io::import_cad(write_shape(cylinder_patch(false), "patch", CadFormat::brep), CadFormat::brep, &err);
  ASSERT_TRUE(plain) << err;
  std::optional<io::CadImport> in =
      io::import_cad(write_shape(cylinder_patch(true), "patch_bspline", CadFormat::brep), CadFormat::brep, &err);
  ASSERT_TRUE(in) << err;
  const Body& b = in->body;
  int circles = 0;
  for (EdgeH e : b.edges()) {
    const auto* c = std::get_if<geo::Circle>(&b.curve(e));
    if (!c) continue;
    ++circles;
    // The arc between the edge's ends is the one between angles 0 and 1, not the rest
    // of the circle.
    HalfedgeH h = halfedge_of(e, 0);
    geo::ParameterRange r = geo::parameter_range(b.curve(e), b.point(b.origin(h)), b.point(b.target(h)));
    geo::Vec3 mid = geo::evaluate(b.curve(e), 0.5 * (r.t0 + r.t1));
    EXPECT_NEAR(std::atan2(mid.y(), mid.x()), 0.5, 1e-9) << e.str();
  }
  EXPECT_EQ(circles, 2);
  EXPECT_EQ(test::compare_bodies(plain->body, b), "");
  EXPECT_EQ(test::compare_bodies(b, plain->body), "");
  io::OcctVerdict verdict = io::occt_check(b);
  EXPECT_TRUE(verdict.valid) << (verdict.problems.empty() ? "" : verdict.problems[0]);
  io::OcctVerdict v0 = io::occt_check(plain->body);
  EXPECT_TRUE(v0.valid) << (v0.problems.empty() ? "" : v0.problems[0]);
}

TEST(OcctModels, FreeFormFaceIsKeptExactly) {
  TColgp_Array2OfPnt pts(1, 5, 1, 5);
  for (int i = 1; i <= 5; ++i)
    for (int j = 1; j <= 5; ++j) pts(i, j) = gp_Pnt(i, j, std::sin(i) * std::cos(1.7 * j));
  Handle(Geom_BSplineSurface) s = GeomAPI_PointsToBSplineSurface(pts).Surface();
  TopoDS_Face face = BRepBuilderAPI_MakeFace(s, 1e-7).Face();
  for (CadFormat f : {CadFormat::step, CadFormat::brep}) {
    std::string err;
    std::optional<io::CadImport> in = io::import_cad(write_shape(face, "wavy", f), f, &err);
    ASSERT_TRUE(in) << err;
    ASSERT_EQ(in->body.counts().faces, 1u);
    const auto* b = std::get_if<geo::BSplineSurface>(&in->body.surface(in->body.faces()[0]));
    ASSERT_TRUE(b) << geo::surface_type_name(in->body.surface(in->body.faces()[0]));
    // Exactly the surface written: its poles one for one.
    ASSERT_EQ(b->u_count, s->NbUPoles());
    ASSERT_EQ(b->v_count, s->NbVPoles());
    for (int i = 1; i <= s->NbUPoles(); ++i)
      for (int j = 1; j <= s->NbVPoles(); ++j)
        EXPECT_LE((b->poles[std::size_t((i - 1) * b->v_count + j - 1)] -
                   geo::Vec3(s->Pole(i, j).X(), s->Pole(i, j).Y(), s->Pole(i, j).Z()))
                      .norm(),
                  1e-12);
    for (const Violation& v : check_topology(in->body)) ADD_FAILURE() << to_string(v);
  }
}

}  // namespace
}  // namespace kintsugi
