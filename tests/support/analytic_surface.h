// Whether S is one of the analytic surfaces (those with a frame and radii), for the
// std::visit bodies in tests that move a frame or change a radius: free-form surfaces
// (geometry/freeform.h) have neither.
#pragma once

#include "geometry/types.h"

#include <type_traits>

namespace kintsugi::geo {

template <class S>
inline constexpr bool kAnalyticSurface = std::is_same_v<S, Plane> || std::is_same_v<S, Cylinder> ||
                                         std::is_same_v<S, Cone> || std::is_same_v<S, Sphere> ||
                                         std::is_same_v<S, Torus>;

}  // namespace kintsugi::geo
