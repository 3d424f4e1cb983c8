// TopoDS_Shape -> Body (spec/exchange.md, "Import").
//
// Faces are read with their orientation composed down from the shape, so a face's
// wires, explored edge by edge, already run counter-clockwise about the face's outward
// normal: that order is our loop order. Degenerated edges (sphere poles, cone apexes)
// are dropped; a seam edge appears twice in its face's wire, once each way, and becomes
// one edge with both half-edges in that face's loop. Half-edges no face uses are free
// edges' far sides: they are linked into border cycles at the end.
#include "io/occt/convert.h"
#include "io/occt/swept_elementary.h"

#include "geometry/freeform.h"
#include "geometry/occt/freeform_occt.h"
#include "geometry/surface.h"
#include "geometry/types.h"
#include "invariants/assemble.h"

#include <BRepAdaptor_Curve.hxx>
#include <BRepLib.hxx>
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <GCPnts_QuasiUniformDeflection.hxx>
#include <Geom2d_BSplineCurve.hxx>
#include <Geom2d_BezierCurve.hxx>
#include <Geom2d_Curve.hxx>
#include <Geom2d_Line.hxx>
#include <Geom2d_TrimmedCurve.hxx>
#include <Extrema_GenLocateExtPS.hxx>
#include <GeomAdaptor_Curve.hxx>
#include <GeomAdaptor_Surface.hxx>
#include <GeomConvert.hxx>
#include <GeomLib_IsPlanarSurface.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_BezierCurve.hxx>
#include <Geom_BezierSurface.hxx>
#include <Geom_Circle.hxx>
#include <Geom_ConicalSurface.hxx>
#include <Geom_CylindricalSurface.hxx>
#include <Geom_ElementarySurface.hxx>
#include <Geom_Ellipse.hxx>
#include <Geom_Line.hxx>
#include <Geom_OffsetCurve.hxx>
#include <Geom_OffsetSurface.hxx>
#include <Geom_Plane.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <Geom_SphericalSurface.hxx>
#include <Geom_SurfaceOfLinearExtrusion.hxx>
#include <Geom_SurfaceOfRevolution.hxx>
#include <Geom_ToroidalSurface.hxx>
#include <Geom_TrimmedCurve.hxx>
#include <Precision.hxx>
#include <ShapeCustom_Surface.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Iterator.hxx>
#include <TopoDS_Vertex.hxx>
#include <TopoDS_Wire.hxx>
#include <gp_Ax3.hxx>
#include <gp_Circ.hxx>
#include <gp_Lin.hxx>
#include <gp_Pnt2d.hxx>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

