// Triangle meshes of a body's faces and polylines of its edges, for drawing (view/):
// curved faces as smooth meshes within a chordal tolerance, computed by our own
// geometry layer (geo::measure_region, which triangulates each face's trimmed region
// in parameter space with CGAL), so what is drawn is what detect and beautify measure.
#pragma once

#include "geometry/box.h"
#include "kernel/body.h"

#include <array>
#include <string>
#include <vector>

namespace kintsugi::view {

struct FaceMesh {
  FaceH face;
  // Vertices shared within the face (welded where the triangulation evaluated the same
  // point twice), triangles counter-clockwise seen from the face's outward side.
  std::vector<geo::Vec3> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::string problem;  // non-empty: not tessellated, and why (the face is still outlined by its edges)
};

struct EdgePolyline {
  EdgeH edge;
  std::vector<geo::Vec3> points;  // from the origin of half-edge 2e to its target
};

struct BodyMesh {
  std::vector<FaceMesh> faces;      // live faces, by handle
  std::vector<EdgePolyline> edges;  // live edges, by handle
  geo::Box bounds;                  // of every vertex and sample drawn
};

// The angle step (radians) that keeps a circle of radius `radius` within `chordal` of
// its chords: r (1 - cos(θ/2)) = chordal, kept within [0.01, 0.8] (at least 8 and at
// most 629 segments per turn).
double angle_step(double radius, double chordal);

// A chordal tolerance that looks smooth at the scale of the whole model.
double default_chordal(const Body& b);

FaceMesh tessellate_face(const Body& b, FaceH f, double chordal);
BodyMesh tessellate(const Body& b, double chordal);

}  // namespace kintsugi::view
