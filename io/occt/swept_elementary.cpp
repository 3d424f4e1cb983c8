#include "io/occt/swept_elementary.h"

#include <Extrema_ExtPS.hxx>
#include <GeomAdaptor_Surface.hxx>
#include <Geom_Circle.hxx>
#include <Geom_ConicalSurface.hxx>
#include <Geom_CylindricalSurface.hxx>
#include <Geom_Line.hxx>
#include <Geom_Plane.hxx>
#include <Geom_SphericalSurface.hxx>
#include <Geom_SurfaceOfLinearExtrusion.hxx>
#include <Geom_SurfaceOfRevolution.hxx>
#include <Geom_ToroidalSurface.hxx>
#include <Geom_TrimmedCurve.hxx>
#include <Precision.hxx>
#include <Standard_Failure.hxx>
#include <gp_Ax3.hxx>
#include <gp_Circ.hxx>
#include <gp_Lin.hxx>

#include <algorithm>
#include <cmath>

namespace kintsugi::io::occt {

namespace {

Handle(Geom_Curve) untrimmed(Handle(Geom_Curve) c) {
  while (auto t = Handle(Geom_TrimmedCurve)::DownCast(c)) c = t->BasisCurve();
  return c;
}

// A frame with main direction d (its x direction any perpendicular: the surfaces below are
// round about d, so only the parametrisation depends on it).
gp_Ax3 frame_along(const gp_Pnt& o, const gp_Dir& d) { return gp_Ax3(o, d); }

// The candidate for a surface of revolution, from its basis curve and axis.
Handle(Geom_Surface) revolved(const Handle(Geom_Curve)& basis, const gp_Ax1& axis, double tol) {
  const gp_Pnt o = axis.Location();
  const gp_Dir d = axis.Direction();
  auto on_axis = [&](const gp_Pnt& p) { return o.Translated(gp_Vec(d) * gp_Vec(o, p).Dot(gp_Vec(d))); };
  if (auto circle = Handle(Geom_Circle)::DownCast(basis)) {
    const gp_Circ c = circle->Circ();
    const gp_Pnt centre = on_axis(c.Location());
    const double major = centre.Distance(c.Location());
    if (major <= tol) return new Geom_SphericalSurface(frame_along(centre, d), c.Radius());
    if (!(c.Radius() < major)) return nullptr;  // a spindle torus: not one kintsugi represents
    return new Geom_ToroidalSurface(frame_along(centre, d), major, c.Radius());
  }
  if (auto line = Handle(Geom_Line)::DownCast(basis)) {
    const gp_Lin l = line->Lin();
    const gp_Pnt q = l.Location();
    const gp_Pnt foot = on_axis(q);
    const double r = foot.Distance(q);
    const double along = l.Direction().Dot(d);  // cosine of the line's angle to the axis
    if (std::abs(along) < 1e-12) return new Geom_Plane(gp_Ax3(q, d));
    if (r <= tol) {
      // The line crosses the axis at q: the cone's apex. Any other point of it serves as
      // the reference circle's.
      const gp_Pnt p = q.Translated(gp_Vec(l.Direction()) * (1.0 / std::abs(along)));
      const gp_Pnt f = on_axis(p);
      const double rr = f.Distance(p), h = gp_Vec(q, f).Dot(gp_Vec(d));
      if (!(rr > tol)) return nullptr;  // the line is the axis
      return new Geom_ConicalSurface(frame_along(f, d), std::atan(rr / h), rr);
    }
    if (std::abs(std::abs(along) - 1) < 1e-12) return new Geom_CylindricalSurface(frame_along(foot, d), r);
    // A cone: the radius changes along the axis by tan(semi-angle) per unit.
    const gp_Vec radial = gp_Vec(foot, q) / r;
    const double semi = std::atan(gp_Vec(l.Direction()).Dot(radial) / along);
    if (!(std::abs(semi) < M_PI / 2 - 1e-9)) return nullptr;
    return new Geom_ConicalSurface(frame_along(foot, d), semi, r);
  }
  return nullptr;
}

Handle(Geom_Surface) extruded(const Handle(Geom_Curve)& basis, const gp_Dir& d) {
  if (auto circle = Handle(Geom_Circle)::DownCast(basis)) {
    const gp_Circ c = circle->Circ();
    return new Geom_CylindricalSurface(frame_along(c.Location(), d), c.Radius());
  }
  if (auto line = Handle(Geom_Line)::DownCast(basis)) {
    const gp_Lin l = line->Lin();
    const gp_Vec n = gp_Vec(l.Direction()).Crossed(gp_Vec(d));
    if (n.Magnitude() < 1e-12) return nullptr;
    return new Geom_Plane(gp_Ax3(l.Location(), gp_Dir(n)));
  }
  return nullptr;
}

}  // namespace

Handle(Geom_Surface) swept_elementary(const Handle(Geom_Surface)& s, double u0, double u1, double v0, double v1,
                                      double tol) {
  if (Precision::IsInfinite(u0) || Precision::IsInfinite(u1) || Precision::IsInfinite(v0) || Precision::IsInfinite(v1))
    return nullptr;
  try {
    Handle(Geom_Surface) candidate;
    if (auto r = Handle(Geom_SurfaceOfRevolution)::DownCast(s))
      candidate = revolved(untrimmed(r->BasisCurve()), r->Axis(), tol);
    else if (auto e = Handle(Geom_SurfaceOfLinearExtrusion)::DownCast(s))
      candidate = extruded(untrimmed(e->BasisCurve()), e->Direction());
    if (candidate.IsNull()) return nullptr;
    // The candidate is built from the basis curve alone; whether that curve lies in a
    // plane through the axis (a circle tilted out of it sweeps no torus) is settled by
    // measuring: every point of a grid over the face's part of `s` within tol of it.
    GeomAdaptor_Surface on(candidate);
    constexpr int kGrid = 9;
    for (int i = 0; i < kGrid; ++i)
      for (int j = 0; j < kGrid; ++j) {
        const gp_Pnt p = s->Value(u0 + (u1 - u0) * i / (kGrid - 1), v0 + (v1 - v0) * j / (kGrid - 1));
        Extrema_ExtPS ext(p, on, Precision::PConfusion(), Precision::PConfusion());
        if (!ext.IsDone() || ext.NbExt() == 0) return nullptr;
        double best = HUGE_VAL;
        for (int k = 1; k <= ext.NbExt(); ++k) best = std::min(best, ext.SquareDistance(k));
        if (!(std::sqrt(best) <= tol)) return nullptr;
      }
    return candidate;
  } catch (const Standard_Failure&) {
    return nullptr;
  }
}

}  // namespace kintsugi::io::occt