namespace kintsugi::io::occt {

namespace {

using geo::Vec3;

Vec3 vec(const gp_XYZ& p) { return Vec3(p.X(), p.Y(), p.Z()); }
Vec3 vec(const gp_Pnt& p) { return vec(p.XYZ()); }
Vec3 vec(const gp_Dir& d) { return vec(d.XYZ()); }

// Our frame for an OpenCASCADE frame: same origin, x and axis; y = z × x. For a
// left-handed gp_Ax3 that flips y, which reverses the u-parameter and so the normal:
// `direct` reports whether OpenCASCADE's surface normal is ours.
geo::Frame frame(const gp_Ax3& a) { return geo::Frame{vec(a.Location()), vec(a.XDirection()), vec(a.Direction())}; }
geo::Frame frame(const gp_Ax2& a) { return geo::Frame{vec(a.Location()), vec(a.XDirection()), vec(a.Direction())}; }

struct Analytic {
  geo::Surface surface;
  bool normal_agrees = true;  // OpenCASCADE's surface normal is our surface's normal
};

// Elementary surfaces map one to one (spec/exchange.md).
std::optional<Analytic> elementary(const Handle(Geom_Surface)& s) {
  if (auto p = Handle(Geom_Plane)::DownCast(s)) {
    const gp_Ax3& a = p->Position();
    return Analytic{geo::Plane{frame(a)}, a.Direct()};
  }
  if (auto c = Handle(Geom_CylindricalSurface)::DownCast(s)) {
    const gp_Ax3& a = c->Position();
    return Analytic{geo::Cylinder{frame(a), c->Radius()}, a.Direct()};
  }
  if (auto c = Handle(Geom_ConicalSurface)::DownCast(s)) {
    const gp_Ax3& a = c->Position();
    return Analytic{geo::Cone{frame(a), c->RefRadius(), c->SemiAngle()}, a.Direct()};
  }
  if (auto sp = Handle(Geom_SphericalSurface)::DownCast(s)) {
    const gp_Ax3& a = sp->Position();
    return Analytic{geo::Sphere{frame(a), sp->Radius()}, a.Direct()};
  }
  if (auto t = Handle(Geom_ToroidalSurface)::DownCast(s)) {
    const gp_Ax3& a = t->Position();
    return Analytic{geo::Torus{frame(a), t->MajorRadius(), t->MinorRadius()}, a.Direct()};
  }
  return std::nullopt;
}

const char* occt_surface_name(const Handle(Geom_Surface)& s) {
  if (s->IsKind(STANDARD_TYPE(Geom_BSplineSurface))) return "B-spline surface";
  if (s->IsKind(STANDARD_TYPE(Geom_BezierSurface))) return "Bezier surface";
  if (s->IsKind(STANDARD_TYPE(Geom_SurfaceOfRevolution))) return "surface of revolution";
  if (s->IsKind(STANDARD_TYPE(Geom_SurfaceOfLinearExtrusion))) return "surface of linear extrusion";
  if (s->IsKind(STANDARD_TYPE(Geom_OffsetSurface))) return "offset surface";
  return s->DynamicType()->Name();
}

// A free-form surface as ours, exactly: B-spline (Bezier ones converted, exactly),
// revolution and extrusion with their basis curve as a B-spline (exact for conics; an
// unbounded basis line is trimmed to the face first), offset of a B-spline.
std::optional<geo::Surface> keep_freeform(const Handle(Geom_Surface)& s, const TopoDS_Face& face, std::string* why) {
  namespace ff = geo::occt;
  double u0, u1, v0, v1;
  BRepTools::UVBounds(face, u0, u1, v0, v1);
  auto basis_curve = [&](Handle(Geom_Curve) c, double f, double l) -> std::optional<geo::BSplineCurve> {
    if (Precision::IsInfinite(c->FirstParameter()) || Precision::IsInfinite(c->LastParameter())) {
      const double m = 0.1 * (l - f) + 1.0;
      c = new Geom_TrimmedCurve(c, f - m, l + m);
    }
    return ff::to_bspline(c, why);
  };
  try {
    if (auto b = Handle(Geom_BSplineSurface)::DownCast(s)) return geo::Surface(ff::bspline_data(b));
    if (s->IsKind(STANDARD_TYPE(Geom_BezierSurface))) {
      if (std::optional<geo::BSplineSurface> b = ff::to_bspline(s, why)) return geo::Surface(*b);
      return std::nullopt;
    }
    if (auto r = Handle(Geom_SurfaceOfRevolution)::DownCast(s)) {
      std::optional<geo::BSplineCurve> basis = basis_curve(r->BasisCurve(), v0, v1);
      if (!basis) return std::nullopt;
      const gp_Ax1 axis = r->Axis();
      return geo::Surface(geo::RevolutionSurface{*basis, vec(axis.Location()), vec(axis.Direction()), nullptr});
    }
    if (auto e = Handle(Geom_SurfaceOfLinearExtrusion)::DownCast(s)) {
      std::optional<geo::BSplineCurve> basis = basis_curve(e->BasisCurve(), u0, u1);
      if (!basis) return std::nullopt;
      return geo::Surface(geo::ExtrusionSurface{*basis, vec(e->Direction()), nullptr});
    }
    if (auto o = Handle(Geom_OffsetSurface)::DownCast(s)) {
      Handle(Geom_Surface) basis = o->BasisSurface();
      while (auto t = Handle(Geom_RectangularTrimmedSurface)::DownCast(basis)) basis = t->BasisSurface();
      std::optional<geo::BSplineSurface> b = ff::to_bspline(basis, why);
      if (!b) return std::nullopt;
      return geo::Surface(geo::OffsetSurface{*b, o->Offset(), nullptr});
    }
  } catch (const Standard_Failure& e) {
    *why = std::string("OpenCASCADE failed converting it: ") + e.GetMessageString();
    return std::nullopt;
  }
  *why = std::string(s->DynamicType()->Name()) + " is not a free-form type kintsugi keeps";
  return std::nullopt;
}

// The face's surface as ours, or the reason it cannot be (the surface type name, for
// the per-type count, and a sentence).
struct SurfaceResult {
  std::optional<Analytic> analytic;
  bool converted = false;  // a free-form surface recognised as analytic
  std::string type, why;
};

SurfaceResult face_surface(const TopoDS_Face& face) {
  SurfaceResult r;
  Handle(Geom_Surface) s = BRep_Tool::Surface(face);
  if (s.IsNull()) return r.type = "no surface", r.why = "the face has no surface", r;
  for (int guard = 0; guard < 16; ++guard) {
    if (auto t = Handle(Geom_RectangularTrimmedSurface)::DownCast(s)) {
      s = t->BasisSurface();
    } else if (auto o = Handle(Geom_OffsetSurface)::DownCast(s)) {
      Handle(Geom_Surface) eq = o->Surface();  // the equivalent non-offset surface, if analytic
      if (eq.IsNull()) break;
      s = eq;
    } else {
      break;
    }
  }
  // A self-intersecting (spindle) torus, minor radius not below the major one, is no
  // torus kintsugi represents (spec/file-format.md): kept as the B-spline it converts to.
  auto representable = [](const std::optional<Analytic>& a) {
    if (!a) return false;
    if (const auto* t = std::get_if<geo::Torus>(&a->surface)) return t->minor_radius < t->major_radius;
    return true;
  };
  if ((r.analytic = elementary(s)) && representable(r.analytic)) return r;
  const bool spindle = r.analytic.has_value();
  r.analytic.reset();
  // Free-form: planar, or analytic, within the face's precision.
  double tol = std::max(1e-6, BRep_Tool::Tolerance(face));
  r.type = occt_surface_name(s);
  // The face's parameter box, for the recognitions and the normal's comparison below.
  double u0, u1, v0, v1;
  BRepTools::UVBounds(face, u0, u1, v0, v1);
  Handle(Geom_Surface) freeform = s;
  Handle(Geom_Surface) ana = swept_elementary(s, u0, u1, v0, v1, tol);  // from the sweep's own data
  if (ana.IsNull() && !s->IsKind(STANDARD_TYPE(Geom_BSplineSurface)) && !s->IsKind(STANDARD_TYPE(Geom_BezierSurface))) {
    try {
      freeform = GeomConvert::SurfaceToBSplineSurface(new Geom_RectangularTrimmedSurface(s, u0, u1, v0, v1));
    } catch (const Standard_Failure&) {
      freeform.Nullify();
    }
  }
  if (ana.IsNull() && !freeform.IsNull()) {
    GeomLib_IsPlanarSurface planar(freeform, tol);
    if (planar.IsPlanar()) {
      ana = new Geom_Plane(planar.Plan());
    } else {
      ShapeCustom_Surface sc(freeform);
      ana = sc.ConvertToAnalytical(tol, Standard_False);
    }
  }
  if (!ana.IsNull()) r.analytic = elementary(ana);
  if (!representable(r.analytic)) r.analytic.reset();
  if (!r.analytic) {
    // Kept exactly as free-form (our normal is OpenCASCADE's: ∂P/∂u × ∂P/∂v).
    if (std::optional<geo::Surface> ff = keep_freeform(spindle && !freeform.IsNull() ? freeform : s, face, &r.why)) {
      // Built now, so that every copy of the surface shares the backend's object and its
      // projection state (geometry/freeform.h): built lazily on a copy, it would be
      // rebuilt for every copy.
      geo::require_freeform().surface_problem(*ff);
      r.analytic = Analytic{std::move(*ff), true};
      return r;
    }
    r.why = std::string(r.type) + " not within precision (" + std::to_string(tol) + ") of an analytic surface, and " + r.why;
    return r;
  }
  // The recognised surface's parametrisation is not the original's: compare the
  // original normal with ours at the middle of the face's parameter box.
  gp_Pnt p;
  gp_Vec du, dv;
  s->D1(0.5 * (u0 + u1), 0.5 * (v0 + v1), p, du, dv);
  Vec3 n0 = vec(du.Crossed(dv).XYZ());
  geo::SurfacePoint sp = geo::closest_point(r.analytic->surface, vec(p));
  r.analytic->normal_agrees = n0.dot(sp.normal) >= 0;
  r.converted = true;
  return r;
}

// An edge whose 3D curve is free-form but which runs along a parameter line of an
// elementary face it bounds (its pcurve keeps u or v constant) lies on that iso-curve,
// which is a line or a circle: the seams OpenCASCADE's ShapeFix adds to seamless
// periodic faces get B-spline 3D curves approximating exactly that. Accepted when points
// along the edge are on the iso-curve within the edge's tolerance (at least 1e-7); a
// circle is oriented to run the edge's way, so that the arc from the edge's first vertex
// to its last is the edge.
std::optional<geo::Curve> iso_curve(const TopoDS_Edge& forward, const std::vector<TopoDS_Face>& faces) {
  BRepAdaptor_Curve ad(forward);
  const double t0 = ad.FirstParameter(), t1 = ad.LastParameter();
  const double tol = std::max(1e-7, BRep_Tool::Tolerance(forward));
  for (const TopoDS_Face& face : faces) {
    double a = 0, b = 0;
    Handle(Geom2d_Curve) pc = BRep_Tool::CurveOnSurface(forward, face, a, b);
    if (pc.IsNull()) continue;
    while (auto t = Handle(Geom2d_TrimmedCurve)::DownCast(pc)) pc = t->BasisCurve();
    // The parameter line the pcurve runs along: a line parallel to an axis, or a
    // B-spline or Bezier curve whose poles all have the same u (or v).
    std::optional<std::pair<bool, double>> along;  // (u constant, the constant)
    if (auto line2d = Handle(Geom2d_Line)::DownCast(pc)) {
      const gp_Dir2d d = line2d->Direction();
      const gp_Pnt2d o = line2d->Location();
      if (std::abs(d.X()) < 1e-12)
        along = {true, o.X()};
      else if (std::abs(d.Y()) < 1e-12)
        along = {false, o.Y()};
    } else {
      std::vector<gp_Pnt2d> poles;
      if (auto bs = Handle(Geom2d_BSplineCurve)::DownCast(pc))
        for (int i = 1; i <= bs->NbPoles(); ++i) poles.push_back(bs->Pole(i));
      else if (auto bz = Handle(Geom2d_BezierCurve)::DownCast(pc))
        for (int i = 1; i <= bz->NbPoles(); ++i) poles.push_back(bz->Pole(i));
      if (poles.size() >= 2) {
        double u0 = poles[0].X(), v0 = poles[0].Y();
        bool same_u = true, same_v = true;
        for (const gp_Pnt2d& p : poles) {
          same_u = same_u && std::abs(p.X() - u0) <= 1e-9 * std::max(1.0, std::abs(u0));
          same_v = same_v && std::abs(p.Y() - v0) <= 1e-9 * std::max(1.0, std::abs(v0));
        }
        if (same_u != same_v) along = {same_u, same_u ? u0 : v0};
      }
    }
    if (!along) continue;
    Handle(Geom_Surface) s = BRep_Tool::Surface(face);
    while (auto t = Handle(Geom_RectangularTrimmedSurface)::DownCast(s)) s = t->BasisSurface();
    if (Handle(Geom_ElementarySurface)::DownCast(s).IsNull()) continue;
    Handle(Geom_Curve) iso;
    try {
      iso = along->first ? s->UIso(along->second) : s->VIso(along->second);
    } catch (const Standard_Failure&) {
      iso.Nullify();
    }
    if (iso.IsNull()) continue;
    while (auto t = Handle(Geom_TrimmedCurve)::DownCast(iso)) iso = t->BasisCurve();  // a sphere's meridians
    std::optional<geo::Curve> out;
    if (auto line = Handle(Geom_Line)::DownCast(iso)) {
      gp_Lin lin = line->Lin();
      bool on = true;
      for (int i = 0; i <= 8 && on; ++i) on = lin.Distance(ad.Value(t0 + (t1 - t0) * i / 8.0)) <= tol;
      if (on) out = geo::Line{vec(lin.Location()), vec(lin.Direction())};
    } else if (auto circ = Handle(Geom_Circle)::DownCast(iso)) {
      gp_Circ ci = circ->Circ();
      bool on = true;
      for (int i = 0; i <= 8 && on; ++i) on = ci.Distance(ad.Value(t0 + (t1 - t0) * i / 8.0)) <= tol;
      if (on) {
        // Run the edge's way: the circle's tangent at the edge's start along the edge's.
        gp_Pnt p;
        gp_Vec tangent;
        ad.D1(t0, p, tangent);
        gp_Vec radial(ci.Location(), p);
        gp_Vec circle_tangent = gp_Vec(ci.Axis().Direction()).Crossed(radial);
        if (circle_tangent.Dot(tangent) < 0)
          ci.SetPosition(gp_Ax2(ci.Location(), ci.Axis().Direction().Reversed(), ci.XAxis().Direction()));
        out = geo::Circle{frame(ci.Position()), ci.Radius()};
      }
    }
    if (out) return out;
  }
  return std::nullopt;
}

// A B-spline or Bezier edge curve whose poles are all within the edge's tolerance (at
// least 1e-7) of the line through its ends is that line: the curve lies in the convex
// hull of its poles (weights are positive). The straight seams ShapeFix adds on free-form
// faces (a cone written as a B-spline surface) are such curves.
//
// The line is written at 1e-7 (our bodies carry no tolerances), so on a curved face it
// must also lie on that face to 1e-7: a short section edge on a torus, straight within its
// boolean's tolerance (1e-5), read as a line left the torus by more than that and
// BRepCheck refused the written shape (fuzz_from_occt, 2026-12-03). Such an edge keeps its
// curve.
std::optional<geo::Curve> straight_curve(const TopoDS_Edge& forward, const Handle(Geom_Curve)& c, double f, double l,
                                         const std::vector<TopoDS_Face>& faces) {
  Handle(Geom_Curve) basis = c;
  while (auto t = Handle(Geom_TrimmedCurve)::DownCast(basis)) basis = t->BasisCurve();
  std::vector<gp_Pnt> poles;
  if (auto bs = Handle(Geom_BSplineCurve)::DownCast(basis)) {
    // Only the poles of the edge's part of the curve count: a copy cut to [f, l].
    Handle(Geom_BSplineCurve) cut = Handle(Geom_BSplineCurve)::DownCast(bs->Copy());
    if (f > cut->FirstParameter() || l < cut->LastParameter()) {
      try {
        cut->Segment(f, l);
      } catch (const Standard_Failure&) {
        return std::nullopt;
      }
    }
    for (int i = 1; i <= cut->NbPoles(); ++i) poles.push_back(cut->Pole(i));
  } else if (auto bz = Handle(Geom_BezierCurve)::DownCast(basis)) {
    if (f > bz->FirstParameter() || l < bz->LastParameter()) return std::nullopt;
    for (int i = 1; i <= bz->NbPoles(); ++i) poles.push_back(bz->Pole(i));
  } else {
    return std::nullopt;
  }
  gp_Pnt p0 = c->Value(f), p1 = c->Value(l);
  const double tol = std::max(1e-7, BRep_Tool::Tolerance(forward));
  if (p0.Distance(p1) <= 10 * tol) return std::nullopt;
  gp_Lin lin(p0, gp_Dir(gp_Vec(p0, p1)));
  for (const gp_Pnt& p : poles)
    if (lin.Distance(p) > tol) return std::nullopt;
  for (const TopoDS_Face& face : faces) {
    Handle(Geom_Surface) s = BRep_Tool::Surface(face);
    if (s.IsNull() || !Handle(Geom_Plane)::DownCast(s).IsNull()) continue;
    // A point of the surface within 1e-7 of the line's point is looked for first near the
    // edge's own pcurve (a local search from its point there): finding one settles it.
    // Only otherwise the global projection (on a B-spline face a grid search: measured,
    // a seventh of reading bearing.iges when done for every point).
    double a = 0, b = 0;
    const Handle(Geom2d_Curve) pc = BRep_Tool::CurveOnSurface(forward, face, a, b);
    const GeomAdaptor_Surface adaptor(s);
    for (double w : {0.25, 0.5, 0.75}) {
      const gp_Pnt q = p0.Translated(w * gp_Vec(p0, p1));
      if (!pc.IsNull()) {
        const gp_Pnt2d guess = pc->Value(a + w * (b - a));
        Extrema_GenLocateExtPS near(adaptor);
        near.Perform(q, guess.X(), guess.Y(), Standard_True);
        if (near.IsDone() && near.SquareDistance() <= 1e-14) continue;
      }
      GeomAPI_ProjectPointOnSurf on(q, s);
      if (on.NbPoints() == 0 || on.LowerDistance() > 1e-7) return std::nullopt;
    }
  }
  return geo::Line{vec(p0), vec(lin.Direction())};
}

// The distance from the curve's arc over [a, b] to the chord between its ends, at 7
// points inside.
double chord_deviation(const BRepAdaptor_Curve& ad, double a, double b) {
  const Vec3 p = vec(ad.Value(a)), q = vec(ad.Value(b)), d = q - p;
  const double dd = d.squaredNorm();
  double worst = 0;
  for (int k = 1; k < 8; ++k) {
    const Vec3 x = vec(ad.Value(a + (b - a) * k / 8.0));
    const double s = dd > 0 ? std::clamp((x - p).dot(d) / dd, 0.0, 1.0) : 0.0;
    worst = std::max(worst, (x - (p + s * d)).norm());
  }
  return worst;
}

// A polyline through the curve at `params`, each chord split at its middle parameter
// until it is within `deflection` of the curve (checked at 7 points): OpenCASCADE's
// GCPnts_QuasiUniformDeflection does not bound the deflection it is given (a fuzzed torus
// section came back 0.000511 from its curve for 0.000293, and the round trip then failed
// BRepCheck). chordal_error is the largest deviation measured, at least `deflection`;
// splitting stops at 2^12 pieces per chord or 2^16 points.
geo::Polyline polyline_within(const BRepAdaptor_Curve& ad, const std::vector<double>& params, double deflection) {
  geo::Polyline pl;
  pl.chordal_error = deflection;
  pl.points.push_back(vec(ad.Value(params.front())));
  struct Piece {
    double a, b;
    int depth;
  };
  for (std::size_t i = 1; i < params.size(); ++i) {
    std::vector<Piece> stack{{params[i - 1], params[i], 0}};  // last on top: pieces come out in order
    while (!stack.empty()) {
      Piece c = stack.back();
      stack.pop_back();
      double dev = chord_deviation(ad, c.a, c.b);
      if (dev > deflection && c.depth < 12 && pl.points.size() < (1u << 16)) {
        double m = 0.5 * (c.a + c.b);
        stack.push_back({m, c.b, c.depth + 1});
        stack.push_back({c.a, m, c.depth + 1});
        continue;
      }
      pl.chordal_error = std::max(pl.chordal_error, dev);
      pl.points.push_back(vec(ad.Value(c.b)));
    }
  }
  return pl;
}

// The edge's curve as ours, along the FORWARD edge (half-edge 2e); `faces` are the
// faces it bounds.
geo::Curve edge_curve(const TopoDS_Edge& forward, const std::vector<TopoDS_Face>& faces, int index,
                      std::vector<std::string>* warnings) {
  double f = 0, l = 0;
  Handle(Geom_Curve) c = BRep_Tool::Curve(forward, f, l);
  if (c.IsNull()) {
    BRepLib::BuildCurve3d(forward);
    c = BRep_Tool::Curve(forward, f, l);
  }
  if (!c.IsNull()) {
    Handle(Geom_Curve) basis = c;
    while (auto t = Handle(Geom_TrimmedCurve)::DownCast(basis)) basis = t->BasisCurve();
    if (auto line = Handle(Geom_Line)::DownCast(basis)) {
      const gp_Ax1& a = line->Position();
      return geo::Line{vec(a.Location()), vec(a.Direction())};
    }
    if (auto circ = Handle(Geom_Circle)::DownCast(basis))
      return geo::Circle{frame(circ->Position()), circ->Radius()};
    if (auto el = Handle(Geom_Ellipse)::DownCast(basis))
      return geo::Ellipse{frame(el->Position()), el->MajorRadius(), el->MinorRadius()};
  }
  if (std::optional<geo::Curve> iso = iso_curve(forward, faces)) {
    warnings->push_back("edge #" + std::to_string(index) + ": " +
                        (c.IsNull() ? std::string("no 3D curve") : std::string(c->DynamicType()->Name())) +
                        " recognised as a " + geo::curve_type_name(*iso) + " (a parameter line of its face)");
    return *iso;
  }
  if (!c.IsNull()) {
    if (std::optional<geo::Curve> line = straight_curve(forward, c, f, l, faces)) {
      warnings->push_back("edge #" + std::to_string(index) + ": " + c->DynamicType()->Name() +
                          " recognised as a line (its poles are on one)");
      return *line;
    }
  }
  // Anything else: the curve itself, exactly, as a B-spline (the edge's part of it).
  if (!c.IsNull()) {
    std::string why;
    Handle(Geom_Curve) part = c;
    if (f > c->FirstParameter() || l < c->LastParameter() || c->IsPeriodic()) {
      try {
        part = new Geom_TrimmedCurve(c, f, l);
      } catch (const Standard_Failure&) {
        part = c;
      }
    }
    if (std::optional<geo::BSplineCurve> b = geo::occt::to_bspline(part, &why)) {
      geo::Curve curve(std::move(*b));
      geo::require_freeform().curve_problem(curve);  // built now: see the surfaces
      return curve;
    }
  }
  // Failing that, a polyline within a chordal error proportional to the edge's size.
  BRepAdaptor_Curve ad(forward);
  double len = ad.Value(ad.FirstParameter()).Distance(ad.Value(0.5 * (ad.FirstParameter() + ad.LastParameter()))) +
               ad.Value(ad.LastParameter()).Distance(ad.Value(0.5 * (ad.FirstParameter() + ad.LastParameter())));
  double deflection = std::max(1e-7, 1e-5 * len);
  GCPnts_QuasiUniformDeflection sampler(ad, deflection);
  std::vector<double> params;
  if (sampler.IsDone() && sampler.NbPoints() >= 2) {
    for (int i = 1; i <= sampler.NbPoints(); ++i) params.push_back(sampler.Parameter(i));
  } else {
    for (int i = 0; i <= 64; ++i) params.push_back(ad.FirstParameter() + (ad.LastParameter() - ad.FirstParameter()) * i / 64.0);
  }
  geo::Polyline pl = polyline_within(ad, params, deflection);
  warnings->push_back("edge #" + std::to_string(index) + ": " +
                      (c.IsNull() ? std::string("no 3D curve") : std::string(c->DynamicType()->Name())) +
                      " sampled as a polyline of " + std::to_string(pl.points.size()) + " points (chordal error " +
                      std::to_string(pl.chordal_error) + ")");
  return pl;
}

struct UnionFind {
  std::vector<std::uint32_t> p;
  explicit UnionFind(std::size_t n) : p(n) { std::iota(p.begin(), p.end(), 0u); }
  std::uint32_t find(std::uint32_t x) {
    while (p[x] != x) x = p[x] = p[p[x]];
    return x;
  }
  void unite(std::uint32_t a, std::uint32_t b) { p[find(a)] = find(b); }
};

constexpr std::uint32_t kNone = ~std::uint32_t{0};

}  // namespace

std::optional<Body> from_shape(const TopoDS_Shape& shape, const FaceLocator& locate, std::vector<std::string>* warnings,
                               std::string* error) {
  // Free-form faces need the backend (geometry/freeform.h): whoever converts a shape gets it.
  geo::occt::register_freeform_backend();
  std::vector<std::string> local_warnings;
  if (!warnings) warnings = &local_warnings;
  std::string local_error;
  if (!error) error = &local_error;
  if (shape.IsNull()) return *error = "no shape", std::nullopt;

  // Faces once each, with their orientation composed from the shape down.
  TopTools_IndexedMapOfShape face_map;
  std::vector<TopoDS_Face> faces;
  for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next()) {
    if (face_map.Contains(ex.Current())) {
      warnings->push_back(locate(ex.Current(), face_map.FindIndex(ex.Current())) +
                          ": appears twice in the shape; read once");
      continue;
    }
    face_map.Add(ex.Current());
    faces.push_back(TopoDS::Face(ex.Current()));
  }
  if (faces.empty()) return *error = "the shape has no faces (only wires, edges or vertices)", std::nullopt;

