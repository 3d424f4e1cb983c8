#include "io/occt/pcurve.h"

#include "geometry/occt/freeform_occt.h"
#include "geometry/recent_answers.h"
#include "geometry/surface.h"

#include <GeomAdaptor_Curve.hxx>
#include <GeomAdaptor_Surface.hxx>
#include <Geom2dAPI_Interpolate.hxx>
#include <Geom2d_BSplineCurve.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_HArray1OfReal.hxx>
#include <TColgp_Array1OfPnt2d.hxx>
#include <TColgp_HArray1OfPnt2d.hxx>
#include <gp_Pnt2d.hxx>
#include <gp_Vec.hxx>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

namespace kintsugi::io::occt {
namespace {

// A curve farther than this many times `within` (half the edge's tolerance) from the
// surface at a sample is clearly off it (pcurve.h).
constexpr double kClearlyOff = 4;
// Samples per piece at most, and over all pieces and samplings of one curve: past either
// the edge is left to ShapeFix (the budget is what one piece doubling to 1025 costs).
constexpr int kMaxSamples = 1025;
constexpr int kSampleBudget = 4 * kMaxSamples;
constexpr int kDegree = 3;  // of the pcurves (Geom2dAPI_Interpolate's)

// A sample: the curve's parameter, its foot's parameters, and its distance from there.
struct Sample {
  double t;
  gp_Pnt2d uv;
  double off;
};

// The feet of a curve's points on a free-form surface (geo::parameters: Newton from the
// last foot), continued across the seam of a periodic surface as the curve runs; and the
// surface evaluated from OpenCASCADE's span cache (GeomAdaptor_Surface) rather than by
// de Boor's algorithm at every point (Geom_BSplineSurface::D1).
class Feet {
 public:
  Feet(const geo::Surface& s, const Handle(Geom_Surface)& gs, const Handle(Geom_Curve)& c)
      : s_(s), c_(c), up_(gs->IsUPeriodic() ? gs->UPeriod() : 0), vp_(gs->IsVPeriodic() ? gs->VPeriod() : 0) {
    geo::occt::load_for_evaluation(surface_, gs);  // a foot held on a bound from the cache too
  }

  // The foot of the curve's point at t: the sample (in the period of `near`, when
  // given), with its distance from the surface. Nullopt at a degenerate point
  // (|S_u x S_v| vanishing: a pole's parameters are not the point's).
  std::optional<Sample> at(double t, const gp_Pnt2d* near) {
    const gp_Pnt p = c_->Value(t);
    const geo::Vec2 q = geo::parameters(s_, geo::Vec3(p.X(), p.Y(), p.Z()));
    Sample x{t, gp_Pnt2d(q.x(), q.y()), 0};
    if (near) {
      if (up_ > 0) x.uv.SetX(x.uv.X() - up_ * std::round((x.uv.X() - near->X()) / up_));
      if (vp_ > 0) x.uv.SetY(x.uv.Y() - vp_ * std::round((x.uv.Y() - near->Y()) / vp_));
    }
    gp_Pnt on;
    gp_Vec du, dv;
    surface_.D1(x.uv.X(), x.uv.Y(), on, du, dv);
    if (!(du.Magnitude() > 1e-12 && dv.Magnitude() > 1e-12 &&
          du.Crossed(dv).Magnitude() > 1e-12 * du.Magnitude() * dv.Magnitude()))
      return std::nullopt;
    x.off = on.Distance(p);
    return x;
  }
  gp_Pnt value(const gp_Pnt2d& uv) const { return surface_.Value(uv.X(), uv.Y()); }
  double period(int i) const { return i == 0 ? up_ : vp_; }
  GeomAdaptor_Surface& surface() { return surface_; }

