// Geometry of kernel elements: the measures repairs decide with (paper 3.1, 4.4, 4.6),
// computed from the analytic geometry attached to the topology.
//
// Curved boundaries are sampled with a chordal error of `chordal` (a length; callers
// pass a fraction of the modelling precision or of the tolerance, so results scale with
// the model). An edge without a curve is taken as the straight segment between its
// vertices.
#pragma once

#include "geometry/area.h"
#include "geometry/box.h"
#include "kernel/body.h"

#include <optional>
#include <vector>

namespace kintsugi {

// Points along the edge of h, from origin(h) to target(h), both included.
std::vector<geo::Vec3> halfedge_polyline(const Body& b, HalfedgeH h, double chordal);
// A box containing halfedge_polyline(b, h, chordal), found without sampling where the
// curve allows (a line's ends; a circle's box with the ends, whose samples between lie
// on the circle); the polyline's own box otherwise.
geo::Box halfedge_box(const Body& b, HalfedgeH h, double chordal);
double edge_length(const Body& b, EdgeH e);
// The face's loops as closed polylines (outer first), for geo::measure_region.
std::vector<std::vector<geo::Vec3>> face_boundary(const Body& b, FaceH f, double chordal);
// The points that stand for the face when its surface is compared with another of the
// same type (geo::surface_deviation, in detection and in pass 8): its boundary samples —
// for a planar face those of its outer loop alone. A point's signed distance to another
// plane is affine in the point, so over a planar face it is largest at a corner of the
// face's convex hull, which is on the outer loop (the other loops lie inside it): the
// deviation of two planes is the same either way, and a plate with a hole per feature
// costs four edges instead of every hole.
std::vector<geo::Vec3> surface_samples(const Body& b, FaceH f, double chordal);
// Area, centroid, bounding box and tessellation of a face; `problem` says why not. With
// `area_and_bounds_only`, no tessellation or centroid (geo::AreaOptions says how that
// is cheaper).
geo::RegionMeasure face_measure(const Body& b, FaceH f, double chordal, bool area_and_bounds_only = false,
                                int freeform_grid = geo::AreaOptions::kFreeformGrid);
// Only the area and bounding box: for a planar face, from its boundary polylines alone
// (the signed areas of its loops about its outward normal; no triangulation, which is
// what makes measuring a large model costly); otherwise face_measure's area and bounds
// only. nullopt where face_measure reports a problem or the loops do not enclose a
// positive area.
struct AreaAndBounds {
  double area;
  geo::Box bounds;
};
// `freeform_grid`: geo::AreaOptions::freeform_grid.
std::optional<AreaAndBounds> face_area_and_bounds(const Body& b, FaceH f, double chordal,
                                                  int freeform_grid = geo::AreaOptions::kFreeformGrid);
double vertex_edge_distance(const Body& b, VertexH v, EdgeH e, double chordal);
double edge_edge_distance(const Body& b, EdgeH e1, EdgeH e2, double chordal);
// Bounding box of the vertices, the sampled edges and the faces that bulge beyond their
// edges (spheres, tori).
geo::Box body_bounds(const Body& b);
// The model size the tolerance model scales with (geometry/tolerance.h): the diagonal of
// body_bounds. The one measure of a model's size; 0 for an empty body.
double model_size(const Body& b);

}  // namespace kintsugi