  // Surfaces first: every unsupported face is reported, counted per type.
  std::vector<Analytic> surf(faces.size());
  std::map<std::string, int> refused_count;
  std::vector<std::string> refused;
  for (std::size_t i = 0; i < faces.size(); ++i) {
    SurfaceResult r = face_surface(faces[i]);
    if (!r.analytic) {
      refused_count[r.type]++;
      refused.push_back(locate(faces[i], int(i + 1)) + ": " + r.why);
      continue;
    }
    surf[i] = *r.analytic;
    if (r.converted)
      warnings->push_back(locate(faces[i], int(i + 1)) + ": " + r.type + " recognised as a " +
                          geo::surface_type_name(r.analytic->surface));
  }
  if (!refused.empty()) {
    std::string msg = std::to_string(refused.size()) + " of " + std::to_string(faces.size()) +
                      " faces are on surfaces kintsugi cannot represent (";
    bool first = true;
    for (const auto& [type, n] : refused_count) {
      msg += (first ? "" : ", ") + std::to_string(n) + " " + type;
      first = false;
    }
    msg += "):";
    for (const std::string& r : refused) msg += "\n  " + r;
    *error = msg;
    return std::nullopt;
  }

  // Vertices and edges, numbered as met; degenerated edges are not ours.
  TopTools_IndexedMapOfShape vertex_map, edge_map;
  std::vector<std::uint32_t> edge_from, edge_to;  // vertex ids of the FORWARD edge
  auto vertex_id = [&](const TopoDS_Vertex& v) { return std::uint32_t(vertex_map.Add(v) - 1); };
  auto edge_id = [&](const TopoDS_Edge& e) {
    int before = edge_map.Extent();
    int i = edge_map.Add(e);
    if (i > before) {
      TopoDS_Edge fwd = TopoDS::Edge(e.Oriented(TopAbs_FORWARD));
      TopoDS_Vertex a, b;
      TopExp::Vertices(fwd, a, b);
      edge_from.push_back(vertex_id(a));
      edge_to.push_back(vertex_id(b));
    }
    return std::uint32_t(i - 1);
  };

