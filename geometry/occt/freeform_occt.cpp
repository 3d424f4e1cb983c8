// OpenCASCADE behind geometry/freeform.h: free-form surfaces and curves are rebuilt once
// from their data (Geom_BSplineSurface, Geom_SurfaceOfRevolution, ...) and kept in the
// data's `cache`, with the projection helpers (ShapeAnalysis_Surface keeps its own
// search grid), so repeated projections onto one face are cheap.
#include "geometry/occt/freeform_occt.h"

#include "geometry/freeform.h"
#include "geometry/recent_answers.h"

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BndLib_AddSurface.hxx>
#include <Bnd_Box.hxx>
#include <GCPnts_AbscissaPoint.hxx>
#include <GCPnts_QuasiUniformDeflection.hxx>
#include <GeomAPI_IntSS.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <GeomAdaptor_Curve.hxx>
#include <GeomAdaptor_Surface.hxx>
#include <GeomConvert.hxx>
#include <Geom_Circle.hxx>
#include <Geom_ConicalSurface.hxx>
#include <Geom_CylindricalSurface.hxx>
#include <Geom_Ellipse.hxx>
#include <Geom_Line.hxx>
#include <Geom_OffsetSurface.hxx>
#include <Geom_Plane.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <Geom_SphericalSurface.hxx>
#include <Geom_SurfaceOfLinearExtrusion.hxx>
#include <Geom_SurfaceOfRevolution.hxx>
#include <Geom_ToroidalSurface.hxx>
#include <Geom_TrimmedCurve.hxx>
#include <Precision.hxx>
#include <ShapeAnalysis_Curve.hxx>
#include <ShapeAnalysis_Surface.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <gp_Ax1.hxx>
#include <gp_Ax3.hxx>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <mutex>
#include <stdexcept>

