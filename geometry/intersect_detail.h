// Internal pieces of intersect.cpp, split by method.
#pragma once

#include "geometry/intersect.h"

namespace kintsugi::geo::detail {

// Length that turns `precision` into an angle: two directions are parallel when they
// deviate by less than precision over this length (the region diagonal, or the
// surfaces' size when no region is given).
double reference_length(const Surface& a, const Surface& b, const IntersectOptions& o);

// Surfaces of revolution about a common axis: nullopt when there is no common axis.
std::optional<SurfaceIntersection> intersect_coaxial(const Surface& a, const Surface& b, const IntersectOptions& o);

// Marching intersection inside o.region.
SurfaceIntersection intersect_march(const Surface& a, const Surface& b, const IntersectOptions& o);

}  // namespace kintsugi::geo::detail