  struct LoopBuild {
    std::uint32_t face;
    std::vector<std::uint32_t> hes;  // half-edge ids in order
    std::uint32_t lone = kNone;
  };
  std::vector<LoopBuild> loops;
  std::vector<std::vector<std::uint32_t>> face_loops(faces.size());
  for (std::size_t fi = 0; fi < faces.size(); ++fi) {
    const TopoDS_Face& face = faces[fi];
    TopoDS_Wire outer = BRepTools::OuterWire(face);
    std::vector<TopoDS_Wire> wires;
    for (TopExp_Explorer ex(face, TopAbs_WIRE); ex.More(); ex.Next()) {
      TopoDS_Wire w = TopoDS::Wire(ex.Current());
      if (w.Orientation() == TopAbs_INTERNAL || w.Orientation() == TopAbs_EXTERNAL) {
        warnings->push_back(locate(face, int(fi + 1)) + ": an internal wire is ignored");
        continue;
      }
      if (!outer.IsNull() && w.IsSame(outer))
        wires.insert(wires.begin(), w);
      else
        wires.push_back(w);
    }
    if (wires.empty()) {
      *error = locate(face, int(fi + 1)) + ": has no boundary (an unbounded face)";
      return std::nullopt;
    }
    for (const TopoDS_Wire& w : wires) {
      // The wire's edges with orientations composed from the face down, put in
      // traversal order: each next edge starts at the vertex where the last ended and,
      // among several such (a vertex visited twice, closed edges, seams), where it ended
      // in the face's parameter plane. The stored order is not always the traversal
      // order (OpenCASCADE's torus), and BRepTools_WireExplorer reports closed edges
      // FORWARD whatever their orientation, so neither is used as is.
      struct Use {
        TopoDS_Edge edge;
        bool degenerated;
        std::uint32_t from, to;  // vertex ids along the traversal
        gp_Pnt2d uv_from, uv_to;
        bool has_uv;
      };
      std::vector<Use> uses;
      for (TopoDS_Iterator it(w); it.More(); it.Next()) {
        TopoDS_Edge e = TopoDS::Edge(it.Value());
        TopAbs_Orientation o = e.Orientation();
        if (o != TopAbs_FORWARD && o != TopAbs_REVERSED) {
          *error = locate(face, int(fi + 1)) + ": has an internal or external edge (a slit), which kintsugi does not read";
          return std::nullopt;
        }
        Use u{e, BRep_Tool::Degenerated(e) == Standard_True, 0, 0, {}, {}, false};
        u.from = vertex_id(TopExp::FirstVertex(e, Standard_True));
        u.to = vertex_id(TopExp::LastVertex(e, Standard_True));
        double a = 0, b = 0;
        Handle(Geom2d_Curve) pc = BRep_Tool::CurveOnSurface(e, face, a, b);
        if (!pc.IsNull()) {
          u.uv_from = pc->Value(o == TopAbs_FORWARD ? a : b);
          u.uv_to = pc->Value(o == TopAbs_FORWARD ? b : a);
          u.has_uv = true;
        }
        uses.push_back(u);
      }
      // Depth first: at each vertex the candidates nearest in the parameter plane first,
      // the others when that one leads to a dead end (a seam's two uses and a closed edge
      // at one vertex: the nearest by pcurve can be the seam's other use a period away,
      // when a pcurve sits a period off; a beautified sink at four times its tolerance).
      // Iterative (a wire may have many edges) and bounded (kMaxSteps choices tried).
      std::vector<std::size_t> order;
      std::vector<std::uint8_t> used(uses.size(), 0);
      std::vector<std::vector<std::size_t>> choices;  // per position after the first: candidates left, best last
      auto candidates = [&](std::size_t at) {
        const Use& cur = uses[at];
        std::vector<std::pair<double, std::size_t>> next;
        for (std::size_t k = 0; k < uses.size(); ++k)
          if (!used[k] && uses[k].from == cur.to)
            next.push_back({(cur.has_uv && uses[k].has_uv) ? cur.uv_to.Distance(uses[k].uv_from) : 0.0, k});
        // Taken from the back: nearest first, and among equals the first in the wire (as
        // the greedy chaining before took them).
        std::sort(next.begin(), next.end(), [](const auto& x, const auto& y) {
          return x.first != y.first ? x.first > y.first : x.second > y.second;
        });
        std::vector<std::size_t> out;
        for (const auto& n : next) out.push_back(n.second);
        return out;
      };
      std::size_t longest = uses.empty() ? 0 : 1, steps = 0;
      constexpr std::size_t kMaxSteps = 100000;
      bool chained = uses.empty();
      if (!uses.empty()) {
        order.push_back(0);
        used[0] = 1;
        choices.push_back(candidates(0));
        while (!choices.empty() && steps < kMaxSteps) {
          if (order.size() == uses.size()) {
            if (uses[order.back()].to == uses[order.front()].from) {
              chained = true;
              break;
            }
          } else if (!choices.back().empty()) {
            const std::size_t k = choices.back().back();
            choices.back().pop_back();
            ++steps;
            used[k] = 1;
            order.push_back(k);
            longest = std::max(longest, order.size());
            choices.push_back(candidates(k));
            continue;
          }
          // A dead end (or a full chain that does not close): back one edge.
          choices.pop_back();
          if (order.size() > 1) {
            used[order.back()] = 0;
            order.pop_back();
          } else {
            break;
          }
        }
      }
      if (!chained) {
        *error = locate(face, int(fi + 1)) + ": a wire is not one connected cycle of edges (" +
                 std::to_string(longest) + " of its " + std::to_string(uses.size()) + " edges chain up)";
        return std::nullopt;
      }
      LoopBuild lb{std::uint32_t(fi), {}, kNone};
      TopoDS_Vertex degenerate_vertex;
      for (std::size_t k : order) {
        const Use& u = uses[k];
        if (u.degenerated) {
          degenerate_vertex = TopExp::FirstVertex(u.edge);
          continue;
        }
        std::uint32_t id = edge_id(u.edge);
        lb.hes.push_back(2 * id + (u.edge.Orientation() == TopAbs_FORWARD ? 0u : 1u));
      }
      if (lb.hes.empty()) {
        if (degenerate_vertex.IsNull()) continue;  // an empty wire
        lb.lone = vertex_id(degenerate_vertex);
      }
      face_loops[fi].push_back(std::uint32_t(loops.size()));
      loops.push_back(std::move(lb));
    }
    if (face_loops[fi].empty()) {
      *error = locate(face, int(fi + 1)) + ": has no boundary edges";
      return std::nullopt;
    }
  }