namespace kintsugi::geo::occt {

namespace {

gp_Pnt pnt(const Vec3& p) { return gp_Pnt(p.x(), p.y(), p.z()); }
gp_Dir dir(const Vec3& d) { return gp_Dir(d.x(), d.y(), d.z()); }
Vec3 vec(const gp_XYZ& p) { return Vec3(p.X(), p.Y(), p.Z()); }
Vec3 vec(const gp_Pnt& p) { return vec(p.XYZ()); }
Vec3 vec(const gp_Vec& p) { return vec(p.XYZ()); }

Handle(Geom_BSplineCurve) make_curve(const BSplineCurve& c) {
  const int n = int(c.poles.size());
  TColgp_Array1OfPnt poles(1, n);
  for (int i = 0; i < n; ++i) poles(i + 1) = pnt(c.poles[std::size_t(i)]);
  TColStd_Array1OfReal knots(1, int(c.knots.size()));
  TColStd_Array1OfInteger mults(1, int(c.knots.size()));
  for (std::size_t i = 0; i < c.knots.size(); ++i) {
    knots(int(i) + 1) = c.knots[i];
    mults(int(i) + 1) = c.multiplicities[i];
  }
  if (c.weights.empty()) return new Geom_BSplineCurve(poles, knots, mults, c.degree, c.periodic);
  TColStd_Array1OfReal w(1, n);
  for (int i = 0; i < n; ++i) w(i + 1) = c.weights[std::size_t(i)];
  return new Geom_BSplineCurve(poles, w, knots, mults, c.degree, c.periodic);
}

Handle(Geom_BSplineSurface) make_surface(const BSplineSurface& b) {
  TColgp_Array2OfPnt poles(1, b.u_count, 1, b.v_count);
  for (int i = 0; i < b.u_count; ++i)
    for (int j = 0; j < b.v_count; ++j) poles(i + 1, j + 1) = pnt(b.poles[std::size_t(i * b.v_count + j)]);
  auto arrays = [](const std::vector<double>& k, const std::vector<int>& m, TColStd_Array1OfReal& ka, TColStd_Array1OfInteger& ma) {
    for (std::size_t i = 0; i < k.size(); ++i) {
      ka(int(i) + 1) = k[i];
      ma(int(i) + 1) = m[i];
    }
  };
  TColStd_Array1OfReal uk(1, int(b.u_knots.size())), vk(1, int(b.v_knots.size()));
  TColStd_Array1OfInteger um(1, int(b.u_knots.size())), vm(1, int(b.v_knots.size()));
  arrays(b.u_knots, b.u_multiplicities, uk, um);
  arrays(b.v_knots, b.v_multiplicities, vk, vm);
  if (b.weights.empty())
    return new Geom_BSplineSurface(poles, uk, vk, um, vm, b.u_degree, b.v_degree, b.u_periodic, b.v_periodic);
  TColStd_Array2OfReal w(1, b.u_count, 1, b.v_count);
  for (int i = 0; i < b.u_count; ++i)
    for (int j = 0; j < b.v_count; ++j) w(i + 1, j + 1) = b.weights[std::size_t(i * b.v_count + j)];
  return new Geom_BSplineSurface(poles, w, uk, vk, um, vm, b.u_degree, b.v_degree, b.u_periodic, b.v_periodic);
}

// An adaptor that can say whether its B-spline cache (one knot span's polynomial) holds a
// parameter: GeomAdaptor_Surface keeps the cache protected.
class SpanAdaptor : public GeomAdaptor_Surface {
 public:
  bool holds(double u, double v) const { return !mySurfaceCache.IsNull() && mySurfaceCache->IsCacheValid(u, v); }
};

// What is cached on a free-form surface's data: the OpenCASCADE surface and the
// projection helper (not thread-safe: guarded).
struct SurfaceCache {
  Handle(Geom_Surface) surface;
  // Evaluation goes through an adaptor: for B-splines (and the B-spline curves under
  // revolution, extrusion and offset surfaces) it keeps one knot span's polynomial
  // (BSplSLib_Cache), where Geom_BSplineSurface::D1 runs de Boor's algorithm
  // (BSplCLib::Bohm) on every call: measured, most of a B-spline face's measure. A solve
  // evaluates its vertices on one surface in turn, each in its own span, and a single
  // cache was rebuilt at nearly every call (BSplSLib::BuildCache, a fifth of
  // linkrods.step's beautify at --tol 0.0056); a B-spline surface keeps kSpans adaptors,
  // each holding the span it last built, and the one built longest ago is rebuilt. The
  // answers are the same: a span's polynomial does not depend on which adaptor holds it.
  // The caches are not thread-safe: evaluations hold `m`.
  static constexpr std::size_t kSpans = 8;
  std::array<SpanAdaptor, kSpans> adaptors;
  std::size_t oldest = 0;
  bool spans = false;  // a B-spline or Bezier surface: its adaptors cache spans
  // The adaptor to evaluate at (u, v) with.
  GeomAdaptor_Surface& at(double u, double v) {
    if (!spans) return adaptors[0];
    for (SpanAdaptor& a : adaptors)
      if (a.holds(u, v)) return a;
    SpanAdaptor& a = adaptors[oldest];
    oldest = (oldest + 1) % kSpans;
    return a;
  }
  Handle(ShapeAnalysis_Surface) analysis;
  // Starting points for a projection that is not near the last one: the surface at the
  // centres of a kSeedGrid × kSeedGrid grid over its bounds (built on first need; empty
  // when the bounds are infinite).
  static constexpr int kSeedGrid = 24;
  bool seeds_built = false;
  std::vector<gp_Pnt2d> seed_uv;
  std::vector<gp_Pnt> seed_xyz;
  // The last points ValueOfUV projected, with its answers.
  std::vector<std::pair<gp_Pnt, gp_Pnt2d>> global;
  ProjectionCounts counts;
  double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
  bool bounded = false;  // all four bounds finite
  // The last projection's parameters: projections come in runs (along a boundary, or a
  // meeting point's iterations), each point near the last, so Gauss-Newton from there
  // replaces the global grid search of ValueOfUV (measured: most of detect's and
  // beautify's time on B-spline parts).
  bool has_last = false;
  gp_Pnt2d last;
  // A converged foot is kept when it is within this of the point (1e-2 of the surface's
  // extent, so scaling the model scales it; Precision::Confusion() for unbounded
  // surfaces): the foot is then the nearest point unless the surface curves or folds
  // back within that distance, which the parts kintsugi repairs (faces whose features
  // are far larger than its tolerance) do not.
  double near_enough = Precision::Confusion();
  Bnd_Box box;  // of the surface within its bounds (void when unbounded)
  std::mutex m;
};
struct CurveCache {
  Handle(Geom_Curve) curve;
  double t0 = 0, t1 = 0;
  std::mutex m;
};

Handle(Geom_Surface) build(const Surface& s) {
  if (const auto* b = std::get_if<BSplineSurface>(&s)) return make_surface(*b);
  if (const auto* r = std::get_if<RevolutionSurface>(&s))
    return new Geom_SurfaceOfRevolution(make_curve(r->basis), gp_Ax1(pnt(r->origin), dir(r->axis)));
  if (const auto* e = std::get_if<ExtrusionSurface>(&s)) return new Geom_SurfaceOfLinearExtrusion(make_curve(e->basis), dir(e->direction));
  if (const auto* o = std::get_if<OffsetSurface>(&s)) return new Geom_OffsetSurface(make_surface(o->basis), o->distance, Standard_True);
  return nullptr;
}

SurfaceCache& surface_cache(const Surface& s) {
  std::shared_ptr<const void>* slot = cache_slot(s);
  if (!slot) throw std::invalid_argument("not a free-form surface");
  if (!*slot) {
    auto c = std::make_shared<SurfaceCache>();
    c->surface = build(s);
    c->surface->Bounds(c->u0, c->u1, c->v0, c->v1);
    c->analysis = new ShapeAnalysis_Surface(c->surface);
    // Boundary samples of every face that reaches a side of its surface are projected
    // onto the bound exactly: evaluated from the cache (load_for_evaluation).
    for (SpanAdaptor& a : c->adaptors) c->bounded = load_for_evaluation(a, c->surface);
    const GeomAbs_SurfaceType type = c->adaptors[0].GetType();
    c->spans = type == GeomAbs_BSplineSurface || type == GeomAbs_BezierSurface;
    if (c->bounded) {
      BndLib_AddSurface::Add(GeomAdaptor_Surface(c->surface), 0.0, c->box);
      if (!c->box.IsVoid()) c->near_enough = std::max(Precision::Confusion(), 1e-2 * std::sqrt(c->box.SquareExtent()));
    }
    *slot = c;
  }
  return *const_cast<SurfaceCache*>(static_cast<const SurfaceCache*>(slot->get()));
}

CurveCache& curve_cache(const Curve& c) {
  const auto* b = std::get_if<BSplineCurve>(&c);
  if (!b) throw std::invalid_argument("not a free-form curve");
  if (!b->cache) {
    auto cc = std::make_shared<CurveCache>();
    cc->curve = make_curve(*b);
    cc->t0 = cc->curve->FirstParameter();
    cc->t1 = cc->curve->LastParameter();
    b->cache = cc;
  }
  return *const_cast<CurveCache*>(static_cast<const CurveCache*>(b->cache.get()));
}

// ---- the backend ------------------------------------------------------------------

Vec3 surface_d1(const Surface& s, const Vec2& uv, Vec3* du, Vec3* dv) {
  SurfaceCache& c = surface_cache(s);
  gp_Pnt p;
  gp_Vec a, b;
  {
    std::lock_guard<std::mutex> lock(c.m);
    c.at(uv.x(), uv.y()).D1(uv.x(), uv.y(), p, a, b);
  }
  *du = vec(a);
  *dv = vec(b);
  return vec(p);
}

// Gauss-Newton for the foot of `target` from (u, v), clamped to the bounds: boundary
// points lie on them, a step may overshoot, and a point beyond the bounds has its nearest
// point on them (where the clamped step vanishes although the residual is not normal to
// the surface). A step that does not bring the point nearer is halved until it does (far
// off a curved surface the full step can overshoot the foot back and forth for ever).
// Converged when a step moves the point by less than a billionth of near_enough, or no
// step brings it nearer; `*uv` is then the last point and the result its distance to the
// target (infinity when it did not converge within 100 steps; from the fourth on, the
// step is Newton's with the surface's curvature, below). `*tangential` is the residual's largest
// share along a tangent, relative to the tangent's length, leaving out a tangent along
// which the point is held at a bound with the residual pointing out of the bounds (there
// the point is the nearest within the bounds, as it should be).
double newton(SurfaceCache& c, const gp_Pnt& target, double u, double v, gp_Pnt2d* uv, double* tangential) {
  gp_Pnt q;
  gp_Vec su, sv;
  c.at(u, v).D1(u, v, q, su, sv);
  double dist = q.Distance(target);
  auto done = [&]() {
    const gp_Vec r(q, target);
    const double tu = r.Dot(su), tv = r.Dot(sv);
    const bool held_u = (u <= c.u0 && tu <= 0) || (u >= c.u1 && tu >= 0);
    const bool held_v = (v <= c.v0 && tv <= 0) || (v >= c.v1 && tv >= 0);
    *tangential = std::max(held_u ? 0.0 : std::abs(tu) / std::max(su.Magnitude(), 1e-300),
                           held_v ? 0.0 : std::abs(tv) / std::max(sv.Magnitude(), 1e-300));
    *uv = gp_Pnt2d(u, v);
    return dist;
  };
  for (int it = 0; it < 100 && std::isfinite(dist); ++it) {
    const gp_Vec r(q, target);
    double a = su.Dot(su), b = su.Dot(sv), d = sv.Dot(sv), det = a * d - b * b;
    if (!(det > 1e-300)) break;
    const double ru = su.Dot(r), rv = sv.Dot(r);
    if (it >= 3) {
      // Still going after three steps: Gauss-Newton leaves out the surface's curvature,
      // and where the point is near a centre of curvature (the distance almost constant
      // along a parameter) it creeps, a hundredth of the way per step. Newton's full
      // Hessian, while it is positive definite.
      gp_Pnt ignored;
      gp_Vec su2, sv2, suu, svv, suv;
      c.at(u, v).D2(u, v, ignored, su2, sv2, suu, svv, suv);
      const double ha = a - r.Dot(suu), hb = b - r.Dot(suv), hd = d - r.Dot(svv), hdet = ha * hd - hb * hb;
      if (ha > 0 && hd > 0 && hdet > 1e-12 * a * d) a = ha, b = hb, d = hd, det = hdet;
    }
    // A parameter at a bound with the residual pointing out of the bounds stays there and
    // the other is solved for alone (the joint step, clamped, would move the free one by a
    // share meant to go with the held one's move, and stop short of the foot).
    const bool held_u = (u <= c.u0 && ru <= 0) || (u >= c.u1 && ru >= 0);
    const bool held_v = (v <= c.v0 && rv <= 0) || (v >= c.v1 && rv >= 0);
    if (held_u && held_v) return done();  // the nearest point within the bounds, at a corner
    double du = held_u ? 0 : held_v ? ru / a : (d * ru - b * rv) / det;
    double dv = held_v ? 0 : held_u ? rv / d : (a * rv - b * ru) / det;
    if (!std::isfinite(du) || !std::isfinite(dv)) break;
    bool moved = false;
    double un = u, vn = v;
    gp_Pnt qn;
    gp_Vec sun, svn;
    for (double t = 1; t > 1.0 / 4096; t *= 0.5) {
      un = std::clamp(u + t * du, c.u0, c.u1);
      vn = std::clamp(v + t * dv, c.v0, c.v1);
      c.at(un, vn).D1(un, vn, qn, sun, svn);
      if (qn.Distance(target) <= dist) {
        moved = true;
        break;
      }
    }
    if (!moved) return done();  // no step brings it nearer: a local foot (to rounding)
    const double step = ((un - u) * su + (vn - v) * sv).Magnitude();
    u = un, v = vn, q = qn, su = sun, sv = svn;
    dist = q.Distance(target);
    if (step <= 1e-9 * c.near_enough + Precision::Confusion() * 1e-3) return done();
  }
  return std::numeric_limits<double>::infinity();
}

void build_seeds(SurfaceCache& c) {
  c.seeds_built = true;
  if (!c.bounded || !(c.u1 > c.u0) || !(c.v1 > c.v0)) return;
  const int n = SurfaceCache::kSeedGrid;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double u = c.u0 + (c.u1 - c.u0) * (i + 0.5) / n, v = c.v0 + (c.v1 - c.v0) * (j + 0.5) / n;
      c.seed_uv.emplace_back(u, v);
      c.seed_xyz.push_back(c.at(u, v).Value(u, v));
    }
}

// The global search the way Extrema's does it: the seed grid's local minima of the
// distance (the nearest four) and the six nearest seeds, refined by Gauss-Newton; the
// nearest true foot (the residual normal to the surface, or pointing out of the bounds
// where the point is held at one) goes to `*uv`. False when none converges.
bool seeded_foot(SurfaceCache& c, const gp_Pnt& target, gp_Pnt2d* uv) {
  if (!c.seeds_built) build_seeds(c);
  if (c.seed_xyz.empty()) return false;
  const int n = SurfaceCache::kSeedGrid;
  std::vector<double> d2(c.seed_xyz.size());
  for (std::size_t i = 0; i < d2.size(); ++i) d2[i] = c.seed_xyz[i].SquareDistance(target);
  std::vector<std::pair<double, std::size_t>> starts;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double here = d2[std::size_t(i * n + j)];
      bool least = true;
      for (int di = -1; di <= 1 && least; ++di)
        for (int dj = -1; dj <= 1 && least; ++dj) {
          const int a = i + di, b = j + dj;
          if ((di || dj) && a >= 0 && a < n && b >= 0 && b < n && d2[std::size_t(a * n + b)] < here) least = false;
        }
      if (least) starts.emplace_back(here, std::size_t(i * n + j));
    }
  std::sort(starts.begin(), starts.end());
  if (starts.size() > 4) starts.resize(4);
  // And the nearest few seeds whatever their neighbours: a foot between seeds can be
  // nearer than the seeds' own minimum says, in the basin of a neighbour of it.
  std::vector<std::pair<double, std::size_t>> all(d2.size());
  for (std::size_t i = 0; i < d2.size(); ++i) all[i] = {d2[i], i};
  std::partial_sort(all.begin(), all.begin() + 6, all.end());
  for (int i = 0; i < 6; ++i)
    if (std::find(starts.begin(), starts.end(), all[std::size_t(i)]) == starts.end()) starts.push_back(all[std::size_t(i)]);
  bool found = false;
  double best = std::numeric_limits<double>::infinity(), tangential = 0;
  for (const auto& [ignored, k] : starts) {
    gp_Pnt2d q;
    const double dist = newton(c, target, c.seed_uv[k].X(), c.seed_uv[k].Y(), &q, &tangential);
    // Tangentially within a hundredth of the modelling precision counts as a foot:
    // ValueOfUV, the alternative, answers to the precision itself.
    const double slack = 1e-6 * dist + 1e-9 * c.near_enough + 1e-2 * Precision::Confusion();
    if (dist < best && tangential <= slack) best = dist, *uv = q, found = true;
  }
  return found;
}

