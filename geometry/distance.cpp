#include "geometry/distance.h"

#include "geometry/box.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <tuple>

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

namespace {

// A run of consecutive segments of a polyline and its bounding box.
struct Chunk {
  std::size_t first, last;  // segments [first, last)
  Box box;
};

// Segments are grouped in runs of kChunk; the box of a run bounds every segment in it.
constexpr std::size_t kChunk = 32;

std::vector<Chunk> chunks(const std::vector<Vec3>& p, std::size_t segments) {
  std::vector<Chunk> out;
  for (std::size_t i = 0; i < segments; i += kChunk) {
    Chunk c{i, std::min(segments, i + kChunk), {}};
    for (std::size_t k = c.first; k <= c.last && k < p.size(); ++k) c.box.add(p[k]);
    out.push_back(c);
  }
  return out;
}


}  // namespace

ClosestPair polyline_polyline(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  if (a.empty() || b.empty()) throw std::invalid_argument("polyline_polyline: a polyline has no points");
  // Treat a single point as a zero-length segment.
  const std::size_t na = std::max<std::size_t>(1, a.size() - 1), nb = std::max<std::size_t>(1, b.size() - 1);
  auto seg = [](const std::vector<Vec3>& p, std::size_t i, Vec3& s0, Vec3& s1) {
    s0 = p[i];
    s1 = p[std::min(i + 1, p.size() - 1)];
  };
  // Boundaries sampled at a thousandth of the tolerance have thousands of segments:
  // every pair would be 10^8 segment tests for two circles. Runs of segments are paired
  // first, nearest boxes first, and a pair of runs is opened only while its boxes are
  // no farther apart than the best distance so far: close to linear for polylines that
  // come close in few places.
  const std::vector<Chunk> ca = chunks(a, na), cb = chunks(b, nb);
  struct RunPair {
    double gap;
    std::size_t x, y;
  };
  std::vector<RunPair> order;
  order.reserve(ca.size() * cb.size());
  for (std::size_t x = 0; x < ca.size(); ++x)
    for (std::size_t y = 0; y < cb.size(); ++y) order.push_back({box_gap(ca[x].box, cb[y].box), x, y});
  std::sort(order.begin(), order.end(), [](const RunPair& l, const RunPair& r) {
    return l.gap != r.gap ? l.gap < r.gap : std::tie(l.x, l.y) < std::tie(r.x, r.y);
  });
  ClosestPair best;
  best.distance = std::numeric_limits<double>::infinity();
  // Among equally near pairs the first in (i, j) order wins, whatever order the runs
  // are opened in: the answer is the one a scan of all pairs gives.
  auto better = [&](const ClosestPair& c, std::size_t i, std::size_t j) {
    if (c.distance != best.distance) return c.distance < best.distance;
    return std::tie(i, j) < std::tie(best.segment_a, best.segment_b);
  };
  for (const RunPair& rp : order) {
    if (rp.gap > best.distance) break;  // every later pair of runs is farther still
    for (std::size_t i = ca[rp.x].first; i < ca[rp.x].last; ++i) {
      Vec3 p0, p1;
      seg(a, i, p0, p1);
      const Vec3 mid = 0.5 * (p0 + p1);
      const double ra = 0.5 * (p1 - p0).norm();
      for (std::size_t j = cb[rp.y].first; j < cb[rp.y].last; ++j) {
        Vec3 q0, q1;
        seg(b, j, q0, q1);
        if ((mid - 0.5 * (q0 + q1)).norm() - ra - 0.5 * (q1 - q0).norm() > best.distance) continue;
        ClosestPair c = segment_segment(p0, p1, q0, q1);
        if (better(c, i, j)) {
          best = c;
          best.segment_a = i, best.segment_b = j;
        }
      }
    }
  }
  return best;
}

}  // namespace kintsugi::geo
