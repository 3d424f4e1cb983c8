// Area, centroid, bounding box and a tessellation of a trimmed region of a surface
// (paper 4.4 sliver faces: area / bounding-box diagonal; 4.6 small faces: area).
//
// The region is given by its boundary loops as closed 3D polylines sampled densely by the
// caller (e.g. with sample_curve). How loops are read - seams, poles, bands, caps,
// orientation - is documented in parameter_domain.h.
//
// Method: map the loops into parameter space, triangulate the domain with CGAL's
// constrained Delaunay triangulation (in/out by nesting), split every triangle so that
// no angular parameter varies by more than `max_angle_step` across a piece, and integrate
// the exact area element |∂P/∂u × ∂P/∂v| with a degree-5 (7-point) rule per piece. The
// area element is linear in the parameters for planes, cylinders and cones, so there the
// integral is exact for the parameter-space polygon; for spheres and tori the relative
// quadrature error is ~1e-9 at the default step. The only other error is the caller's
// sampling of curved boundaries (the parameter-space polygon is the interpolation of
// the samples).
#pragma once

#include "geometry/box.h"
#include "geometry/types.h"

#include <array>
#include <string>
#include <vector>

namespace kintsugi::geo {

struct Tessellation {
  std::vector<Vec3> vertices;
  // Counter-clockwise seen from the surface normal side (from the other side when
  // `reversed`). Vertices are not shared between the pieces of different domain
  // triangles (no welding).
  std::vector<std::array<int, 3>> triangles;
};

struct AreaOptions {
  bool reversed = false;         // loops are oriented against the surface normal
  double max_angle_step = 0.05;  // radians, see above
  // Only the area and the bounds are wanted (detection's small faces and slivers): no
  // tessellation is kept and the centroid is not computed (left zero). On planes,
  // cylinders and cones each domain triangle is then integrated whole — the area element
  // is at most linear in the parameters there, so the rule is exact — and the bounds are
  // the boundary's: each ruling meets the region in segments that end on its boundary (or
  // at a cone's apex, added when the region reaches it), so the region lies in the
  // boundary's convex hull.
  bool area_and_bounds_only = false;
  // Only the tessellation (and the bounds) are wanted: the same triangles, but no
  // quadrature, so area and centroid are left zero. The quadrature evaluates the surface
  // fourteen times a triangle; a sphere's or torus's thousands of grid triangles cost 40
  // ms, most of the zoo's time choosing where a face gap goes.
  bool mesh_only = false;
  // Free-form surfaces: the region's parameter box is split into this many cells a side
  // for Steiner points (add_grid), so that the triangles are small where the area element
  // varies. Detection's coarse pass, which only has to show a face far from small and
  // thin by a wide margin (repair/detect.cpp), takes fewer.
  int freeform_grid = kFreeformGrid;
  static constexpr int kFreeformGrid = 16;
};

struct RegionMeasure {
  double area = 0.0;
  Vec3 centroid = Vec3::Zero();
  Box bounds;               // of the tessellation and the loop points
  Tessellation mesh;
  std::string problem;      // non-empty: nothing measured, and why
  bool ok() const { return problem.empty(); }
};

RegionMeasure measure_region(const Surface& s, const std::vector<std::vector<Vec3>>& loops,
                             const AreaOptions& options = {});

}  // namespace kintsugi::geo