// A point a thousand times the surface's extent away from it (a region solve that ran off,
// measured: Motor-c.brep at 4x its tolerance, targets 1e10 to 1e68 away, 16 of 18 s in
// ValueOfUV): the nearest seed, as ValueOfUV's answer would be no better for anything.
// There Gauss-Newton cannot converge (a step changes the distance by less than its
// rounding) and ValueOfUV's global search costs tens of milliseconds. Such a point is
// off the surface by far more than any tolerance whatever its foot, so no decision
// depends on where exactly the foot is. False when the point is nearer.
bool far_foot(SurfaceCache& c, const gp_Pnt& target, gp_Pnt2d* uv) {
  if (c.box.IsVoid() || !c.box.IsOut(target)) return false;
  double x0, y0, z0, x1, y1, z1;
  c.box.Get(x0, y0, z0, x1, y1, z1);
  const double dx = std::max({x0 - target.X(), target.X() - x1, 0.0}), dy = std::max({y0 - target.Y(), target.Y() - y1, 0.0}),
               dz = std::max({z0 - target.Z(), target.Z() - z1, 0.0});
  if (!(dx * dx + dy * dy + dz * dz > 1e6 * c.box.SquareExtent())) return false;
  if (!c.seeds_built) build_seeds(c);
  if (c.seed_xyz.empty()) return false;
  std::size_t best = 0;
  for (std::size_t i = 1; i < c.seed_xyz.size(); ++i)
    if (c.seed_xyz[i].SquareDistance(target) < c.seed_xyz[best].SquareDistance(target)) best = i;
  *uv = c.seed_uv[best];
  return true;
}

