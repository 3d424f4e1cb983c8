// Free-form faces carried exactly (issue 22): a prism and a solid of revolution on a
// B-spline profile read with their extrusion / revolution surfaces and B-spline edges,
// check valid, survive the native format and BREP/STEP/IGES exactly, pass OpenCASCADE's
// checker, and come out of beautify unchanged when nothing is wrong with them. Without
// the backend, the native reader refuses them, saying why.
#include "geometry/curve.h"
#include "geometry/freeform.h"
#include "geometry/surface.h"
#include "geometry/surface_params.h"
#include "invariants/element_geometry.h"
#include "invariants/geometry_check.h"
#include "invariants/region_validity.h"
#include "invariants/topology_check.h"
#include "io/native_json.h"
#include "io/occt/pcurve.h"
#include "io/occt/exchange.h"
#include "repair/beautify.h"
#include "repair/detect.h"
#include "tests/occt/compare.h"
// OpenCASCADE's headers after ours: its Handle(x) macro would hit kernel/handles.h.
#include "geometry/occt/freeform_occt.h"

#include <Bnd_Box.hxx>
#include <BndLib_AddSurface.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepPrimAPI_MakePrism.hxx>
#include <BRepPrimAPI_MakeRevol.hxx>
#include <BRepTools.hxx>
#include <Geom2d_Curve.hxx>
#include <Geom_Circle.hxx>
#include <GeomAdaptor_Surface.hxx>
#include <Geom_Line.hxx>
#include <gp.hxx>
#include <gp_Ax2.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <GeomConvert.hxx>
#include <Geom_CylindricalSurface.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <GeomAPI_PointsToBSpline.hxx>
#include <GeomAPI_PointsToBSplineSurface.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <gp_Ax1.hxx>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace kintsugi {
namespace {

using io::CadFormat;

// A closed planar profile in z = 0: a B-spline arc through four points, closed by a line.
TopoDS_Face profile() {
  TColgp_Array1OfPnt pts(1, 4);
  pts(1) = gp_Pnt(2, 0, 0);
  pts(2) = gp_Pnt(3, 1.5, 0);
  pts(3) = gp_Pnt(2.5, 3, 0);
  pts(4) = gp_Pnt(2, 4, 0);
  Handle(Geom_BSplineCurve) c = GeomAPI_PointsToBSpline(pts).Curve();
  TopoDS_Edge arc = BRepBuilderAPI_MakeEdge(c);
  TopoDS_Edge back = BRepBuilderAPI_MakeEdge(gp_Pnt(2, 4, 0), gp_Pnt(2, 0, 0));
  return BRepBuilderAPI_MakeFace(BRepBuilderAPI_MakeWire(arc, back).Wire());
}

TopoDS_Shape prism() { return BRepPrimAPI_MakePrism(profile(), gp_Vec(0, 0, 5)).Shape(); }
// Turned about the y axis (the profile is at x >= 2, away from it).
TopoDS_Shape revolved() { return BRepPrimAPI_MakeRevol(profile(), gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(0, 1, 0))).Shape(); }

Body read(const TopoDS_Shape& s, const std::string& name) {
  std::string path = test::temp_path(name + ".brep"), err;
  EXPECT_TRUE(BRepTools::Write(s, path.c_str()));
  std::optional<io::CadImport> in = io::import_cad(path, CadFormat::brep, &err);
  if (!in) {
    ADD_FAILURE() << err;
    return Body{};
  }
  return std::move(in->body);
}

int count_freeform_faces(const Body& b) {
  int n = 0;
  for (FaceH f : b.faces()) n += geo::is_freeform(b.surface(f));
  return n;
}

void expect_valid(const Body& b, const std::string& name) {
  for (const Violation& v : check_topology(b)) ADD_FAILURE() << name << ": " << to_string(v);
  GeometryReport g = check_geometry(b, 1e-7);
  for (const Violation& v : g.violations) ADD_FAILURE() << name << ": " << to_string(v);
  geo::Tolerances tol = geo::Tolerances::for_model(1e-3 * model_size(b), model_size(b));
  for (const Violation& v : region_violations(b, whole_body(b), tol, 1e-7)) ADD_FAILURE() << name << ": " << to_string(v);
  io::OcctVerdict o = io::occt_check(b);
  EXPECT_TRUE(o.valid) << name << ": " << (o.problems.empty() ? "" : o.problems.front());
}

