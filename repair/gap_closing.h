// Closing gaps (paper 4.1, passes 1-3): what the three gap passes share. A gap is one
// simple cycle of a border cycle; its half-edges fall into runs, each a maximal stretch
// whose other side lies in one face. The passes differ in which runs they keep:
//   face gap (one run inside a face): the ring is removed, the face's surface covers it;
//   edge gap (two runs): both runs kept, the gap becomes one edge between the junctions;
//   multiple-face gap: no run kept (one vertex), two opposite runs kept (two vertices and
//   an edge), or every run kept and the gap filled by a new face with a fitted surface.
#pragma once

#include "repair/beautify_detail.h"

#include <optional>
#include <string>
#include <vector>

namespace kintsugi::detail {

struct GapRun {
  FaceH face;                    // the face across this stretch of the gap
  std::vector<HalfedgeH> edges;  // border half-edges, in cycle order
};

struct Gap {
  LoopH border;
  std::vector<HalfedgeH> cycle;  // border half-edges of this gap, in order
  std::vector<GapRun> runs;      // rotated so that runs[0] starts where the face changes
  bool whole_loop = true;        // false when the border cycle holds further gaps
  // Junction i: the vertex where run i ends and run i+1 begins.
  VertexH junction(const Body& b, std::size_t i) const;
};

// The gap the problem names, as the body is now: the problem's border cycle split into
// simple cycles, the cycle whose faces are the problem's. nullopt with *why when it is
// gone or changed.
std::optional<Gap> find_gap(const Body& b, const Problem& p, std::string* why);

// Pass 1: removes a face gap lying inside its face (a ring whose other side is the gap):
// kev along the cycle to one edge, kef of that edge, then the lone vertex left as a ring
// is joined to the outer loop (mekr) and collapsed (kev). Nothing geometric changes.
std::string remove_hole(RepairCall& c, const Gap& g);

// Passes 2 and 3: keeps the runs in `keep` (each joined into one edge), collapses every
// other run into the vertex where its neighbours meet, and then: with no run kept, the
// gap is one vertex at points[0]; with two kept runs the gap closes between them into one
// edge whose ends are the collapsed groups (at points[0] and points[1] in the order the
// groups follow the first kept run; an empty group keeps its junction where it is).
// Curves at moved vertices and of the new edge are derived from the faces beside them.
std::string collapse_gap(RepairCall& c, const Gap& g, const std::vector<std::size_t>& keep,
                         const std::vector<geo::Vec3>& points);

// Pass 3, more than two meeting points: a new face (mfkb) over the gap, each run joined
// into one edge, the face's surface fitted to the junctions and the gap's border (a plane
// when they are coplanar within tolerance, else the analytic surface that fits best).
// *surface_kind says which ("plane", "sphere", "cylinder", ...).
std::string fill_gap(RepairCall& c, const Gap& g, std::string* surface_kind);

// The ways a multiple-face gap can close, decided from the geometry before any change.
struct GapClosure {
  enum Kind { one_vertex, two_vertices, new_face } kind = new_face;
  std::vector<std::size_t> keep;  // runs kept (two_vertices: the two runs the new edge separates)
  std::vector<geo::Vec3> points;  // where the collapsed groups go
  double residual = 0.0;          // how far the meeting points are from the surfaces
  std::string note;               // why the simpler closures were not taken
};
// `exhaustive` (for tests): solve every pair of opposite runs, without the search's
// pruning of groups that grow from one with no common point.
GapClosure plan_multi_face_gap(const Body& b, const Gap& g, const geo::Tolerances& tol, bool exhaustive = false);

}  // namespace kintsugi::detail
