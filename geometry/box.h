// Axis-aligned bounding box: the region of interest for intersections and the extent
// reported for a measured face.
#pragma once

#include "geometry/types.h"

#include <limits>

namespace kintsugi::geo {

struct Box {
  Vec3 min = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 max = Vec3::Constant(-std::numeric_limits<double>::infinity());

  static Box around(const Vec3& centre, double half_extent) {
    return Box{centre.array() - half_extent, centre.array() + half_extent};
  }
  bool empty() const { return (min.array() > max.array()).any(); }
  void add(const Vec3& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  Vec3 centre() const { return 0.5 * (min + max); }
  double diagonal() const { return empty() ? 0.0 : (max - min).norm(); }
  bool contains(const Vec3& p, double margin = 0.0) const {
    return (p.array() >= min.array() - margin).all() && (p.array() <= max.array() + margin).all();
  }
};

// Distance between two boxes (0 where they overlap): no point of one is nearer the other.
inline double box_gap(const Box& a, const Box& b) {
  return (a.min - b.max).cwiseMax(b.min - a.max).cwiseMax(0.0).norm();
}

}  // namespace kintsugi::geo