// A Ceres residual "point on a fixed free-form surface" follows its foot from the last
// evaluation (Gauss-Newton) instead of projecting globally every time: along a path of
// points off the prism's B-spline side (as a solve's iterates move), its distance is the
// global projection's.
TEST(FreeForm, FollowedFootGivesTheGlobalDistance) {
  Body b = read(prism(), "follow_prism");
  FaceH side;
  for (FaceH f : b.faces())
    if (geo::is_freeform(b.surface(f))) side = f;
  ASSERT_TRUE(side.valid());
  const geo::Surface& s = b.surface(side);
  const double w = 1.0;
  geo::OnFixedSurface residual(s, &w);
  // Points 0.05-0.3 off the side, walking along it in small steps, then jumping back.
  int compared = 0;
  for (int k = 0; k <= 60; ++k) {
    const double t = k <= 40 ? k / 40.0 : (60 - k) / 20.0;
    const geo::Vec3 on = geo::evaluate(s, geo::Vec2(0.1 + 0.8 * t * 1.0, 0.5 + 4.0 * t));
    const geo::SurfacePoint at = geo::closest_point(s, on);
    const geo::Vec3 p = on + (0.05 + 0.25 * t) * at.normal;
    const double x[3] = {p.x(), p.y(), p.z()};
    const double* params[1] = {x};
    double r = 0, jac[3];
    double* jacs[1] = {jac};
    ASSERT_TRUE(residual.Evaluate(params, &r, jacs));
    const geo::SurfacePoint global = geo::closest_point(s, p);
    EXPECT_NEAR(r, global.distance, 1e-9) << "point " << k;
    EXPECT_NEAR(geo::Vec3(jac[0], jac[1], jac[2]).dot(global.normal), 1.0, 1e-9) << "point " << k;
    ++compared;
  }
  EXPECT_EQ(compared, 61);
}

// A B-spline through a 12 x 12 grid of the waves z = 0.8 sin x cos 0.7y over [0, 10]²,
// x moved by `shear` · y (so that S_u and S_v are not orthogonal when it is not 0).
Handle(Geom_BSplineSurface) wavy_patch(double shear) {
  TColgp_Array2OfPnt pts(1, 12, 1, 12);
  for (int i = 1; i <= 12; ++i)
    for (int j = 1; j <= 12; ++j) {
      const double x = (i - 1) * 10.0 / 11, y = (j - 1) * 10.0 / 11;
      pts(i, j) = gp_Pnt(x + shear * y, y, 0.8 * std::sin(x) * std::cos(0.7 * y));
    }
  return GeomAPI_PointsToBSplineSurface(pts).Surface();
}

// The backend keeps its last intersections (a repair tried again meets the same pair):
// asked again, a pair gets the same curves, and another pair never gets the first
// one's. Planes x = 3 and x = 6 across the wavy patch: each answer lies in its plane.
TEST(FreeForm, IntersectionsAskedAgainAreTheSame) {
  geo::occt::register_freeform_backend();
  const geo::Surface patch = geo::occt::bspline_data(wavy_patch(0.0));
  auto plane_at = [](double x) {
    geo::Plane p;
    p.frame.origin = geo::Vec3(x, 0, 0);
    p.frame.z = geo::Vec3::UnitX();
    p.frame.x = geo::Vec3::UnitY();
    return geo::Surface(p);
  };
  const auto& ff = geo::require_freeform();
  auto in_plane = [&](const std::vector<geo::Curve>& cs, double x) {
    double worst = 0;
    for (const geo::Curve& c : cs) {
      double t0 = 0, t1 = 1;  // a line's or circle's: any two points
      if (geo::is_freeform(c)) ff.curve_bounds(c, &t0, &t1);
      for (int i = 0; i <= 8; ++i) worst = std::max(worst, std::abs(geo::evaluate(c, t0 + (t1 - t0) * i / 8).x() - x));
    }
    return worst;
  };
  const std::vector<geo::Curve> at3 = ff.intersect(patch, plane_at(3), 1e-7, nullptr);
  const std::vector<geo::Curve> at6 = ff.intersect(patch, plane_at(6), 1e-7, nullptr);
  const std::vector<geo::Curve> at3_again = ff.intersect(patch, plane_at(3), 1e-7, nullptr);
  ASSERT_FALSE(at3.empty());
  ASSERT_FALSE(at6.empty());
  EXPECT_LT(in_plane(at3, 3), 1e-6);
  EXPECT_LT(in_plane(at6, 6), 1e-6);
  EXPECT_TRUE(at3_again == at3);
  // A copy of the patch's data (no shared cache) is the same surface.
  EXPECT_TRUE(ff.intersect(geo::occt::bspline_data(wavy_patch(0.0)), plane_at(6), 1e-7, nullptr) == at6);
}