  // Half-edge incidences.
  const std::size_t ne = std::size_t(edge_map.Extent());
  std::vector<std::uint32_t> he_origin(2 * ne), he_next(2 * ne, kNone), he_prev(2 * ne, kNone), he_loop(2 * ne, kNone);
  for (std::size_t e = 0; e < ne; ++e) {
    he_origin[2 * e] = edge_from[e];
    he_origin[2 * e + 1] = edge_to[e];
  }
  auto target = [&](std::uint32_t h) { return he_origin[h ^ 1u]; };
  for (std::uint32_t li = 0; li < loops.size(); ++li) {
    const LoopBuild& lb = loops[li];
    for (std::size_t k = 0; k < lb.hes.size(); ++k) {
      std::uint32_t h = lb.hes[k], n = lb.hes[(k + 1) % lb.hes.size()];
      if (he_loop[h] != kNone) {
        std::uint32_t other = loops[he_loop[h]].face;
        bool twin_used = he_loop[h ^ 1u] != kNone;
        *error = "edge #" + std::to_string(h / 2 + 1) + " is used " + (twin_used ? "by more than two faces (non-manifold)" : "twice in the same direction (inconsistent orientation)") +
                 ": " + locate(faces[other], int(other + 1)) + " and " + locate(faces[lb.face], int(lb.face + 1));
        return std::nullopt;
      }
      if (target(h) != he_origin[n]) {
        *error = locate(faces[lb.face], int(lb.face + 1)) + ": a wire does not close up (edge #" +
                 std::to_string(h / 2 + 1) + " ends where the next edge does not start)";
        return std::nullopt;
      }
      he_loop[h] = li;
      he_next[h] = n;
      he_prev[n] = h;
    }
  }

