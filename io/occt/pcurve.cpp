#include "io/occt/pcurve.h"

#include "geometry/surface.h"

#include <GeomAdaptor_Curve.hxx>
#include <Geom2dAPI_Interpolate.hxx>
#include <Geom2d_BSplineCurve.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_HArray1OfReal.hxx>
#include <TColgp_HArray1OfPnt2d.hxx>
#include <gp_Pnt2d.hxx>
#include <gp_Vec.hxx>

#include <algorithm>
#include <cmath>

namespace kintsugi::io::occt {
namespace {

// A curve farther than this many times `within` (half the edge's tolerance) from the
// surface at a sample is clearly off it (pcurve.h).
constexpr double kClearlyOff = 4;

}  // namespace

Handle(Geom2d_Curve) projected_pcurve(const geo::Surface& s, const Handle(Geom_Surface)& gs, const Handle(Geom_Curve)& c,
                                     double t0, double t1, double within) {
  const double up = gs->IsUPeriodic() ? gs->UPeriod() : 0, vp = gs->IsVPeriodic() ? gs->VPeriod() : 0;
  // The foot of the curve's point at t: its parameters `*x` (in the period of `near`,
  // when given) and the surface's point there `*on`. False at a degenerate point.
  auto foot = [&](double t, const gp_Pnt2d* near, gp_Pnt2d* x, gp_Pnt* on) {
    const gp_Pnt p = c->Value(t);
    const geo::Vec2 q = geo::parameters(s, geo::Vec3(p.X(), p.Y(), p.Z()));
    *x = gp_Pnt2d(q.x(), q.y());
    // Continued across the seam of a periodic surface, as the edge runs.
    if (near) {
      if (up > 0) x->SetX(x->X() - up * std::round((x->X() - near->X()) / up));
      if (vp > 0) x->SetY(x->Y() - vp * std::round((x->Y() - near->Y()) / vp));
    }
    gp_Vec du, dv;
    gs->D1(x->X(), x->Y(), *on, du, dv);
    return du.Magnitude() > 1e-12 && dv.Magnitude() > 1e-12 &&
           du.Crossed(dv).Magnitude() > 1e-12 * du.Magnitude() * dv.Magnitude();
  };
  gp_Pnt2d x;
  GeomAdaptor_Curve ad(c, t0, t1);
  const int spans = ad.NbIntervals(GeomAbs_C2);
  for (int n = std::clamp(4 * spans + 1, 9, 1025); n <= 1025; n = 2 * n - 1) {
    Handle(TColgp_HArray1OfPnt2d) uv = new TColgp_HArray1OfPnt2d(1, n);
    Handle(TColStd_HArray1OfReal) ts = new TColStd_HArray1OfReal(1, n);
    double off = 0;  // the samples' farthest distance from the surface
    for (int i = 0; i < n; ++i) {
      const double t = i + 1 == n ? t1 : t0 + (t1 - t0) * i / (n - 1);
      gp_Pnt on;
      if (!foot(t, i > 0 ? &uv->Value(i) : nullptr, &x, &on)) return nullptr;
      off = std::max(off, on.Distance(c->Value(t)));
      uv->SetValue(i + 1, x);
      ts->SetValue(i + 1, t);
    }
    // Near the surface but not on it: left to ShapeFix (its pcurves of such curves pass
    // BRepCheck on two edges of OpenCASCADE's Top.brep, 1.4e-7 off with a tolerance of
    // 1.7e-7, where the feet's did not).
    if (off > within && off <= kClearlyOff * within) return nullptr;
    const double image = std::max(off, within);
    Handle(Geom2d_BSplineCurve) pc;
    try {
      Geom2dAPI_Interpolate interpolate(uv, ts, Standard_False, 1e-12);
      interpolate.Perform();
      if (!interpolate.IsDone()) return nullptr;
      pc = interpolate.Curve();
    } catch (const Standard_Failure&) {
      return nullptr;
    }
    bool on = true;
    for (int i = 0; i + 1 < n && on; ++i)
      for (const double f : {0.25, 0.5, 0.75}) {
        const double t = (1 - f) * ts->Value(i + 1) + f * ts->Value(i + 2);
        gp_Pnt at;
        const gp_Pnt2d y = pc->Value(t);
        on = on && foot(t, &uv->Value(i + 1), &x, &at) && gs->Value(y.X(), y.Y()).Distance(at) <= image;
      }
    if (on) return pc;
  }
  return nullptr;
}

}  // namespace kintsugi::io::occt
