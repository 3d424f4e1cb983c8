// Solids built only from Euler operators, with consistent analytic geometry: the test
// fixtures and `kintsugi generate` models. Each returns a body that passes the full
// topology check; outer loops run counter-clockwise seen from outside.
//
// Bad parameters (non-positive sizes, fewer than 3 polygon points, a polygon that is
// not counter-clockwise) throw std::invalid_argument naming the parameter.
#pragma once

#include "kernel/body.h"

#include <vector>

namespace kintsugi::build {

// Axis-aligned box with one corner at the origin.
Body box(double sx = 1, double sy = 1, double sz = 1);
// Prism over a counter-clockwise polygon in the xy-plane, extruded by `height` along +z.
Body prism(const std::vector<geo::Vec2>& polygon, double height);
// Pyramid over a counter-clockwise polygon in the xy-plane, apex at `height` above the
// polygon's vertex centroid.
Body pyramid(const std::vector<geo::Vec2>& polygon, double height);
// Cylinder of the given radius on the xy-plane, axis +z: 3 faces, 3 edges, 2 vertices.
Body cylinder(double radius, double height);
// Cone with its base circle on the xy-plane and apex at (0, 0, height): 2 faces.
Body cone(double radius, double height);
// Sphere about the origin: one face, bounded by a seam edge between the poles.
Body sphere(double radius);
// Torus about the z-axis: one face, two circular edges through one vertex (genus 1).
Body torus(double major_radius, double minor_radius);
// A unit box whose six faces are each cut into k×k planar quads, k chosen so that
// 6k² is about `faces` (k ≥ 1). Adjacent quads of one side are coplanar by design:
// this is a size benchmark, not a defect-free model for detection.
Body grid_box(std::size_t faces, double size = 1.0);

// A regular n-gon of circumradius r about the origin, counter-clockwise.
std::vector<geo::Vec2> regular_polygon(int n, double r);

// Gives every face of a polyhedral body the plane of its outer loop (Newell normal,
// through the loop's vertex centroid) and every edge the line through its vertices.
void assign_planar_geometry(Body& b);

}  // namespace kintsugi::build
