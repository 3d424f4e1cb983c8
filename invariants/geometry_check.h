// Geometric consistency of a body (spec/invariants.md, spec/tolerances.md): within the
// modelling precision,
//   * every vertex lies on the curve of each of its edges and the surface of each face
//     around it (`vertex_on_curve`, `vertex_on_surface`);
//   * every edge lies on the surfaces of both faces beside it (`edge_on_surface`,
//     checked at points sampled along the edge);
//   * every planar face's outer loop turns counter-clockwise about its outward normal
//     (surface normal, flipped when the face is not `same_sense`) (`face_sense`);
//   * every face has a surface and every edge a curve (`face_without_surface`,
//     `edge_without_curve`).
// Each violation carries its distance; the report also gives the largest deviation
// found anywhere, with the elements it belongs to, even when it is within precision.
#pragma once

#include "invariants/violation.h"
#include "kernel/body.h"

#include <string>
#include <vector>

namespace kintsugi {

struct GeometryReport {
  std::vector<Violation> violations;
  double max_deviation = 0.0;
  std::vector<std::string> max_elements;  // e.g. {"v3", "f2"}
};

// On `threads` threads where the body is large and has no free-form element: the same
// report, violations in the same order (Geometry.CheckOnTwoThreadsIsTheSame).
GeometryReport check_geometry(const Body& b, double precision, int threads = 1);

// `face_sense` for one face: false when f is planar and its outer loop (curved edges
// followed within `precision`) turns clockwise about its outward normal, i.e. the face is
// inside out. True for non-planar faces and faces without an outer loop.
bool planar_face_sense_ok(const Body& b, FaceH f, double precision);

}  // namespace kintsugi
