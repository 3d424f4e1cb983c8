// Trimmed regions in parameter space: the boundary loops of a face mapped into (u, v),
// with periodic angles unwrapped and seams and poles resolved, so that the region is the
// inside of plain polygons (outer boundaries and holes, by nesting). Used by area.cpp.
//
// How loops are read (spec/geometry.md, "Trimmed regions"):
//  * Every loop is a closed 3D polyline (the last point may repeat the first). Loops
//    are oriented so that the region is on their left seen from the surface normal side
//    (outer counter-clockwise, holes clockwise); `reversed` says the face uses the
//    opposite sense. Orientation only matters for the cases marked (*) below; otherwise
//    in/out is decided by nesting alone.
//  * Angles are unwrapped continuously along each loop; a loop that comes back shifted by
//    ±2π winds around the surface.
//  * A loop containing the seam edge twice (closed surface cut open, B-rep style) unwraps
//    into an ordinary polygon spanning the full period: nothing special is needed.
//  * Two loops winding around the same way bound a band (cylinder or cone band, sphere
//    zone, torus band): the band is cut open at a seam chosen away from any hole.
//  * (*) One loop winding around a sphere bounds a cap: it is closed through the pole on
//    its left (so the equator traversed eastwards bounds the northern hemisphere). On a
//    cone it is closed through the apex.
//  * (*) A loop passing through a sphere pole or cone apex turns there by the angle that
//    keeps the region on its left (a lune from pole to pole, an octant, the full sphere
//    cut along one meridian with both seam sides at the same 3D points). A zero turn is
//    read as a full turn.
//  * (*) On a sphere or torus, an outer loop oriented clockwise bounds the complement:
//    the whole surface minus the loop's inside.
//  * No loops at all: the whole sphere or torus (an error for unbounded surfaces).
#pragma once

#include "geometry/types.h"

#include <string>
#include <vector>

namespace kintsugi::geo {

struct ParameterDomain {
  std::vector<std::vector<Vec2>> polygons;  // boundaries; in/out by nesting
  std::string problem;                      // non-empty: could not build the domain
};

ParameterDomain parameter_domain(const Surface& s, const std::vector<std::vector<Vec3>>& loops, bool reversed);

}  // namespace kintsugi::geo