  // Free edges: link the unused half-edges into border cycles. A border half-edge h
  // ends at v; its successor is the next border half-edge leaving v in v's rotation,
  // found by turning from twin(h) through the faces around v (g -> twin(prev(g))).
  std::vector<std::uint32_t> border_next(2 * ne, kNone);
  for (std::uint32_t h = 0; h < 2 * ne; ++h) {
    if (he_loop[h] != kNone) continue;
    if (he_loop[h ^ 1u] == kNone) {
      *error = "edge #" + std::to_string(h / 2 + 1) + " belongs to no face";
      return std::nullopt;
    }
    std::uint32_t g = h ^ 1u;
    std::size_t steps = 0;
    while (he_loop[g] != kNone && steps++ <= 2 * ne) g = he_prev[g] ^ 1u;
    if (he_loop[g] != kNone) {
      *error = "the faces around vertex #" + std::to_string(target(h) + 1) + " do not form a fan (free edges cannot be followed)";
      return std::nullopt;
    }
    border_next[h] = g;
  }
  std::vector<std::uint32_t> border_of(2 * ne, kNone);
  std::size_t border_start = loops.size();
  for (std::uint32_t h = 0; h < 2 * ne; ++h) {
    if (border_next[h] == kNone || border_of[h] != kNone) continue;
    LoopBuild lb{kNone, {}, kNone};
    std::uint32_t li = std::uint32_t(loops.size());
    for (std::uint32_t g = h; border_of[g] == kNone; g = border_next[g]) {
      border_of[g] = li;
      lb.hes.push_back(g);
    }
    if (lb.hes.front() != border_next[lb.hes.back()]) {
      *error = "free edges around edge #" + std::to_string(h / 2 + 1) + " do not close into a cycle";
      return std::nullopt;
    }
    for (std::size_t k = 0; k < lb.hes.size(); ++k) {
      he_loop[lb.hes[k]] = li;
      he_next[lb.hes[k]] = lb.hes[(k + 1) % lb.hes.size()];
    }
    loops.push_back(std::move(lb));
  }
  if (loops.size() > border_start)
    warnings->push_back(std::to_string(loops.size() - border_start) + " border cycle(s) of free edges: the shell is open");