// Near a known stretch (a marched branch's points, repair/beautify_geometry.cpp), the
// backend intersects only the surfaces' parameter windows around it: the curves it gives
// still run through the stretch and lie in the plane, and end within reach of it rather
// than cross the whole patch. The x = 3 plane across the wavy patch, near the stretch of
// the whole intersection with y in [4, 5]; the patch spans y in [0, 10].
TEST(FreeForm, IntersectionNearAStretchIsTheCurveThere) {
  geo::occt::register_freeform_backend();
  const geo::Surface patch = geo::occt::bspline_data(wavy_patch(0.0));
  geo::Plane plane;
  plane.frame.origin = geo::Vec3(3, 0, 0);
  plane.frame.z = geo::Vec3::UnitX();
  plane.frame.x = geo::Vec3::UnitY();
  const auto& ff = geo::require_freeform();
  const std::vector<geo::Curve> whole = ff.intersect(patch, plane, 1e-7, nullptr);
  ASSERT_EQ(whole.size(), 1u);
  double t0 = 0, t1 = 1;
  ff.curve_bounds(whole[0], &t0, &t1);
  std::vector<geo::Vec3> stretch;
  for (int i = 0; i <= 400; ++i) {
    const geo::Vec3 p = geo::evaluate(whole[0], t0 + (t1 - t0) * i / 400);
    if (p.y() >= 4 && p.y() <= 5) stretch.push_back(p);
  }
  ASSERT_GT(stretch.size(), 10u);
  const std::vector<geo::Curve> near = ff.intersect(patch, plane, 1e-7, &stretch);
  ASSERT_FALSE(near.empty());
  double y_min = HUGE_VAL, y_max = -HUGE_VAL, off_plane = 0;
  for (const geo::Curve& c : near) {
    double a = 0, b = 1;
    ff.curve_bounds(c, &a, &b);
    for (int i = 0; i <= 64; ++i) {
      const geo::Vec3 p = geo::evaluate(c, a + (b - a) * i / 64);
      y_min = std::min(y_min, p.y()), y_max = std::max(y_max, p.y());
      off_plane = std::max(off_plane, std::abs(p.x() - 3));
      EXPECT_LT(std::abs(geo::signed_distance(patch, p)), 1e-6);
    }
  }
  EXPECT_LT(off_plane, 1e-6);
  for (const geo::Vec3& p : stretch) {
    double nearest = HUGE_VAL;
    for (const geo::Curve& c : near) nearest = std::min(nearest, geo::closest_point(c, p).distance);
    EXPECT_LT(nearest, 1e-6);
  }
  EXPECT_LE(y_min, 4.0);
  EXPECT_GE(y_max, 5.0);
  EXPECT_GT(y_min, 1.0);  // not the whole patch's crossing
  EXPECT_LT(y_max, 9.0);
}

// A projection with no last foot to follow starts from a seed grid's local minima
// (geometry/occt/freeform_occt.cpp): on a wavy B-spline patch, for points on both sides of
// it, the nearest point found is never farther than OpenCASCADE's exhaustive extremum
// search finds, nor than the point's own offset along the normal.
TEST(FreeForm, ProjectionFindsTheGlobalFoot) {
  geo::occt::register_freeform_backend();
  Handle(Geom_BSplineSurface) patch = wavy_patch(0.0);
  const geo::Surface s = geo::occt::bspline_data(patch);
  double u0, u1, v0, v1;
  patch->Bounds(u0, u1, v0, v1);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int compared = 0;
  for (int k = 0; k < 400; ++k) {
    const geo::Vec2 uv(u0 + (u1 - u0) * (0.05 + 0.9 * unit(rng)), v0 + (v1 - v0) * (0.05 + 0.9 * unit(rng)));
    const double offset = -0.4 + 0.8 * unit(rng);
    const geo::Vec3 p = geo::evaluate(s, uv) + offset * geo::normal(s, uv);
    // A fresh copy of the data has no last foot to follow: the seeds are searched.
    const geo::Surface fresh = geo::occt::bspline_data(patch);
    const geo::SurfacePoint ours = geo::closest_point(fresh, p);
    EXPECT_LE(std::abs(ours.distance), std::abs(offset) + 1e-9) << "point " << k;
    GeomAPI_ProjectPointOnSurf occ(gp_Pnt(p.x(), p.y(), p.z()), patch);
    if (occ.NbPoints() == 0) continue;
    EXPECT_LE(std::abs(ours.distance), occ.LowerDistance() + 1e-9) << "point " << k;
    ++compared;
  }
  EXPECT_GT(compared, 300);
}

