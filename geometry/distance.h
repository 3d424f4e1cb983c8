// Shortest distances between points, segments and polylines: "distance between two
// edges" and "vertex to edge" (paper section 4.2, pinched faces) on sampled edges.
#pragma once

#include "geometry/types.h"

#include <cstddef>
#include <vector>

namespace kintsugi::geo {

struct ClosestPair {
  double distance = 0.0;
  Vec3 on_a = Vec3::Zero(), on_b = Vec3::Zero();
  // Segment index and position along it in [0, 1] on each side (0 for a point).
  std::size_t segment_a = 0, segment_b = 0;
  double s = 0.0, t = 0.0;
};

// Nearest point of segment [a, b] to p; `t` in [0, 1]. A zero-length segment is its point.
ClosestPair point_segment(const Vec3& p, const Vec3& a, const Vec3& b);
// Nearest points of [p0, p1] and [q0, q1]; robust for parallel and degenerate segments
// (on parallel overlapping segments one of the equally near pairs is returned).
ClosestPair segment_segment(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1);
// Nearest point of a polyline (≥ 1 point) to p; segment_b / t locate it on the polyline.
ClosestPair point_polyline(const Vec3& p, const std::vector<Vec3>& polyline);
// Nearest points of two polylines (each ≥ 1 point). Exact (up to rounding) over all
// segment pairs; runs of segments whose boxes are farther apart than the best distance
// found are skipped, so long polylines that come close in few places cost about their
// length. Among equally near pairs, the first in segment order (a's, then b's).
ClosestPair polyline_polyline(const std::vector<Vec3>& a, const std::vector<Vec3>& b);

}  // namespace kintsugi::geo