// ValueOfUV, for what the other searches do not reach. The same point comes back (a
// vertex on a degenerate side of the surface, where |S_u| vanishes and Gauss-Newton
// cannot converge, is projected once per sample of each of its edges, in every measure
// of its face; measured: over half of the calls on Bottom.brep and bearing.iges), so its
// answers for the last 64 points are kept.
gp_Pnt2d global_foot(SurfaceCache& c, const gp_Pnt& target) {
  const auto same = [&](const std::pair<gp_Pnt, gp_Pnt2d>& e) {
    return e.first.X() == target.X() && e.first.Y() == target.Y() && e.first.Z() == target.Z();
  };
  if (auto it = std::find_if(c.global.begin(), c.global.end(), same); it != c.global.end()) return it->second;
  ++c.counts.value_of_uv;
  const gp_Pnt2d uv = c.analysis->ValueOfUV(target, Precision::Confusion());
  if (c.global.size() >= 64) c.global.erase(c.global.begin());
  c.global.emplace_back(target, uv);
  return uv;
}

}  // namespace

ProjectionCounts projection_counts(const Surface& s) {
  SurfaceCache& c = surface_cache(s);
  std::lock_guard<std::mutex> lock(c.m);
  return c.counts;
}

namespace {

Vec2 surface_project(const Surface& s, const Vec3& p) {
  SurfaceCache& c = surface_cache(s);
  std::lock_guard<std::mutex> lock(c.m);
  // Projections come in runs, each point near the last: Gauss-Newton from the last
  // answer (a few D1 evaluations), kept when it converges (within the surface's bounds)
  // to a foot within `near_enough` of the point. Otherwise the seeded global search;
  // ValueOfUV only when that finds nothing: it rebuilds Extrema's grid on every call
  // (measured: most of detect's and beautify's time on B-spline parts when used for
  // every point, a fifth when used for the points off the surface).
  const gp_Pnt target = pnt(p);
  gp_Pnt2d uv;
  double tangential = 0;
  ++c.counts.projections;
  bool found = c.has_last && newton(c, target, c.last.X(), c.last.Y(), &uv, &tangential) <= c.near_enough;
  if (!found) {
    ++c.counts.seeded;
    found = seeded_foot(c, target, &uv);
  }
  if (!found && far_foot(c, target, &uv)) {
    ++c.counts.far;
    found = true;
  }
  if (!found) uv = global_foot(c, target);
  c.last = uv;
  c.has_last = true;
  return Vec2(uv.X(), uv.Y());
}

void surface_bounds(const Surface& s, double* u0, double* u1, double* v0, double* v1) {
  SurfaceCache& c = surface_cache(s);
  *u0 = c.u0, *u1 = c.u1, *v0 = c.v0, *v1 = c.v1;
}

std::string surface_problem(const Surface& s) {
  try {
    SurfaceCache& c = surface_cache(s);
    if (c.surface.IsNull()) return std::string(surface_type_name(s)) + ": OpenCASCADE could not build it";
    if (const auto* r = std::get_if<RevolutionSurface>(&s); r && !(std::abs(r->axis.norm() - 1) < 1e-9))
      return "revolution_surface: the axis is not a unit vector";
  } catch (const Standard_Failure& e) {
    return std::string(surface_type_name(s)) + ": OpenCASCADE refused the data: " + e.GetMessageString();
  } catch (const std::exception& e) {
    return std::string(surface_type_name(s)) + ": " + e.what();
  }
  return "";
}

Vec3 curve_d1(const Curve& c, double t, Vec3* d) {
  CurveCache& cc = curve_cache(c);
  gp_Pnt p;
  gp_Vec v;
  cc.curve->D1(t, p, v);
  *d = vec(v);
  return vec(p);
}

double curve_project(const Curve& c, const Vec3& p) {
  CurveCache& cc = curve_cache(c);
  std::lock_guard<std::mutex> lock(cc.m);
  ShapeAnalysis_Curve sac;
  gp_Pnt proj;
  double t = cc.t0;
  sac.Project(cc.curve, pnt(p), Precision::Confusion(), proj, t, Standard_False);
  return t;
}

void curve_bounds(const Curve& c, double* t0, double* t1) {
  CurveCache& cc = curve_cache(c);
  *t0 = cc.t0, *t1 = cc.t1;
}

double curve_length(const Curve& c, double t0, double t1) {
  CurveCache& cc = curve_cache(c);
  GeomAdaptor_Curve ad(cc.curve);
  return GCPnts_AbscissaPoint::Length(ad, std::min(t0, t1), std::max(t0, t1));
}

std::vector<Vec3> curve_sample(const Curve& c, double t0, double t1, double chordal) {
  CurveCache& cc = curve_cache(c);
  GeomAdaptor_Curve ad(cc.curve);
  const double lo = std::min(t0, t1), hi = std::max(t0, t1);
  std::vector<Vec3> out;
  if (hi > lo) {
    GCPnts_QuasiUniformDeflection q(ad, std::max(chordal, 1e-12), lo, hi);
    if (q.IsDone() && q.NbPoints() >= 2)
      for (int i = 1; i <= q.NbPoints(); ++i) out.push_back(vec(q.Value(i)));
  }
  if (out.size() < 2) {
    out.clear();
    for (int i = 0; i <= 16; ++i) out.push_back(vec(cc.curve->Value(lo + (hi - lo) * i / 16.0)));
  }
  if (t0 > t1) std::reverse(out.begin(), out.end());
  return out;
}

std::string curve_problem(const Curve& c) {
  try {
    if (curve_cache(c).curve.IsNull()) return "bspline_curve: OpenCASCADE could not build it";
  } catch (const Standard_Failure& e) {
    return std::string("bspline_curve: OpenCASCADE refused the data: ") + e.GetMessageString();
  }
  return "";
}

// An analytic surface as an OpenCASCADE one (same parametrisation; see to_occt.cpp).
Handle(Geom_Surface) any_surface(const Surface& s) {
  auto ax3 = [](const Frame& f) { return gp_Ax3(pnt(f.origin), dir(f.z), dir(f.x)); };
  if (const auto* p = std::get_if<Plane>(&s)) return new Geom_Plane(ax3(p->frame));
  if (const auto* c = std::get_if<Cylinder>(&s)) return new Geom_CylindricalSurface(ax3(c->frame), c->radius);
  if (const auto* c = std::get_if<Cone>(&s)) {
    if (c->half_angle >= 0) return new Geom_ConicalSurface(ax3(c->frame), c->half_angle, c->radius);
    return new Geom_ConicalSurface(gp_Ax3(pnt(c->frame.origin), dir(-c->frame.z), dir(c->frame.x)), -c->half_angle, c->radius);
  }
  if (const auto* c = std::get_if<Sphere>(&s)) return new Geom_SphericalSurface(ax3(c->frame), c->radius);
  if (const auto* c = std::get_if<Torus>(&s)) return new Geom_ToroidalSurface(ax3(c->frame), c->major_radius, c->minor_radius);
  return surface_cache(s).surface;
}

// An OpenCASCADE intersection curve as ours: lines, circles and ellipses as such, the
// rest as exact B-splines (bounded ones only).
std::optional<Curve> from_geom(const Handle(Geom_Curve)& c) {
  Handle(Geom_Curve) basis = c;
  while (auto t = Handle(Geom_TrimmedCurve)::DownCast(basis)) basis = t->BasisCurve();
  if (auto l = Handle(Geom_Line)::DownCast(basis)) return Line{vec(l->Position().Location()), vec(gp_Vec(l->Position().Direction()))};
  auto frame = [](const gp_Ax2& a) { return Frame{vec(a.Location()), vec(gp_Vec(a.XDirection())), vec(gp_Vec(a.Direction()))}; };
  if (auto k = Handle(Geom_Circle)::DownCast(basis)) return Circle{frame(k->Position()), k->Radius()};
  if (auto e = Handle(Geom_Ellipse)::DownCast(basis)) return Ellipse{frame(e->Position()), e->MajorRadius(), e->MinorRadius()};
  if (Precision::IsInfinite(c->FirstParameter()) || Precision::IsInfinite(c->LastParameter())) return std::nullopt;
  std::string why;
  if (std::optional<BSplineCurve> b = to_bspline(c, &why)) return Curve(*b);
  return std::nullopt;
}

// The part of `s` (as OpenCASCADE's surface `gs`) whose parameters are within reach of
// `near`: the box of the points' feet, widened on each side by a quarter of its width and
// by at least the points' own spread (over the surface's speed there), within the
// surface's bounds; a periodic direction is cut where the feet leave their widest gap
// round the period, and left whole when the window would wrap. Null when no window can be
// told (a foot at a degenerate point, where the speed vanishes): the whole surface then.
Handle(Geom_Surface) window(const Surface& s, const Handle(Geom_Surface)& gs, const std::vector<Vec3>& near) {
  if (near.empty() || gs.IsNull()) return nullptr;
  constexpr std::size_t kFeet = 17;  // spread evenly along the points, both ends included
  const std::size_t n = std::min(kFeet, near.size());
  std::vector<double> us, vs;
  Bnd_Box box;
  for (std::size_t j = 0; j < n; ++j) {
    const Vec3& p = near[n == 1 ? 0 : j * (near.size() - 1) / (n - 1)];
    Vec2 uv;
    if (is_freeform(s)) {
      uv = surface_project(s, p);
    } else {
      GeomAPI_ProjectPointOnSurf proj(pnt(p), gs);
      if (!proj.IsDone() || proj.NbPoints() == 0) return nullptr;
      double u, v;
      proj.LowerDistanceParameters(u, v);
      uv = Vec2(u, v);
    }
    us.push_back(uv.x());
    vs.push_back(uv.y());
    box.Add(pnt(p));
  }
  const double spread = std::sqrt(box.SquareExtent());
  double ub0, ub1, vb0, vb1;
  gs->Bounds(ub0, ub1, vb0, vb1);
  // [lo, hi] of one direction's feet; periodic values unwrapped across their widest gap.
  auto range = [](std::vector<double> x, bool periodic, double period, double* lo, double* hi) {
    std::sort(x.begin(), x.end());
    *lo = x.front(), *hi = x.back();
    if (!periodic || x.size() < 2) return;
    double gap = x.front() + period - x.back();
    for (std::size_t i = 0; i + 1 < x.size(); ++i)
      if (x[i + 1] - x[i] > gap) gap = x[i + 1] - x[i], *lo = x[i + 1], *hi = x[i] + period;
  };
  double u0, u1, v0, v1;
  range(us, gs->IsUPeriodic(), gs->IsUPeriodic() ? gs->UPeriod() : 0, &u0, &u1);
  range(vs, gs->IsVPeriodic(), gs->IsVPeriodic() ? gs->VPeriod() : 0, &v0, &v1);
  gp_Pnt mid;
  gp_Vec du, dv;
  try {
    gs->D1(0.5 * (u0 + u1), 0.5 * (v0 + v1), mid, du, dv);
  } catch (const Standard_Failure&) {
    return nullptr;
  }
  if (!(du.Magnitude() > 1e-12 * (1 + spread)) || !(dv.Magnitude() > 1e-12 * (1 + spread))) return nullptr;
  const double wu = std::max(0.25 * (u1 - u0), spread / du.Magnitude());
  const double wv = std::max(0.25 * (v1 - v0), spread / dv.Magnitude());
  u0 -= wu, u1 += wu, v0 -= wv, v1 += wv;
  const bool u_whole = gs->IsUPeriodic() && u1 - u0 >= gs->UPeriod();
  const bool v_whole = gs->IsVPeriodic() && v1 - v0 >= gs->VPeriod();
  if (!gs->IsUPeriodic()) u0 = std::max(u0, ub0), u1 = std::min(u1, ub1);
  if (!gs->IsVPeriodic()) v0 = std::max(v0, vb0), v1 = std::min(v1, vb1);
  if (!(u1 > u0) || !(v1 > v0)) return nullptr;
  try {
    if (u_whole && v_whole) return nullptr;
    if (u_whole) return new Geom_RectangularTrimmedSurface(gs, v0, v1, Standard_False);
    if (v_whole) return new Geom_RectangularTrimmedSurface(gs, u0, u1, Standard_True);
    return new Geom_RectangularTrimmedSurface(gs, u0, u1, v0, v1);
  } catch (const Standard_Failure&) {
    return nullptr;
  }
}

// The last few intersections, for the pairs asked again: a repair refused and tried again
// in a later round, or in the run beautify starts over (CrankArm.brep at tolerance 0.175
// met the same pinch's edge curve a dozen times, two thirds of its time in
// GeomAPI_IntSS). The answer is a function of the two surfaces' data, the precision and
// the points it is asked near alone; all are kept by value (the surfaces' caches
// shared), compared by value.
struct IntersectionQuestion {
  Surface a, b;
  double precision;
  std::vector<Vec3> near;
  std::vector<Curve> curves;
};

RecentAnswers<IntersectionQuestion, 64>& recent_intersections() {
  static RecentAnswers<IntersectionQuestion, 64> memo;
  return memo;
}

std::vector<Curve> intersect_uncached(const Surface& a, const Surface& b, double precision, const std::vector<Vec3>& near);

std::vector<Curve> intersect(const Surface& a, const Surface& b, double precision, const std::vector<Vec3>* near_points) {
  static const std::vector<Vec3> kNowhere;
  const std::vector<Vec3>& near = near_points ? *near_points : kNowhere;
  if (auto known = recent_intersections().find(
          [&](const IntersectionQuestion& e) { return e.precision == precision && e.a == a && e.b == b && e.near == near; },
          [](const IntersectionQuestion& e) { return e.curves; }))
    return *known;
  std::vector<Curve> out = intersect_uncached(a, b, precision, near);
  recent_intersections().remember({a, b, precision, near, out});
  return out;
}

std::vector<Curve> intersect_uncached(const Surface& a, const Surface& b, double precision, const std::vector<Vec3>& near) {
  std::vector<Curve> out;
  try {
    Handle(Geom_Surface) ga = any_surface(a), gb = any_surface(b);
    if (Handle(Geom_Surface) wa = window(a, ga, near)) ga = wa;
    if (Handle(Geom_Surface) wb = window(b, gb, near)) gb = wb;
    GeomAPI_IntSS inter(ga, gb, std::max(precision, Precision::Confusion()));
    if (!inter.IsDone()) return out;
    for (int i = 1; i <= inter.NbLines(); ++i)
      if (std::optional<Curve> c = from_geom(inter.Line(i))) out.push_back(*c);
  } catch (const Standard_Failure&) {
    out.clear();
  }
  return out;
}

void surface_forget(const Surface& s) {
  SurfaceCache& c = surface_cache(s);
  std::lock_guard<std::mutex> lock(c.m);
  c.has_last = false;
}

const FreeformBackend kBackend{surface_d1,   surface_project, surface_bounds, surface_problem, curve_d1,
                               curve_project, curve_bounds,   curve_length,   curve_sample,    curve_problem,
                               intersect,     surface_forget};

}  // namespace