  // Shells: faces connected across edges.
  UnionFind uf(faces.size());
  for (std::size_t e = 0; e < ne; ++e) {
    std::uint32_t a = loops[he_loop[2 * e]].face, b = loops[he_loop[2 * e + 1]].face;
    if (a != kNone && b != kNone) uf.unite(a, b);
  }
  std::map<std::uint32_t, std::uint32_t> shell_of_root;
  std::vector<std::uint32_t> face_shell(faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f) {
    auto [it, inserted] = shell_of_root.emplace(uf.find(std::uint32_t(f)), std::uint32_t(shell_of_root.size()));
    face_shell[f] = it->second;
  }
  auto loop_shell = [&](std::uint32_t li) {
    const LoopBuild& lb = loops[li];
    if (lb.face != kNone) return face_shell[lb.face];
    return face_shell[loops[he_loop[lb.hes.front() ^ 1u]].face];
  };

  // Genus per shell from Euler–Poincaré: V − E + F + B − R = 2(1 − g).
  const std::size_t ns = shell_of_root.size();
  std::vector<long> chi(ns, 0);
  std::vector<std::uint32_t> vertex_shell(std::size_t(vertex_map.Extent()), kNone);
  for (std::size_t e = 0; e < ne; ++e) {
    std::uint32_t s = loop_shell(he_loop[2 * e]);
    chi[s] -= 1;
    vertex_shell[edge_from[e]] = vertex_shell[edge_to[e]] = s;
  }
  for (std::uint32_t li = 0; li < loops.size(); ++li) {
    if (loops[li].lone != kNone) vertex_shell[loops[li].lone] = loop_shell(li);
    if (loops[li].face == kNone) chi[loop_shell(li)] += 1;
  }
  for (std::uint32_t s : vertex_shell)
    if (s != kNone) chi[s] += 1;
  for (std::size_t f = 0; f < faces.size(); ++f) chi[face_shell[f]] += 1 - long(face_loops[f].size() - 1);
  std::vector<std::uint32_t> genus(ns, 0);
  for (std::size_t s = 0; s < ns; ++s) {
    if (chi[s] > 2 || chi[s] % 2 != 0) {
      *error = "shell " + std::to_string(s + 1) + " has Euler characteristic " + std::to_string(chi[s]) +
               ", which no orientable surface has (inconsistent topology)";
      return std::nullopt;
    }
    genus[s] = std::uint32_t(1 - chi[s] / 2);
  }

