#include "geometry/frame.h"

#include <sstream>

namespace kintsugi::geo {

Frame frame_from_axis(const Vec3& origin, const Vec3& axis, const Vec3& hint) {
  Frame f;
  f.origin = origin;
  f.z = axis.normalized();
  Vec3 x = hint - hint.dot(f.z) * f.z;
  if (x.norm() < 1e-9 * std::max(1.0, hint.norm())) {
    // No usable hint: the world axis least aligned with z keeps x well conditioned.
    Eigen::Index i = 0;
    f.z.cwiseAbs().minCoeff(&i);
    const Vec3 e = Vec3::Unit(i);
    x = e - e.dot(f.z) * f.z;
  }
  f.x = x.normalized();
  return f;
}

std::string frame_problem(const Frame& f, double eps) {
  std::ostringstream out;
  if (!f.origin.allFinite() || !f.x.allFinite() || !f.z.allFinite()) {
    out << "frame has a non-finite component";
  } else if (std::abs(f.x.norm() - 1.0) > eps) {
    out << "frame x is not unit (|x| = " << f.x.norm() << ")";
  } else if (std::abs(f.z.norm() - 1.0) > eps) {
    out << "frame z is not unit (|z| = " << f.z.norm() << ")";
  } else if (std::abs(f.x.dot(f.z)) > eps) {
    out << "frame x and z are not orthogonal (x·z = " << f.x.dot(f.z) << ")";
  }
  return out.str();
}

}  // namespace kintsugi::geo