// Two places where Gauss-Newton from the seed grid used to stop short of the foot and
// leave the point to ValueOfUV's costly grid search (a third of beautify's time on
// OpenCASCADE's Top.brep): a point beyond a corner of the parameter domain, where the
// joint step, clamped, moved the free parameter by the share meant for the held one; and
// a point near a centre of curvature, where the distance hardly changes along the
// surface and Gauss-Newton, leaving out the curvature, crept a hundredth of the way per
// step. Both are now answered by the search itself, exactly.
TEST(FreeForm, ProjectionNeedsNoGridSearchAtCornersOrNearAnAxis) {
  geo::occt::register_freeform_backend();
  Handle(Geom_BSplineSurface) patch = wavy_patch(0.6);  // sheared: S_u . S_v != 0
  double u0, u1, v0, v1;
  patch->Bounds(u0, u1, v0, v1);
  int corners = 0;
  for (const double u : {u0, u1})
    for (const double v : {v0, v1})
      for (const double reach : {1e-6, 1e-3, 0.3}) {
        // Out of the domain along both parameters, and off the surface along its normal.
        gp_Pnt c;
        gp_Vec su, sv;
        patch->D1(u, v, c, su, sv);
        const gp_Vec out = (u == u0 ? -1.0 : 1.0) * su.Normalized() + (v == v0 ? -0.3 : 0.3) * sv.Normalized();
        const gp_Vec n = su.Crossed(sv).Normalized();
        const gp_Pnt p = c.Translated(reach * out + 0.5 * reach * n);
        const geo::Surface fresh = geo::occt::bspline_data(patch);
        const geo::Vec2 uv = geo::parameters(fresh, geo::Vec3(p.X(), p.Y(), p.Z()));
        // No point of the patch is nearer: its sides sampled densely (the nearest point
        // is on one of them, or the corner), and a grid inside.
        double nearest = std::numeric_limits<double>::infinity();
        for (int i = 0; i <= 4000; ++i) {
          const double a = u0 + (u1 - u0) * i / 4000, b = v0 + (v1 - v0) * i / 4000;
          for (const gp_Pnt& q : {patch->Value(a, v0), patch->Value(a, v1), patch->Value(u0, b), patch->Value(u1, b)})
            nearest = std::min(nearest, q.Distance(p));
        }
        for (int i = 1; i < 100; ++i)
          for (int j = 1; j < 100; ++j)
            nearest = std::min(nearest, patch->Value(u0 + (u1 - u0) * i / 100, v0 + (v1 - v0) * j / 100).Distance(p));
        const double ours = patch->Value(uv.x(), uv.y()).Distance(p);
        EXPECT_LE(ours, nearest + 1e-12) << "corner " << u << " " << v << " reach " << reach;
        EXPECT_GE(ours, 0.999 * nearest - 1e-12) << "corner " << u << " " << v << " reach " << reach;
        EXPECT_EQ(geo::occt::projection_counts(fresh).value_of_uv, 0) << "corner " << u << " " << v << " reach " << reach;
        ++corners;
      }
  EXPECT_EQ(corners, 12);
  // A quarter of a cylinder of radius 5 as a B-spline; points 0.3 off its axis, between
  // its ends and inside its angle: the foot is on the ray from the axis through the point.
  Handle(Geom_Surface) quarter =
      new Geom_RectangularTrimmedSurface(new Geom_CylindricalSurface(gp_Ax3(gp::XOY()), 5.0), 0.0, M_PI / 2, 0.0, 10.0);
  const Handle(Geom_BSplineSurface) cylinder = GeomConvert::SurfaceToBSplineSurface(quarter);
  for (int k = 0; k < 20; ++k) {
    const double angle = (0.1 + 0.8 * k / 19.0) * M_PI / 2, z = 1.0 + 8.0 * k / 19.0;
    const geo::Vec3 p(0.3 * std::cos(angle), 0.3 * std::sin(angle), z);
    const geo::Surface fresh = geo::occt::bspline_data(cylinder);
    const geo::SurfacePoint foot = geo::closest_point(fresh, p);
    EXPECT_NEAR(std::abs(foot.distance), 4.7, 1e-7) << "point " << k;
    EXPECT_EQ(geo::occt::projection_counts(fresh).value_of_uv, 0) << "point " << k;
  }
}

