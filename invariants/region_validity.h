// Validity of the region a repair touched (spec/beautify.md, "The validity gate"): the
// check every repair must pass before it is committed, so that beautify never writes a
// model that is worse than what it read. It finds what OpenCASCADE's BRepCheck finds in
// such a region, by our own geometry:
//   * `vertex_on_curve`, `vertex_on_surface`, `edge_on_surface`: vertices on the curves of
//     their edges and the surfaces of their faces, edges on both faces' surfaces, within
//     `lies_on` (the modelling precision, or what the input already had: see
//     lies_on_limit);
//   * `degenerate_edge`: an edge whose two distinct vertices coincide (OpenCASCADE cannot
//     write it: "different points on a closed curve", "line through identical points");
//   * `loop_self_intersection`, `loops_cross`: in the face's parameter domain (angles
//     unwrapped, with the period shifts of periodic surfaces), a loop crosses itself or
//     another loop of the same face;
//   * `loop_orientation`: a loop that closes in the parameter domain turns the wrong way
//     (outer loops counter-clockwise about the outward normal, holes clockwise) on a
//     plane, cylinder or cone face;
//   * whatever an external check registered with `set_external_region_check` reports
//     (with OpenCASCADE: that the model converts, and BRepCheck of the touched faces).
// The region is the given elements and everything around them: the edges at a touched
// vertex, the faces beside a touched edge, and the vertices and edges of touched faces.
#pragma once

#include "geometry/tolerance.h"
#include "invariants/violation.h"
#include "kernel/body.h"

#include <set>
#include <string>
#include <vector>

namespace kintsugi {

struct Region {
  std::set<VertexH> vertices;
  std::set<EdgeH> edges;
  std::set<FaceH> faces;
};

// The whole body as a region (for `kintsugi check` and tests).
Region whole_body(const Body& b);

// "Lies on" limit: tol.precision, raised to what the input body already had (a model
// read from a file whose vertices are 1e-7 off their curves is not made invalid by a
// repair that keeps them so). `input_deviation` is check_geometry's max_deviation of the
// body before any repair.
double lies_on_limit(const geo::Tolerances& tol, double input_deviation);

// Every violation in the region; `lies_on` is the distance limit for the geometric ones.
// `coincide_within` (default: `lies_on`) is the distance at which two distinct vertices
// are one point (degenerate_edge): a repair whose positions are only consistent to the
// tolerance is gated with `lies_on` = the tolerance, but an edge shorter than that is a
// short edge for pass 11, not a degenerate one; only below the precision is it that.
std::vector<Violation> region_violations(const Body& b, const Region& r, const geo::Tolerances& tol, double lies_on,
                                         double coincide_within = -1);

// "" when the region is valid, else the first violation as a sentence.
std::string region_validity(const Body& b, const Region& r, const geo::Tolerances& tol, double lies_on,
                            double coincide_within = -1);

// Only the parameter-domain checks (self-intersection, crossing, orientation) of faces.
std::vector<Violation> loop_violations(const Body& b, const std::set<FaceH>& faces, const geo::Tolerances& tol);

// A further check of the region (e.g. OpenCASCADE's), registered by a library that
// geometry/ and invariants/ must not depend on. Returns "" or the reason.
using ExternalRegionCheck = std::string (*)(const Body& b, const Region& r);
void set_external_region_check(ExternalRegionCheck fn);
ExternalRegionCheck external_region_check();

}  // namespace kintsugi
