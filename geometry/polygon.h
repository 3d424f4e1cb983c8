// Normals and areas of (nearly) planar polygons given by their corners.
#pragma once

#include "geometry/types.h"

#include <vector>

namespace kintsugi::geo {

// Newell's vector of a closed polygon: normal to its best plane, pointing so that the
// corners turn counter-clockwise about it, with length twice the area. Computed about
// the first corner, not the origin: the cross products of absolute positions cancel
// catastrophically far from the origin (a 0.03-wide triangle at x = 3000 came out 1e-6
// rad off, its own corners 3e-8 from its plane), and the result must not depend on
// where the model sits.
Vec3 polygon_normal(const std::vector<Vec3>& corners);
inline double polygon_area(const std::vector<Vec3>& corners) { return polygon_normal(corners).norm() / 2; }

}  // namespace kintsugi::geo
