// Swept surfaces recognised as the elementary surfaces they are (io/occt/swept_elementary.h).
// Our headers before OpenCASCADE's: its Handle(T) macro would rewrite kernel/handles.h.
#include "geometry/surface.h"
#include "invariants/geometry_check.h"
#include "invariants/topology_check.h"
#include "io/occt/exchange.h"
#include "tests/occt/compare.h"

#include "io/occt/swept_elementary.h"

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepPrimAPI_MakeRevol.hxx>
#include <BRepTools.hxx>
#include <GC_MakeArcOfCircle.hxx>
#include <Geom_Circle.hxx>
#include <Geom_ConicalSurface.hxx>
#include <Geom_CylindricalSurface.hxx>
#include <Geom_Line.hxx>
#include <Geom_Plane.hxx>
#include <Geom_SphericalSurface.hxx>
#include <Geom_SurfaceOfLinearExtrusion.hxx>
#include <Geom_SurfaceOfRevolution.hxx>
#include <Geom_ToroidalSurface.hxx>
#include <gtest/gtest.h>

#include <cmath>

namespace kintsugi {
namespace {

using io::occt::swept_elementary;

const gp_Ax1 kZ(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1));
constexpr double kTol = 1e-7;

// The surface swept by revolving `c` about z, recognised over a quarter turn and the
// curve's parameters [v0, v1].
Handle(Geom_Surface) revolve(const Handle(Geom_Curve)& c, double v0, double v1) {
  return swept_elementary(new Geom_SurfaceOfRevolution(c, kZ), 0, M_PI / 2, v0, v1, kTol);
}
Handle(Geom_Curve) line(gp_Pnt p, gp_Dir d) { return new Geom_Line(p, d); }

TEST(SweptElementary, ACircleRevolvedInAPlaneThroughTheAxisIsATorus) {
  // Centre 30 from the axis at height 5, in the xz plane.
  Handle(Geom_Surface) s = revolve(new Geom_Circle(gp_Ax2(gp_Pnt(30, 0, 5), gp_Dir(0, 1, 0)), 4), 0, 2 * M_PI);
  auto t = Handle(Geom_ToroidalSurface)::DownCast(s);
  ASSERT_FALSE(t.IsNull());
  EXPECT_NEAR(t->MajorRadius(), 30, 1e-12);
  EXPECT_NEAR(t->MinorRadius(), 4, 1e-12);
  EXPECT_LT(t->Location().Distance(gp_Pnt(0, 0, 5)), 1e-12);
  EXPECT_TRUE(t->Axis().Direction().IsParallel(gp_Dir(0, 0, 1), 1e-12));
}

TEST(SweptElementary, ACircleTiltedOutOfThePlaneThroughTheAxisIsNoTorus) {
  // Its plane turned 5 degrees about the line from the axis to its centre: the sweep is
  // no torus, though a torus has the same major and minor radius.
  const double a = 5 * M_PI / 180;
  Handle(Geom_Surface) s =
      revolve(new Geom_Circle(gp_Ax2(gp_Pnt(30, 0, 5), gp_Dir(0, std::cos(a), std::sin(a))), 4), 0, 2 * M_PI);
  EXPECT_TRUE(s.IsNull());
}

TEST(SweptElementary, ACircleCentredOnTheAxisIsASphere) {
  Handle(Geom_Surface) s = revolve(new Geom_Circle(gp_Ax2(gp_Pnt(0, 0, 7), gp_Dir(0, 1, 0)), 6), 0, M_PI / 2);
  auto sp = Handle(Geom_SphericalSurface)::DownCast(s);
  ASSERT_FALSE(sp.IsNull());
  EXPECT_NEAR(sp->Radius(), 6, 1e-12);
  EXPECT_LT(sp->Location().Distance(gp_Pnt(0, 0, 7)), 1e-12);
}

TEST(SweptElementary, LinesRevolvedAreCylindersConesAndPlanes) {
  const double a = 20 * M_PI / 180;
  // Opening upwards from r 10: +20 degrees; closing: -20 degrees.
  for (double sign : {1.0, -1.0}) {
    auto c = Handle(Geom_ConicalSurface)::DownCast(
        revolve(line(gp_Pnt(10, 0, 0), gp_Dir(sign * std::sin(a), 0, std::cos(a))), 0, 20));
    ASSERT_FALSE(c.IsNull()) << sign;
    EXPECT_NEAR(c->SemiAngle(), sign * a, 1e-12);
  }
  // Through the axis: the apex is on it.
  auto apex = Handle(Geom_ConicalSurface)::DownCast(revolve(line(gp_Pnt(0, 0, 3), gp_Dir(1, 0, 1)), 1, 20));
  ASSERT_FALSE(apex.IsNull());
  EXPECT_LT(apex->Apex().Distance(gp_Pnt(0, 0, 3)), 1e-9);
  EXPECT_NEAR(std::abs(apex->SemiAngle()), M_PI / 4, 1e-12);
  auto cyl = Handle(Geom_CylindricalSurface)::DownCast(revolve(line(gp_Pnt(10, 0, 0), gp_Dir(0, 0, 1)), 0, 20));
  ASSERT_FALSE(cyl.IsNull());
  EXPECT_NEAR(cyl->Radius(), 10, 1e-12);
  auto plane = Handle(Geom_Plane)::DownCast(revolve(line(gp_Pnt(0, 5, 4), gp_Dir(1, 0, 0)), -20, 20));
  ASSERT_FALSE(plane.IsNull());
  EXPECT_TRUE(plane->Axis().Direction().IsParallel(gp_Dir(0, 0, 1), 1e-12));
  EXPECT_NEAR(plane->Location().Z(), 4, 1e-12);
}

TEST(SweptElementary, ASkewLineRevolvedIsAHyperboloidNotACone) {
  // Through x = 10, rising across y and a little outwards: its distance from the axis
  // changes, but not linearly (a cone's candidate, from its slope at x = 10, misses it).
  EXPECT_TRUE(revolve(line(gp_Pnt(10, 0, 0), gp_Dir(0.3, 1, 1)), -10, 10).IsNull());
}

TEST(SweptElementary, ExtrusionsOfALineAndOfACircleAlongItsAxisArePlaneAndCylinder) {
  auto extrude = [](const Handle(Geom_Curve)& c, gp_Dir d, double u0, double u1) {
    return swept_elementary(new Geom_SurfaceOfLinearExtrusion(c, d), u0, u1, -5, 5, kTol);
  };
  const Handle(Geom_Curve) circle = new Geom_Circle(gp_Ax2(gp_Pnt(1, 2, 3), gp_Dir(0, 0, 1)), 8);
  auto cyl = Handle(Geom_CylindricalSurface)::DownCast(extrude(circle, gp_Dir(0, 0, 1), 0, M_PI));
  ASSERT_FALSE(cyl.IsNull());
  EXPECT_NEAR(cyl->Radius(), 8, 1e-12);
  // Extruded obliquely, the circle sweeps an elliptic cylinder.
  EXPECT_TRUE(extrude(circle, gp_Dir(0, 1, 1), 0, M_PI).IsNull());
  auto plane = Handle(Geom_Plane)::DownCast(extrude(line(gp_Pnt(0, 0, 0), gp_Dir(1, 0, 0)), gp_Dir(0, 1, 1), -3, 3));
  ASSERT_FALSE(plane.IsNull());
  EXPECT_TRUE(plane->Axis().Direction().IsParallel(gp_Dir(0, -1, 1), 1e-12));
}

// A part revolved from a sketch with a rounded ridge (two lines and an arc between them):
// OpenCASCADE sweeps the arc into a surface of revolution, which reads as the torus it is,
// the lines into cones; the model valid.
TEST(SweptElementary, ARevolvedSketchReadsAsElementaryFaces) {
  auto at = [](double x, double z) { return gp_Pnt(x, 0, z); };
  BRepBuilderAPI_MakeWire w;
  w.Add(BRepBuilderAPI_MakeEdge(at(0, 0), at(10, 0)).Edge());
  w.Add(BRepBuilderAPI_MakeEdge(at(10, 0), at(20, 10)).Edge());
  // An arc from (20, 10) out to x = 25 and back to (20, 20): centre (20, 15), radius 5 (a
  // torus of major radius 20); tangency to the lines is not needed for the recognition.
  w.Add(BRepBuilderAPI_MakeEdge(GC_MakeArcOfCircle(at(20, 10), at(25, 15), at(20, 20)).Value()).Edge());
  w.Add(BRepBuilderAPI_MakeEdge(at(20, 20), at(10, 30)).Edge());
  w.Add(BRepBuilderAPI_MakeEdge(at(10, 30), at(0, 30)).Edge());
  w.Add(BRepBuilderAPI_MakeEdge(at(0, 30), at(0, 0)).Edge());
  ASSERT_TRUE(w.IsDone());
  TopoDS_Shape s = BRepPrimAPI_MakeRevol(BRepBuilderAPI_MakeFace(w.Wire()).Face(), kZ).Shape();
  std::string path = test::temp_path("swept_sketch.brep"), err;
  ASSERT_TRUE(BRepTools::Write(s, path.c_str()));
  std::optional<io::CadImport> in = io::import_cad(path, io::CadFormat::brep, &err);
  ASSERT_TRUE(in) << err;
  const Body& b = in->body;
  int tori = 0, cones = 0, planes = 0;
  for (FaceH f : b.faces()) {
    tori += std::holds_alternative<geo::Torus>(b.surface(f));
    cones += std::holds_alternative<geo::Cone>(b.surface(f));
    planes += std::holds_alternative<geo::Plane>(b.surface(f));
  }
  EXPECT_EQ(tori, 1);
  EXPECT_EQ(cones, 2);
  EXPECT_EQ(planes, 2);
  EXPECT_TRUE(check_topology(b).empty());
  EXPECT_LT(check_geometry(b, 1e-7).max_deviation, 1e-7);
  EXPECT_TRUE(io::occt_check(b).valid);
}

}  // namespace
}  // namespace kintsugi