  // Describe and assemble (which runs the full topology check).
  BodyDescription d;
  for (std::size_t v = 0; v < vertex_shell.size(); ++v) {
    if (vertex_shell[v] == kNone) continue;  // only on degenerated edges
    d.vertices.push_back({std::uint32_t(v), vec(BRep_Tool::Pnt(TopoDS::Vertex(vertex_map(int(v + 1)))))});
  }
  for (std::size_t e = 0; e < ne; ++e) {
    EdgeDesc ed;
    ed.id = std::uint32_t(e);
    for (int side = 0; side < 2; ++side) {
      std::uint32_t h = std::uint32_t(2 * e + side);
      ed.he[side] = {he_origin[h], he_next[h], he_loop[h]};
    }
    std::vector<TopoDS_Face> beside;
    for (int side = 0; side < 2; ++side)
      if (std::uint32_t lf = loops[he_loop[2 * e + side]].face; lf != kNone) beside.push_back(faces[lf]);
    ed.curve = edge_curve(TopoDS::Edge(edge_map(int(e + 1)).Oriented(TopAbs_FORWARD)), beside, int(e + 1), warnings);
    d.edges.push_back(std::move(ed));
  }
  for (std::uint32_t li = 0; li < loops.size(); ++li) {
    LoopDesc ld;
    ld.id = li;
    if (loops[li].face != kNone) ld.face = loops[li].face;
    if (loops[li].lone != kNone)
      ld.lone = loops[li].lone;
    else
      ld.first = loops[li].hes.front();
    d.loops.push_back(ld);
  }
  for (std::size_t f = 0; f < faces.size(); ++f) {
    FaceDesc fd;
    fd.id = std::uint32_t(f);
    fd.shell = face_shell[f];
    fd.loops = face_loops[f];
    fd.surface = surf[f].surface;
    // Outward normal = OpenCASCADE's surface normal for a FORWARD face, its opposite for a
    // REVERSED one; ours agrees with OpenCASCADE's or not (left-handed frames).
    bool forward = faces[f].Orientation() == TopAbs_FORWARD;
    fd.same_sense = forward == surf[f].normal_agrees;
    d.faces.push_back(std::move(fd));
  }
  for (std::size_t s = 0; s < ns; ++s) d.shells.push_back({std::uint32_t(s), genus[s]});
  AssembleError ae;
  std::optional<Body> body = assemble(std::move(d), &ae);
  if (!body) {
    *error = "the topology read is inconsistent: " + (ae.element.empty() ? "" : ae.element + ": ") + ae.message;
    return std::nullopt;
  }
  return body;
}

}  // namespace kintsugi::io::occt
