// Marching surface-surface intersection.
//
// 1. Seeds: each surface is sampled on a seed_grid × seed_grid parameter grid (angles over
//    their full period, linear parameters over the region); every grid edge along which
//    the signed distance to the other surface changes sign gives a seed, refined onto
//    both surfaces by Newton steps (minimum-norm steps on the two signed distances).
// 2. Tracing: from a seed not yet covered, step along t = n_a × n_b, correct the
//    predicted point onto both surfaces, and accept the step only if the corrected point
//    is where a step of that length should land, the tangent turned by < 20°, and the
//    chord midpoint lies within chordal_error of the curve (the midpoint is itself
//    projected onto both surfaces and the distance measured). Otherwise halve the step.
//    A step shrinking below ~10·precision means a singular point (tangency, crossing,
//    apex): the branch ends there.
// 3. A branch ends when it returns to its seed (closed polyline: last point == first),
//    leaves the region (its last vertex is the first one outside), or hits a singular
//    point; open branches are traced in both directions from the seed.
#include "geometry/distance.h"
#include "geometry/frame.h"
#include "geometry/intersect_detail.h"
#include "geometry/surface.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace kintsugi::geo::detail {

namespace {

bool bounded(const Surface& s) { return std::holds_alternative<Sphere>(s) || std::holds_alternative<Torus>(s); }

struct Range {
  double lo, hi;
};

// Parameter box of `s` worth sampling: the whole period for angles, the region's extent
// for linear parameters (nullopt if that is unbounded).
std::optional<std::array<Range, 2>> sample_ranges(const Surface& s, const Box& region) {
  if (std::holds_alternative<Sphere>(s)) return std::array<Range, 2>{{{-kPi, kPi}, {-kPi / 2, kPi / 2}}};
  if (std::holds_alternative<Torus>(s)) return std::array<Range, 2>{{{-kPi, kPi}, {-kPi, kPi}}};
  if (region.empty()) return std::nullopt;
  Range r0{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()}, r1 = r0;
  for (int i = 0; i < 8; ++i) {
    const Vec3 corner((i & 1) ? region.max.x() : region.min.x(), (i & 2) ? region.max.y() : region.min.y(),
                      (i & 4) ? region.max.z() : region.min.z());
    Vec2 uv = Vec2::Zero();
    if (const auto* p = std::get_if<Plane>(&s)) {
      const Vec3 l = to_local(p->frame, corner);
      uv = Vec2(l.x(), l.y());
    } else if (const auto* c = std::get_if<Cylinder>(&s)) {
      uv = Vec2(0, to_local(c->frame, corner).z());
    } else if (const auto* c = std::get_if<Cone>(&s)) {
      uv = Vec2(0, to_local(c->frame, corner).z() / std::cos(c->half_angle));
    }
    r0 = {std::min(r0.lo, uv.x()), std::max(r0.hi, uv.x())};
    r1 = {std::min(r1.lo, uv.y()), std::max(r1.hi, uv.y())};
  }
  if (!std::holds_alternative<Plane>(s)) r0 = {-kPi, kPi};
  return std::array<Range, 2>{{r0, r1}};
}

class Marcher {
 public:
  Marcher(const Surface& a, const Surface& b, const IntersectOptions& o) : a_(a), b_(b), o_(o) {
    const double len = reference_length(a, b, o);
    eps_ = o.precision;
    h_max_ = len / 16;
    h_min_ = 10 * eps_ + 1e-3 * o.chordal_error;
    cover_ = 4 * o.chordal_error + 10 * eps_;
  }

  // Newton onto both surfaces; false if it does not reach `precision` or the normals are
  // parallel (tangency).
  bool project(Vec3& x) const {
    for (int it = 0; it < 40; ++it) {
      const SurfacePoint ca = closest_point(a_, x), cb = closest_point(b_, x);
      const double fa = ca.distance, fb = cb.distance;
      if (std::max(std::abs(fa), std::abs(fb)) <= 0.01 * eps_) return true;
      const double c = ca.normal.dot(cb.normal), det = 1 - c * c;
      if (det < 1e-12) return false;
      const double la = (fa - c * fb) / det, lb = (fb - c * fa) / det;
      const Vec3 step = -(la * ca.normal + lb * cb.normal);
      if (!(step.norm() < 4 * h_max_)) return false;  // diverging (or NaN)
      x += step;
      if (step.norm() <= 1e-3 * eps_) break;
    }
    return std::max(std::abs(signed_distance(a_, x)), std::abs(signed_distance(b_, x))) <= eps_;
  }

  std::optional<Vec3> tangent(const Vec3& x) const {
    const Vec3 t = closest_point(a_, x).normal.cross(closest_point(b_, x).normal);
    if (t.norm() < 1e-9) return std::nullopt;
    return t.normalized();
  }

  // Appends projected midpoints between p (already in `out`) and q (not appended) until
  // every chord's midpoint is within the chordal error of the curve; false when a
  // midpoint does not project.
  bool close_chord(const Vec3& p, const Vec3& q, std::vector<Vec3>& out, int depth) const {
    Vec3 mid = 0.5 * (p + q);
    const Vec3 chord_mid = mid;
    if (!project(mid)) return false;
    if ((mid - chord_mid).norm() <= o_.chordal_error) return true;
    if (depth == 0) return false;
    if (!close_chord(p, mid, out, depth - 1)) return false;
    out.push_back(mid);
    return close_chord(mid, q, out, depth - 1);
  }

