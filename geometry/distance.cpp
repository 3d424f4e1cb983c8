#include "geometry/distance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace kintsugi::geo {

ClosestPair point_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  ClosestPair r;
  r.on_a = p;
  r.on_b = a + t * ab;
  r.t = t;
  r.distance = (p - r.on_b).norm();
  return r;
}

ClosestPair segment_segment(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1) {
  // Minimise |p0 + s·d1 - q0 - t·d2| over the unit square: the unconstrained optimum
  // if it lies inside, else the best of the four edge problems (each a point-segment
  // problem). The edge cases also cover parallel and zero-length segments.
  const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), b = d1.dot(d2);
  const double c = d1.dot(r), f = d2.dot(r);
  const double den = a * e - b * b;
  ClosestPair best;
  best.distance = std::numeric_limits<double>::infinity();
  // Interior solution only when the segments are clearly not parallel; otherwise the
  // edges give the answer and the division would amplify rounding.
  if (den > 1e-14 * a * e && a > 0 && e > 0) {
    const double s = (b * f - c * e) / den, t = (a * f - b * c) / den;
    if (s >= 0 && s <= 1 && t >= 0 && t <= 1) {
      best.s = s, best.t = t;
      best.on_a = p0 + s * d1, best.on_b = q0 + t * d2;
      best.distance = (best.on_a - best.on_b).norm();
      return best;
    }
  }
  auto consider = [&](const ClosestPair& c2, bool swapped, double fixed) {
    if (c2.distance >= best.distance) return;
    best.distance = c2.distance;
    if (!swapped) {  // point on a at s = fixed, nearest on b
      best.on_a = c2.on_a, best.on_b = c2.on_b, best.s = fixed, best.t = c2.t;
    } else {  // point on b at t = fixed, nearest on a
      best.on_a = c2.on_b, best.on_b = c2.on_a, best.s = c2.t, best.t = fixed;
    }
  };
  consider(point_segment(p0, q0, q1), false, 0.0);
  consider(point_segment(p1, q0, q1), false, 1.0);
  consider(point_segment(q0, p0, p1), true, 0.0);
  consider(point_segment(q1, p0, p1), true, 1.0);
  return best;
}

ClosestPair point_polyline(const Vec3& p, const std::vector<Vec3>& polyline) {
  if (polyline.empty()) throw std::invalid_argument("point_polyline: polyline has no points");
  if (polyline.size() == 1) return point_segment(p, polyline[0], polyline[0]);
  ClosestPair best;
  best.distance = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < polyline.size(); ++i) {
    ClosestPair c = point_segment(p, polyline[i], polyline[i + 1]);
    if (c.distance < best.distance) {
      best = c;
      best.segment_b = i;
    }
  }
  return best;
}

ClosestPair polyline_polyline(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  if (a.empty() || b.empty()) throw std::invalid_argument("polyline_polyline: a polyline has no points");
  // Treat a single point as a zero-length segment.
  const std::size_t na = std::max<std::size_t>(1, a.size() - 1), nb = std::max<std::size_t>(1, b.size() - 1);
  auto seg = [](const std::vector<Vec3>& p, std::size_t i, Vec3& s0, Vec3& s1) {
    s0 = p[i];
    s1 = p[std::min(i + 1, p.size() - 1)];
  };
  struct Sphere {
    Vec3 c;
    double r;
  };
  std::vector<Sphere> sb(nb);
  for (std::size_t j = 0; j < nb; ++j) {
    Vec3 q0, q1;
    seg(b, j, q0, q1);
    sb[j] = {0.5 * (q0 + q1), 0.5 * (q1 - q0).norm()};
  }
  ClosestPair best;
  best.distance = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < na; ++i) {
    Vec3 p0, p1;
    seg(a, i, p0, p1);
    const Vec3 ca = 0.5 * (p0 + p1);
    const double ra = 0.5 * (p1 - p0).norm();
    for (std::size_t j = 0; j < nb; ++j) {
      if ((ca - sb[j].c).norm() - ra - sb[j].r >= best.distance) continue;
      Vec3 q0, q1;
      seg(b, j, q0, q1);
      ClosestPair c = segment_segment(p0, p1, q0, q1);
      if (c.distance < best.distance) {
        best = c;
        best.segment_a = i, best.segment_b = j;
      }
    }
  }
  return best;
}

}  // namespace kintsugi::geo