// A point far off a surface (a region solve that ran off: Motor-c.brep at 4x its
// tolerance projected points 1e10 to 1e68 away, 16 of 18 s in ValueOfUV's grid search).
// Beyond a thousand times the surface's extent the nearest seed answers: its distance is
// the least within a grid cell, a relative error below 1e-4 there, and no grid search.
TEST(FreeForm, AFarPointTakesTheNearestSeedWithoutAGridSearch) {
  geo::occt::register_freeform_backend();
  Handle(Geom_BSplineSurface) patch = wavy_patch(0.6);
  double u0, u1, v0, v1;
  patch->Bounds(u0, u1, v0, v1);
  Bnd_Box box;
  BndLib_AddSurface::Add(GeomAdaptor_Surface(patch), 0.0, box);
  const double extent = std::sqrt(box.SquareExtent());
  int far = 0;
  for (const double reach : {1e4, 1e8, 1e60})
    for (const gp_Dir d : {gp_Dir(1, 0, 0), gp_Dir(0, -1, 0), gp_Dir(0.3, 0.4, 1), gp_Dir(-1, 1, -1)}) {
      const gp_Pnt p = patch->Value(0.5 * (u0 + u1), 0.5 * (v0 + v1)).Translated(reach * extent * gp_Vec(d));
      const geo::Surface fresh = geo::occt::bspline_data(patch);
      const geo::Vec2 uv = geo::parameters(fresh, geo::Vec3(p.X(), p.Y(), p.Z()));
      ASSERT_TRUE(uv.x() >= u0 && uv.x() <= u1 && uv.y() >= v0 && uv.y() <= v1) << reach;
      double nearest = std::numeric_limits<double>::infinity();
      for (int i = 0; i <= 200; ++i)
        for (int j = 0; j <= 200; ++j)
          nearest = std::min(nearest, patch->Value(u0 + (u1 - u0) * i / 200, v0 + (v1 - v0) * j / 200).Distance(p));
      EXPECT_LE(patch->Value(uv.x(), uv.y()).Distance(p), nearest * (1 + 1e-4)) << "reach " << reach;
      const geo::occt::ProjectionCounts counts = geo::occt::projection_counts(fresh);
      EXPECT_EQ(counts.value_of_uv, 0) << "reach " << reach;
      far += counts.far > 0;
    }
  // Which of them the seed grid's Gauss-Newton answers by itself depends on rounding; on
  // this patch six do not (the reaches 1e4 and 1e8).
  EXPECT_GT(far, 0);
  // Ten extents away is not far: the search proper answers.
  const geo::Surface fresh = geo::occt::bspline_data(patch);
  const gp_Pnt p = patch->Value(u0, v0).Translated(10 * extent * gp_Vec(1, 1, 1));
  (void)geo::parameters(fresh, geo::Vec3(p.X(), p.Y(), p.Z()));
  EXPECT_EQ(geo::occt::projection_counts(fresh).far, 0);
}

// The largest distance between the surface along pcurve pc and the foot on it of curve
// c's point, over [t0, t1] (for a curve on the surface, the distance to the curve).
double pcurve_miss(const geo::Surface& s, const Handle(Geom_Surface)& gs, const Handle(Geom2d_Curve)& pc,
                   const Handle(Geom_Curve)& c, double t0, double t1) {
  double worst = 0;
  for (int i = 0; i <= 2000; ++i) {
    const double t = t0 + (t1 - t0) * i / 2000;
    const gp_Pnt2d uv = pc->Value(t);
    const gp_Pnt p = c->Value(t);
    const geo::Vec3 foot = geo::closest_point(s, geo::Vec3(p.X(), p.Y(), p.Z())).point;
    worst = std::max(worst, gs->Value(uv.X(), uv.Y()).Distance(gp_Pnt(foot.x(), foot.y(), foot.z())));
  }
  return worst;
}