void register_freeform_backend() { set_freeform_backend(&kBackend); }

bool load_for_evaluation(GeomAdaptor_Surface& a, const Handle(Geom_Surface)& s) {
  double u0, u1, v0, v1;
  s->Bounds(u0, u1, v0, v1);
  const bool bounded = std::isfinite(u0) && std::isfinite(u1) && std::isfinite(v0) && std::isfinite(v1) &&
                       std::abs(u0) < 1e100 && std::abs(u1) < 1e100 && std::abs(v0) < 1e100 && std::abs(v1) < 1e100;
  if (bounded && u1 > u0 && v1 > v0) {
    const double du = 1e-9 * (u1 - u0), dv = 1e-9 * (v1 - v0);
    a.Load(s, u0 - du, u1 + du, v0 - dv, v1 + dv);
  } else {
    a.Load(s);
  }
  return bounded;
}

BSplineCurve bspline_data(const Handle(Geom_BSplineCurve)& c) {
  BSplineCurve out;
  out.degree = c->Degree();
  out.periodic = c->IsPeriodic();
  for (int i = 1; i <= c->NbPoles(); ++i) out.poles.push_back(vec(c->Pole(i)));
  if (c->IsRational())
    for (int i = 1; i <= c->NbPoles(); ++i) out.weights.push_back(c->Weight(i));
  for (int i = 1; i <= c->NbKnots(); ++i) {
    out.knots.push_back(c->Knot(i));
    out.multiplicities.push_back(c->Multiplicity(i));
  }
  return out;
}