 private:
  const geo::Surface& s_;
  Handle(Geom_Curve) c_;
  double up_, vp_;
  GeomAdaptor_Surface surface_;
};

// The interior bounds of the C2 intervals of `a` in u (i = 0) or v (1): the parameter
// lines where a B-spline surface with multiple knots (or the curve a revolution turns or
// an extrusion sweeps) is less smooth, and so are the feet of a curve crossing them.
std::vector<double> c2_lines(GeomAdaptor_Surface& a, int i) {
  const int n = i == 0 ? a.NbUIntervals(GeomAbs_C2) : a.NbVIntervals(GeomAbs_C2);
  if (n < 2) return {};
  TColStd_Array1OfReal bounds(1, n + 1);
  if (i == 0)
    a.UIntervals(bounds, GeomAbs_C2);
  else
    a.VIntervals(bounds, GeomAbs_C2);
  return std::vector<double>(bounds.begin() + 1, bounds.end() - 1);
}

// Where between samples `a` and `b` the foot's coordinate `i` (0: u, 1: v) crosses `k`:
// the secant step, kept inside the bracket by halving the end that stays (Illinois).
// Nullopt at a degenerate foot.
std::optional<Sample> crossing(Feet& feet, Sample a, Sample b, int i, double k) {
  double ga = a.uv.Coord(i + 1) - k, gb = b.uv.Coord(i + 1) - k;
  std::optional<Sample> m;
  for (int step = 0; step < 60; ++step) {
    double t = (a.t * gb - b.t * ga) / (gb - ga);
    if (!(t > std::min(a.t, b.t) && t < std::max(a.t, b.t))) t = 0.5 * (a.t + b.t);
    m = feet.at(t, &a.uv);
    if (!m) return std::nullopt;
    const double g = m->uv.Coord(i + 1) - k;
    if (std::abs(g) <= 1e-13 * (1 + std::abs(k)) || std::abs(b.t - a.t) <= 1e-15 * (1 + std::abs(t))) break;
    if ((g < 0) == (ga < 0)) {
      a = *m, ga = g, gb *= 0.5;
    } else {
      b = *m, gb = g, ga *= 0.5;
    }
  }
  return m;
}

// The samples where the feet cross one of the surface's C2 lines between consecutive
// samples of `run` (every copy of a periodic direction's line the interval spans).
std::optional<std::vector<Sample>> line_crossings(Feet& feet, const std::vector<Sample>& run) {
  std::vector<Sample> out;
  for (int i = 0; i < 2; ++i) {
    const std::vector<double> lines = c2_lines(feet.surface(), i);
    const double period = feet.period(i);
    for (std::size_t j = 0; j + 1 < run.size(); ++j)
      for (double k0 : lines) {
        const double lo = std::min(run[j].uv.Coord(i + 1), run[j + 1].uv.Coord(i + 1));
        const double hi = std::max(run[j].uv.Coord(i + 1), run[j + 1].uv.Coord(i + 1));
        const int m0 = period > 0 ? int(std::ceil((lo - k0) / period)) : 0;
        const int m1 = period > 0 ? int(std::floor((hi - k0) / period)) : 0;
        for (int m = m0; m <= m1; ++m) {
          const double k = k0 + m * period;
          if (!(lo < k && k < hi)) continue;
          std::optional<Sample> x = crossing(feet, run[j], run[j + 1], i, k);
          if (!x) return std::nullopt;
          out.push_back(*x);
        }
      }
  }
  return out;
}

// The pcurve over [from.t, to.t] through the feet `from` and `to` at its ends, from `n`
// samples doubled until it passes (pcurve.h); null when it does not, when the curve is
// near the surface but not on it, or when `*budget` samples run out.
Handle(Geom2d_BSplineCurve) piece(Feet& feet, const Sample& from, const Sample& to, int n, double within,
                                  int* budget) {
  for (; n <= kMaxSamples; n = 2 * n - 1) {
    if ((*budget -= n) < 0) return nullptr;
    Handle(TColgp_HArray1OfPnt2d) uv = new TColgp_HArray1OfPnt2d(1, n);
    Handle(TColStd_HArray1OfReal) ts = new TColStd_HArray1OfReal(1, n);
    double off = std::max(from.off, to.off);  // the samples' farthest distance from the surface
    uv->SetValue(1, from.uv), ts->SetValue(1, from.t);
    uv->SetValue(n, to.uv), ts->SetValue(n, to.t);
    for (int i = 1; i + 1 < n; ++i) {
      std::optional<Sample> x = feet.at(from.t + (to.t - from.t) * i / (n - 1), &uv->Value(i));
      if (!x) return nullptr;
      off = std::max(off, x->off);
      uv->SetValue(i + 1, x->uv);
      ts->SetValue(i + 1, x->t);
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
      if (pc->Degree() < kDegree) pc->IncreaseDegree(kDegree);
    } catch (const Standard_Failure&) {
      return nullptr;
    }
    bool on = pc->Degree() == kDegree;
    for (int i = 0; i + 1 < n && on; ++i)
      for (const double f : {0.25, 0.5, 0.75}) {
        const std::optional<Sample> x = feet.at((1 - f) * ts->Value(i + 1) + f * ts->Value(i + 2), &uv->Value(i + 1));
        on = on && x && feet.value(pc->Value(x->t)).Distance(feet.value(x->uv)) <= image;
      }
    if (on) return pc;
  }
  return nullptr;
}

// The pieces as one B-spline: a knot of multiplicity `kDegree` where two meet (their
// shared end a pole of both), so that each keeps its own shape on its interval.
Handle(Geom2d_Curve) joined(const std::vector<Handle(Geom2d_BSplineCurve)>& pieces) {
  if (pieces.size() == 1) return Handle(Geom2d_Curve)(pieces.front());
  int poles = 1, knots = 1;
  for (const auto& p : pieces) poles += p->NbPoles() - 1, knots += p->NbKnots() - 1;
  TColgp_Array1OfPnt2d all_poles(1, poles);
  TColStd_Array1OfReal all_knots(1, knots);
  TColStd_Array1OfInteger mults(1, knots);
  int at_pole = 1, at_knot = 1;
  all_poles(1) = pieces.front()->Pole(1);
  all_knots(1) = pieces.front()->Knot(1);
  mults(1) = kDegree + 1;
  for (const auto& p : pieces) {
    for (int i = 2; i <= p->NbPoles(); ++i) all_poles(++at_pole) = p->Pole(i);
    for (int i = 2; i <= p->NbKnots(); ++i) {
      all_knots(++at_knot) = p->Knot(i);
      mults(at_knot) = i == p->NbKnots() ? kDegree : p->Multiplicity(i);
    }
  }
  mults(knots) = kDegree + 1;
  return new Geom2d_BSplineCurve(all_poles, all_knots, mults, kDegree);
}

}  // namespace

Handle(Geom2d_Curve) projected_pcurve(const geo::Surface& s, const Handle(Geom_Surface)& gs, const Handle(Geom_Curve)& c,
                                     double t0, double t1, double within) {
  Feet feet(s, gs, c);
  // The first sampling (4 per C2 span of the curve, at least 9) with the bounds of those
  // spans, then where the feet cross the surface's C2 lines: the feet turn there, and a
  // C2 interpolation through such a turn closes in slowly (a line across the double
  // knots of a bicubic sheet of OpenCASCADE's linkrods.step still missed at 1025
  // samples); the pcurve is made in pieces between these breaks.
  GeomAdaptor_Curve ad(c, t0, t1);
  const int spans = ad.NbIntervals(GeomAbs_C2);
  const int n0 = std::clamp(4 * spans + 1, 9, kMaxSamples);
  std::vector<double> ts;
  for (int i = 0; i < n0; ++i) ts.push_back(i + 1 == n0 ? t1 : t0 + (t1 - t0) * i / (n0 - 1));
  std::vector<double> curve_breaks;
  if (spans > 1) {
    TColStd_Array1OfReal bounds(1, spans + 1);
    ad.Intervals(bounds, GeomAbs_C2);
    curve_breaks.assign(bounds.begin() + 1, bounds.end() - 1);
    ts.insert(ts.end(), curve_breaks.begin(), curve_breaks.end());
    std::sort(ts.begin(), ts.end());
  }
  std::vector<Sample> run;
  for (double t : ts) {
    std::optional<Sample> x = feet.at(t, run.empty() ? nullptr : &run.back().uv);
    if (!x) return nullptr;
    run.push_back(*x);
  }
  std::optional<std::vector<Sample>> breaks = line_crossings(feet, run);
  if (!breaks) return nullptr;
  for (const Sample& x : run)
    if (std::binary_search(curve_breaks.begin(), curve_breaks.end(), x.t)) breaks->push_back(x);
  breaks->push_back(run.front());
  breaks->push_back(run.back());
  std::sort(breaks->begin(), breaks->end(), [](const Sample& a, const Sample& b) { return a.t < b.t; });
  // Breaks closer than this are one.
  const double apart = 1e-9 * (t1 - t0);
  std::vector<Sample> ends{breaks->front()};
  for (const Sample& x : *breaks)
    if (x.t - ends.back().t > apart) ends.push_back(x);
  if (ends.size() > 1 && t1 - ends.back().t <= apart) ends.back() = run.back();
  if (ends.size() < 2) return nullptr;

  std::vector<Handle(Geom2d_BSplineCurve)> pieces;
  int budget = kSampleBudget;
  for (std::size_t i = 0; i + 1 < ends.size(); ++i) {
    const double share = (ends[i + 1].t - ends[i].t) / (t1 - t0);
    const int n = std::clamp(int(std::lround((n0 - 1) * share)) + 1, 5, kMaxSamples);
    Handle(Geom2d_BSplineCurve) p = piece(feet, ends[i], ends[i + 1], n, within, &budget);
    if (p.IsNull()) return nullptr;
    pieces.push_back(p);
  }
  return joined(pieces);
}

namespace {
struct PcurveQuestion {
  geo::Surface s;
  geo::Curve of;
  geo::Vec3 p0, p1;
  double t0, t1, within;
  Handle(Geom2d_Curve) pcurve;  // null: no pcurve of ours (ShapeFix makes one)
};
geo::RecentAnswers<PcurveQuestion, 512>& recent_pcurves() {
  static geo::RecentAnswers<PcurveQuestion, 512> memo;
  return memo;
}
// A copy for the caller: the shape it goes into owns it, and nothing another shape holds
// may change with it.
Handle(Geom2d_Curve) copy_of(const Handle(Geom2d_Curve)& c) {
  return c.IsNull() ? c : Handle(Geom2d_Curve)::DownCast(c->Copy());
}
}  // namespace

Handle(Geom2d_Curve) projected_pcurve_remembered(const geo::Surface& s, const geo::Curve& of,
                                                const Handle(Geom_Surface)& gs, const Handle(Geom_Curve)& c,
                                                double t0, double t1, double within) {
  const gp_Pnt a = c->Value(t0), b = c->Value(t1);
  const geo::Vec3 p0(a.X(), a.Y(), a.Z()), p1(b.X(), b.Y(), b.Z());
  if (auto known = recent_pcurves().find(
          [&](const PcurveQuestion& e) {
            return e.t0 == t0 && e.t1 == t1 && e.within == within && e.p0 == p0 && e.p1 == p1 && e.of == of && e.s == s;
          },
          [](const PcurveQuestion& e) { return copy_of(e.pcurve); }))
    return *known;
  Handle(Geom2d_Curve) pc = projected_pcurve(s, gs, c, t0, t1, within);
  recent_pcurves().remember({s, of, p0, p1, t0, t1, within, copy_of(pc)});
  return pc;
}

}  // namespace kintsugi::io::occt