// The writer's pcurves on free-form faces (io/occt/pcurve.h) follow the feet of their
// curves' points within `within` everywhere, not only where they were checked. A flat
// B-spline sheet whose parameter runs unevenly for a stretch a quarter of the way between
// two of the samples of a straight line along it: a check halfway between the samples
// alone let a pcurve 7e-4 off through (on OpenCASCADE's linkrods.step such pcurves made
// BRepCheck call three edges off their faces). The same line a little above the sheet is
// left to ShapeFix; 1e-3 above and starting past its bound, the feet's pcurve follows them
// as near as the line is to the sheet. A circle on a cylinder turned into
// a rational B-spline (its parameter is not the circle's angle) and a line along a
// surface of revolution whose meridian runs at an uneven speed get exact ones.
TEST(FreeForm, ProjectedPCurvesLieOnTheirCurves) {
  geo::occt::register_freeform_backend();
  const double within = 5e-8;
  // Cubic in x over [0, 8] in 64 even spans, the poles at the Greville abscissae (so x is
  // the parameter) but pole 3 moved by 0.001 along x: its basis function lives on
  // [0, 0.5] and peaks (2/3) at 0.25, where x runs ahead of the parameter by 6.7e-4 (the
  // sheet itself stays flat and x grows with the parameter); linear in y over [-1, 1].
  const int spans = 64, nu = spans + 3;
  TColgp_Array2OfPnt poles(1, nu, 1, 2);
  TColStd_Array1OfReal uknots(1, spans + 1), vknots(1, 2);
  TColStd_Array1OfInteger umults(1, spans + 1), vmults(1, 2);
  for (int k = 0; k <= spans; ++k) uknots(k + 1) = 8.0 * k / spans, umults(k + 1) = k == 0 || k == spans ? 4 : 1;
  vknots(1) = -1, vknots(2) = 1, vmults(1) = vmults(2) = 2;
  auto knot = [&](int i) { return 8.0 * std::clamp(i - 3, 0, spans) / spans; };  // the flat knot vector
  for (int k = 0; k < nu; ++k) {
    const double x = (knot(k + 1) + knot(k + 2) + knot(k + 3)) / 3 + (k == 3 ? 0.001 : 0.0);
    poles(k + 1, 1) = gp_Pnt(x, -1, 0);
    poles(k + 1, 2) = gp_Pnt(x, 1, 0);
  }
  Handle(Geom_BSplineSurface) sheet = new Geom_BSplineSurface(poles, uknots, vknots, umults, vmults, 3, 1);
  ASSERT_NEAR(sheet->Value(0.25, -1).X(), 0.25 + 0.002 / 3, 1e-9);
  const geo::Surface ours = geo::occt::bspline_data(sheet);
  // The writer's first sampling of a line is 9 points: 0, 1, ..., 8.
  Handle(Geom_Curve) line = new Geom_Line(gp_Pnt(0, -0.5, 0), gp_Dir(1, 0, 0));
  const Handle(Geom2d_Curve) along = io::occt::projected_pcurve(ours, sheet, line, 0.0, 8.0, within);
  ASSERT_FALSE(along.IsNull());
  EXPECT_LE(pcurve_miss(ours, sheet, along, line, 0.0, 8.0), within);
  // Near the sheet but not on it: ShapeFix's.
  Handle(Geom_Curve) near = new Geom_Line(gp_Pnt(0, -0.5, 3 * within), gp_Dir(1, 0, 0));
  EXPECT_TRUE(io::occt::projected_pcurve(ours, sheet, near, 0.0, 8.0, within).IsNull());
  // Clearly off (1e-3 above), and running 2e-3 past the sheet's bound x = 0, where its
  // feet stay on the bound: the pcurve follows the feet as near as the line is to the
  // sheet (its corner at x = 0 is 2e-3 after the line's start, closer than 8 / 1024).
  Handle(Geom_Curve) above = new Geom_Line(gp_Pnt(-2e-3, -0.5, 1e-3), gp_Dir(1, 0, 0));
  const Handle(Geom2d_Curve) over = io::occt::projected_pcurve(ours, sheet, above, 0.0, 8.002, within);
  ASSERT_FALSE(over.IsNull());
  EXPECT_LE(pcurve_miss(ours, sheet, over, above, 0.0, 8.002), std::hypot(2e-3, 1e-3));
  EXPECT_NEAR(over->Value(0.0).X(), 0.0, 1e-12);
  // Remembered (the validity gate writes the same edges again for each repair): asked
  // again, the same pcurve, as a copy of its own; the line above the sheet is not the
  // line on it, even though asked over the same parameters.
  const geo::Curve on_sheet = geo::Line{{0, -0.5, 0}, {1, 0, 0}}, off_sheet = geo::Line{{0, -0.5, 3 * within}, {1, 0, 0}};
  const Handle(Geom2d_Curve) first = io::occt::projected_pcurve_remembered(ours, on_sheet, sheet, line, 0.0, 8.0, within);
  const Handle(Geom2d_Curve) again = io::occt::projected_pcurve_remembered(ours, on_sheet, sheet, line, 0.0, 8.0, within);
  ASSERT_FALSE(first.IsNull());
  ASSERT_FALSE(again.IsNull());
  EXPECT_NE(first.get(), again.get());
  for (double t : {0.0, 0.3, 4.1, 8.0}) {
    EXPECT_NEAR(first->Value(t).X(), along->Value(t).X(), 1e-12);
    EXPECT_EQ(again->Value(t).X(), first->Value(t).X());
    EXPECT_EQ(again->Value(t).Y(), first->Value(t).Y());
  }
  EXPECT_TRUE(io::occt::projected_pcurve_remembered(ours, off_sheet, sheet, near, 0.0, 8.0, within).IsNull());

  Handle(Geom_Surface) quarter =
      new Geom_RectangularTrimmedSurface(new Geom_CylindricalSurface(gp_Ax3(gp::XOY()), 5.0), 0.0, M_PI / 2, 0.0, 10.0);
  const Handle(Geom_BSplineSurface) cylinder = GeomConvert::SurfaceToBSplineSurface(quarter);
  // Its u is not the angle: a pcurve that is a line in the angle is not one in u.
  const geo::Surface bcylinder = geo::occt::bspline_data(cylinder);
  ASSERT_GT(std::abs(geo::parameters(bcylinder, geo::Vec3(5 * std::cos(0.7), 5 * std::sin(0.7), 3)).x() - 0.7), 1e-3);
  Handle(Geom_Curve) circle = new Geom_Circle(gp_Ax2(gp_Pnt(0, 0, 3), gp::DZ()), 5.0);
  const Handle(Geom2d_Curve) around =
      io::occt::projected_pcurve(bcylinder, cylinder, circle, 0.1, 1.4, within);
  ASSERT_FALSE(around.IsNull());
  EXPECT_LE(pcurve_miss(bcylinder, cylinder, around, circle, 0.1, 1.4), within);

  TColgp_Array1OfPnt mpoles(1, 3);
  mpoles(1) = gp_Pnt(2, 0, 0), mpoles(2) = gp_Pnt(2.5, 0, 2), mpoles(3) = gp_Pnt(3, 0, 4);
  TColStd_Array1OfReal weights(1, 3), knots(1, 2);
  weights(1) = 1, weights(2) = 6, weights(3) = 1;
  knots(1) = 0, knots(2) = 1;
  TColStd_Array1OfInteger mults(1, 2);
  mults(1) = mults(2) = 3;
  const geo::Surface turned =
      geo::RevolutionSurface{geo::occt::bspline_data(new Geom_BSplineCurve(mpoles, weights, knots, mults, 2)),
                             geo::Vec3::Zero(), geo::Vec3::UnitZ(), nullptr};
  const Handle(Geom_Surface) gturned = geo::occt::geom_surface(turned);
  // The meridian turned by 0.3 radians, as a line parameterised by length.
  const gp_Pnt from(2 * std::cos(0.3), 2 * std::sin(0.3), 0), to(3 * std::cos(0.3), 3 * std::sin(0.3), 4);
  Handle(Geom_Curve) meridian = new Geom_Line(from, gp_Dir(gp_Vec(from, to)));
  const Handle(Geom2d_Curve) up_meridian =
      io::occt::projected_pcurve(turned, gturned, meridian, 0.0, from.Distance(to), within);
  ASSERT_FALSE(up_meridian.IsNull());
  EXPECT_LE(pcurve_miss(turned, gturned, up_meridian, meridian, 0.0, from.Distance(to)), within);
}