BSplineSurface bspline_data(const Handle(Geom_BSplineSurface)& s) {
  BSplineSurface out;
  out.u_degree = s->UDegree();
  out.v_degree = s->VDegree();
  out.u_count = s->NbUPoles();
  out.v_count = s->NbVPoles();
  out.u_periodic = s->IsUPeriodic();
  out.v_periodic = s->IsVPeriodic();
  const bool rational = s->IsURational() || s->IsVRational();
  for (int i = 1; i <= out.u_count; ++i)
    for (int j = 1; j <= out.v_count; ++j) {
      out.poles.push_back(vec(s->Pole(i, j)));
      if (rational) out.weights.push_back(s->Weight(i, j));
    }
  for (int i = 1; i <= s->NbUKnots(); ++i) {
    out.u_knots.push_back(s->UKnot(i));
    out.u_multiplicities.push_back(s->UMultiplicity(i));
  }
  for (int i = 1; i <= s->NbVKnots(); ++i) {
    out.v_knots.push_back(s->VKnot(i));
    out.v_multiplicities.push_back(s->VMultiplicity(i));
  }
  return out;
}

std::optional<BSplineCurve> to_bspline(const Handle(Geom_Curve)& c, std::string* why) {
  try {
    if (auto b = Handle(Geom_BSplineCurve)::DownCast(c)) return bspline_data(b);
    Handle(Geom_BSplineCurve) b = GeomConvert::CurveToBSplineCurve(c);
    if (b.IsNull()) return *why = std::string(c->DynamicType()->Name()) + " cannot be converted to a B-spline", std::nullopt;
    return bspline_data(b);
  } catch (const Standard_Failure& e) {
    *why = std::string(c->DynamicType()->Name()) + " cannot be converted to a B-spline: " + e.GetMessageString();
  }
  return std::nullopt;
}

std::optional<BSplineSurface> to_bspline(const Handle(Geom_Surface)& s, std::string* why) {
  try {
    if (auto b = Handle(Geom_BSplineSurface)::DownCast(s)) return bspline_data(b);
    Handle(Geom_BSplineSurface) b = GeomConvert::SurfaceToBSplineSurface(s);
    if (b.IsNull()) return *why = std::string(s->DynamicType()->Name()) + " cannot be converted to a B-spline", std::nullopt;
    return bspline_data(b);
  } catch (const Standard_Failure& e) {
    *why = std::string(s->DynamicType()->Name()) + " cannot be converted to a B-spline: " + e.GetMessageString();
  }
  return std::nullopt;
}

Handle(Geom_Surface) geom_surface(const Surface& s) {
  if (!is_freeform(s)) return nullptr;
  return surface_cache(s).surface;
}

Handle(Geom_Curve) geom_curve(const Curve& c) {
  if (!is_freeform(c)) return nullptr;
  return curve_cache(c).curve;
}

}  // namespace kintsugi::geo::occt
