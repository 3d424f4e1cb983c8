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
//     (with OpenCASCADE: that the model converts, and BRepCheck of the touched faces),
//     but for the faces the caller keeps provisionally (Region::provisional).
// The region is the given elements and everything around them: the edges at a touched
// vertex, the faces beside a touched edge, and the vertices and edges of touched faces.
//
// A face with many loops (a plate with a hole per feature) is checked near what changed
// only: OpenCASCADE classifies every wire of a face against every other, so one repair
// beside a plate with 27,000 holes took an hour and a half, and checking every vertex of
// such a plate after each repair beside it costs as much as the repair many times over.
// "Near" is loops_near of the box of the edges the repair changed (an edge of the
// region, or one at a vertex of the region), grown by the tolerance. The loops left out
// have edges that are the same curves between the same points as before the repair:
//   * when the face's surface was not set by the repair (Region::surfaces_set), they lie
//     on it as they did, so they are not grown into the region at all;
//   * when it was (or the caller does not say), all its vertices and edges are checked
//     on the new surface, and then only the loop checks and the external check look
//     near the change.
// (A loop that joined the face without changing — a ring kef moved, a new face's loops —
// is one of the changed ones: beautify adds its elements to the region from the journal.)
// Either way a crossing or a nesting among the loops left out is one the face had
// before; a new crossing has a changed edge on one side, and so a loop near it on the
// other. What the gate promises, that a repair makes nothing worse, still holds.
#pragma once

#include "geometry/box.h"
#include "geometry/tolerance.h"
#include "invariants/loop_index.h"
#include "invariants/violation.h"
#include "kernel/body.h"

#include <algorithm>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace kintsugi {

struct Region {
  std::set<VertexH> vertices;
  std::set<EdgeH> edges;
  std::set<FaceH> faces;
  // Only in the region given to the external check: faces with more than kManyLoops
  // loops, each with the box (grown by the tolerance) of the edges on it that the repair
  // changed and loops_near(b, f, box), the loops it is checked with.
  struct Near {
    geo::Box box;
    std::vector<LoopH> loops;
  };
  std::map<FaceH, Near> near;
  // The faces whose surface the repair set, when the caller knows (from the journal);
  // nullopt: any face may have a new surface (see the header).
  std::optional<std::set<FaceH>> surfaces_set;
  // Where the loops of faces with many loops were after the last committed change
  // (invariants/loop_index.h), when the caller keeps that; else they are scanned.
  const LoopBoxIndex* loop_index = nullptr;
  // Faces whose loops touch and which the caller keeps so provisionally (beautify: a
  // later repair must remove the touch, or its run is undone). Our own checks see them
  // as always; the external check does not: OpenCASCADE calls a loop that touches itself
  // unorientable, which is the touch itself. The caller puts them to the external check
  // once the touch is gone.
  std::set<FaceH> provisional;
};

// A face with more loops than this is checked near the change only (see above).
inline constexpr std::size_t kManyLoops = 16;

// The chordal error at which the boxes of changed edges and of loops are found.
inline double loop_chordal(const geo::Tolerances& tol) { return std::max(tol.length * 0.05, tol.precision * 10); }

// The outer loop of f and every other loop whose box meets `box` (lone vertices: when in
// the box), outer first.
std::vector<LoopH> loops_near(const Body& b, FaceH f, const geo::Box& box);

// For a face f with more than kManyLoops loops: the box of its edges that a change of
// `vertices` and `edges` changed (the edges themselves and those at the vertices), and of
// the lone vertices among them, grown by the tolerance; an empty box when none is on f.
// nullopt for a face with fewer loops (it is taken whole).
std::optional<geo::Box> near_change(const Body& b, const std::set<VertexH>& vertices, const std::set<EdgeH>& edges,
                                    FaceH f, const geo::Tolerances& tol);

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
