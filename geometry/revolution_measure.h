// Exact area and extreme points of regions on spheres and ring tori, for the fast
// measure (AreaOptions::area_and_bounds_only) that detection asks for on every face.
//
// On both surfaces the area element depends on v alone: r²·cos v on a sphere
// (v ∈ [-π/2, π/2]), r·|R + r cos v| on a torus. Over a parameter-space triangle the
// area is then ∫ width(v) · (A + B cos v) dv with a width that is linear on each side of
// the middle vertex: a closed form, exact for any triangle however long. The quadrature
// it replaces needed the triangle cut into pieces 0.05 rad across and seven cosines a
// piece (a hemisphere: some 16,000 pieces), which was most of the audit's time.
//
// Bounds: a smooth surface's extent along a direction d is reached on the region's
// boundary or at an interior critical point of the height d·P(u, v). On a sphere those
// are the two points c ± r·d; on a torus four points in the plane through the axis and d,
// or, when d is along the axis, the whole top and bottom circles. So the region's box is
// the boundary's box plus those of the candidates (for d = x, y, z) that lie in the
// region: exact, where a grid of evaluated points fell short by up to r·step²/8.
#pragma once

#include "geometry/types.h"

#include <array>
#include <optional>
#include <vector>

namespace kintsugi::geo {

// The exact area of the surface over the parameter-space triangle, or nothing when the
// closed form does not apply (not a sphere or a ring torus; a sphere triangle reaching
// beyond a pole's latitude, where the area element's |cos v| folds).
std::optional<double> exact_triangle_area(const Surface& s, const std::array<Vec2, 3>& t);

// True for the surfaces exact_triangle_area may answer for (spheres and ring tori).
bool has_exact_triangle_area(const Surface& s);

// Where the height along a coordinate axis may have an interior extremum, in (u, v):
// isolated points (`points`, to be tried at every 2π shift of their periodic
// coordinates) and lines v = const along which the height is constant (`circles`: a
// sphere's poles, a torus's top and bottom circles when its axis is a coordinate axis).
struct ExtremeCandidates {
  std::vector<Vec2> points;
  std::vector<double> circles;
};
ExtremeCandidates extreme_candidates(const Surface& s);

}  // namespace kintsugi::geo
