#include "geometry/polygon.h"

namespace kintsugi::geo {

Vec3 polygon_normal(const std::vector<Vec3>& corners) {
  Vec3 n = Vec3::Zero();
  for (std::size_t i = 1; i + 1 < corners.size(); ++i) n += (corners[i] - corners[0]).cross(corners[i + 1] - corners[0]);
  return n;
}

}  // namespace kintsugi::geo