// A sheet only C1 across its double knots (the bicubic patches of OpenCASCADE's
// linkrods.step): the feet of a line across those knots turn there, and one C2
// interpolation through them closes in at a quarter of the miss per doubling (the line of
// linkrods still missed at 1025 samples). Made in pieces between the crossings, the pcurve
// lies on the line within `within` from a few samples per piece.
TEST(FreeForm, ProjectedPCurvesBreakWhereTheSurfaceIsLessSmooth) {
  geo::occt::register_freeform_backend();
  const double within = 5e-8;
  // x along v: a cubic with double knots at 1, ..., 7, its poles off the Greville
  // abscissae (where x would be v) by a little.
  const int spans = 8, nv = 2 * (spans - 1) + 4;
  TColgp_Array2OfPnt poles(1, 2, 1, nv);
  TColStd_Array1OfReal uknots(1, 2), vknots(1, spans + 1);
  TColStd_Array1OfInteger umults(1, 2), vmults(1, spans + 1);
  uknots(1) = -1, uknots(2) = 1, umults(1) = umults(2) = 2;
  for (int k = 0; k <= spans; ++k) vknots(k + 1) = k, vmults(k + 1) = k == 0 || k == spans ? 4 : 2;
  std::vector<double> flat;
  for (int k = 0; k <= spans; ++k) flat.insert(flat.end(), vmults(k + 1), double(k));
  for (int k = 0; k < nv; ++k) {
    const double x = (flat[k + 1] + flat[k + 2] + flat[k + 3]) / 3 + 0.02 * std::sin(1.7 * k);
    poles(1, k + 1) = gp_Pnt(x, -1, 0);
    poles(2, k + 1) = gp_Pnt(x, 1, 0);
  }
  Handle(Geom_BSplineSurface) sheet = new Geom_BSplineSurface(poles, uknots, vknots, umults, vmults, 1, 3);
  ASSERT_EQ(GeomAdaptor_Surface(sheet).NbVIntervals(GeomAbs_C2), spans);
  const geo::Surface ours = geo::occt::bspline_data(sheet);
  const double length = poles(1, nv).X() - poles(1, 1).X();
  Handle(Geom_Curve) line = new Geom_Line(gp_Pnt(poles(1, 1).X(), 0.25, 0), gp_Dir(1, 0, 0));
  const long before = geo::occt::projection_counts(ours).projections;
  const Handle(Geom2d_Curve) across = io::occt::projected_pcurve(ours, sheet, line, 0.0, length, within);
  const long projections = geo::occt::projection_counts(ours).projections - before;
  ASSERT_FALSE(across.IsNull());
  EXPECT_LE(pcurve_miss(ours, sheet, across, line, 0.0, length), within);
  // Eight pieces of 33 samples at most, their checks and the crossings' searches.
  EXPECT_LT(projections, 2000);
}