  bool inside(const Vec3& x) const { return o_.region.empty() || o_.region.contains(x); }

  std::vector<Vec3> seeds() const {
    std::vector<Vec3> out;
    for (int side = 0; side < 2; ++side) {
      const Surface& s = side == 0 ? a_ : b_;
      const Surface& other = side == 0 ? b_ : a_;
      const auto ranges = sample_ranges(s, o_.region);
      if (!ranges) continue;
      const int n = std::max(4, o_.seed_grid);
      std::vector<Vec3> pts((n + 1) * (n + 1));
      std::vector<double> dist(pts.size());
      for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) {
          const Vec2 uv((*ranges)[0].lo + ((*ranges)[0].hi - (*ranges)[0].lo) * i / n,
                        (*ranges)[1].lo + ((*ranges)[1].hi - (*ranges)[1].lo) * j / n);
          pts[i * (n + 1) + j] = evaluate(s, uv);
          dist[i * (n + 1) + j] = signed_distance(other, pts[i * (n + 1) + j]);
        }
      auto edge = [&](int p, int q) {
        const double dp = dist[p], dq = dist[q];
        if (!(dp * dq < 0 || dp == 0)) return;
        Vec3 x = dp == 0 ? pts[p] : Vec3(pts[p] + (dp / (dp - dq)) * (pts[q] - pts[p]));
        if (project(x) && inside(x)) out.push_back(x);
      };
      for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) {
          if (i < n) edge(i * (n + 1) + j, (i + 1) * (n + 1) + j);
          if (j < n) edge(i * (n + 1) + j, i * (n + 1) + j + 1);
        }
    }
    return out;
  }

  // Walk from `seed` in direction sign·t. `closed` is set when the walk returned to the seed.
  std::vector<Vec3> walk(const Vec3& seed, double sign, bool& closed) const {
    closed = false;
    std::vector<Vec3> pts{seed};
    const auto t0 = tangent(seed);
    if (!t0) return pts;
    Vec3 x = seed, t = sign * *t0;
    double h = h_max_ / 8;
    constexpr std::size_t kMaxPoints = 200000;
    const double cos_turn = std::cos(0.35);
    while (pts.size() < kMaxPoints) {
      if (h < h_min_) break;  // singular point: the branch ends here
      Vec3 y = x + h * t;
      if (!project(y)) { h /= 2; continue; }
      const Vec3 chord = y - x;
      const double len = chord.norm();
      const auto ty = tangent(y);
      if (!ty || len < 0.3 * h || len > 2 * h || chord.dot(t) <= 0) { h /= 2; continue; }
      // n_a × n_b keeps its sense along a regular branch; a flip means we crossed or
      // jumped to another branch.
      const Vec3 tn = sign * *ty;
      if (tn.dot(t) < cos_turn) { h /= 2; continue; }
      Vec3 mid = 0.5 * (x + y);
      const Vec3 chord_mid = mid;
      if (!project(mid) || (mid - chord_mid).norm() > o_.chordal_error) { h /= 2; continue; }
      // Back at the seed: the seed lies on this chord's arc.
      if (pts.size() >= 3) {
        const ClosestPair c = point_segment(seed, x, y);
        if (c.distance <= cover_ && c.t > 0) {
          // The closing chord x–seed is not the chord x–y checked above: bring it
          // within the chordal error too.
          const std::size_t before = pts.size();
          if (!close_chord(x, seed, pts, 8)) {
            pts.resize(before);
            h /= 2;
            continue;
          }
          pts.push_back(seed);
          closed = true;
          return pts;
        }
      }
      pts.push_back(y);
      if (!inside(y)) break;  // left the region: keep the first outside vertex
      x = y;
      t = tn;
      h = std::min(1.5 * h, h_max_);
    }
    return pts;
  }

  SurfaceIntersection run() const {
    SurfaceIntersection out;
    out.marched = true;
    if (o_.region.empty() && !bounded(a_) && !bounded(b_)) {
      out.kind = IntersectionKind::failed;
      out.problem = std::string("marching a ") + surface_type_name(a_) + "-" + surface_type_name(b_) +
                    " intersection needs a region (both surfaces are unbounded)";
      return out;
    }
    std::vector<std::vector<Vec3>> traced;
    for (const Vec3& s : seeds()) {
      bool covered = false;
      for (const auto& p : traced) covered = covered || point_polyline(s, p).distance <= cover_;
      if (covered) continue;
      bool closed = false;
      std::vector<Vec3> fwd = walk(s, 1.0, closed);
      if (!closed) {
        bool unused = false;
        std::vector<Vec3> back = walk(s, -1.0, unused);
        std::reverse(back.begin(), back.end());
        back.insert(back.end(), fwd.begin() + 1, fwd.end());
        fwd = std::move(back);
      }
      if (fwd.size() >= 2) traced.push_back(std::move(fwd));
    }
    for (auto& p : traced) out.curves.push_back(Polyline{std::move(p), o_.chordal_error});
    out.kind = out.curves.empty() ? IntersectionKind::empty : IntersectionKind::curves;
    return out;
  }

 private:
  const Surface& a_;
  const Surface& b_;
  const IntersectOptions& o_;
  double eps_, h_max_, h_min_, cover_;
};

}  // namespace

SurfaceIntersection intersect_march(const Surface& a, const Surface& b, const IntersectOptions& o) {
  return Marcher(a, b, o).run();
}

}  // namespace kintsugi::geo::detail
