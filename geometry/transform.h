// Similarity transforms (rotation, uniform scale, translation) of points and of every
// curve and surface type: the audit's and the zoo's random rigid motions, and the
// property that scaling a model and its tolerance together changes no decision.
#pragma once

#include "geometry/types.h"

namespace kintsugi::geo {

struct Similarity {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // orthonormal, det +1
  double scale = 1.0;                                        // > 0
  Vec3 translation = Vec3::Zero();

  Vec3 point(const Vec3& p) const { return scale * (rotation * p) + translation; }
  Vec3 direction(const Vec3& d) const { return rotation * d; }
};

Frame transformed(const Frame& f, const Similarity& s);
Surface transformed(const Surface& surface, const Similarity& s);
Curve transformed(const Curve& curve, const Similarity& s);

}  // namespace kintsugi::geo