TEST(FreeForm, PrismOnABSplineProfileIsReadExactly) {
  Body b = read(prism(), "ff_prism");
  EXPECT_EQ(b.counts(), test::counts(4, 6, 4, 4));
  int extrusions = 0, bspline_edges = 0;
  for (FaceH f : b.faces()) extrusions += std::holds_alternative<geo::ExtrusionSurface>(b.surface(f));
  for (EdgeH e : b.edges()) bspline_edges += std::holds_alternative<geo::BSplineCurve>(b.curve(e));
  EXPECT_EQ(extrusions, 1);
  EXPECT_EQ(bspline_edges, 2);
  expect_valid(b, "prism");
}

TEST(FreeForm, SolidOfRevolutionIsReadExactly) {
  Body b = read(revolved(), "ff_revolved");
  int revolutions = 0;
  for (FaceH f : b.faces()) revolutions += std::holds_alternative<geo::RevolutionSurface>(b.surface(f));
  EXPECT_EQ(revolutions, 1);
  expect_valid(b, "revolved");
}

TEST(FreeForm, NativeFormatKeepsTheDataExactly) {
  for (const TopoDS_Shape& s : {prism(), revolved()}) {
    Body b = read(s, "ff_native");
    ASSERT_GT(count_freeform_faces(b), 0);
    std::string text = io::write_native(b);
    EXPECT_NE(text.find("bspline_curve"), std::string::npos);
    std::string err;
    std::optional<io::NativeDocument> back = io::read_native(text, &err);
    ASSERT_TRUE(back) << err;
    std::string why;
    EXPECT_TRUE(back->body.equals(b, &why)) << why;
    // Without the backend the reader refuses them, at the object, saying why.
    geo::set_freeform_backend(nullptr);
    std::optional<io::NativeDocument> refused = io::read_native(text, &err);
    geo::occt::register_freeform_backend();
    EXPECT_FALSE(refused);
    EXPECT_NE(err.find("needs OpenCASCADE"), std::string::npos) << err;
  }
}

TEST(FreeForm, CadFormatsRoundTrip) {
  for (CadFormat f : {CadFormat::brep, CadFormat::step, CadFormat::iges}) {
    Body b = read(prism(), "ff_cad");
    Body back = test::round_trip(b, f, "ff_round_trip");
    EXPECT_EQ(back.counts(), b.counts()) << int(f);
    EXPECT_EQ(count_freeform_faces(back), count_freeform_faces(b)) << int(f);
  }
}

TEST(FreeForm, TakesPartInDetectionAndComesThroughBeautifyUnchanged) {
  Body b = read(revolved(), "ff_beautify");
  const double size = model_size(b);
  // Areas of free-form faces are measured (a face measured 0 would be a small face).
  for (FaceH f : b.faces()) {
    std::optional<AreaAndBounds> a = face_area_and_bounds(b, f, 1e-4 * size);
    ASSERT_TRUE(a) << f.str();
    EXPECT_GT(a->area, 1e-2 * size * size) << f.str();
  }
  geo::Tolerances tol = geo::Tolerances::for_model(1e-4 * size, size);
  Detection d = detect(b, tol);
  for (const Problem& p : d.problems) EXPECT_EQ(p.type, ProblemType::mergeable_edges) << problem_name(p.type);
  const Body before = b;
  BeautifyReport r = beautify(b, tol);
  if (r.repaired() == 0) {
    std::string why;
    EXPECT_TRUE(b.equals(before, &why)) << why;
  }
  expect_valid(b, "after beautify");
}

}  // namespace
}  // namespace kintsugi
