// Detection: the first half of the paper's algorithm. With one length tolerance, find
// every problem of the eleven types (spec/problems.md) and say where it is. Read-only,
// linear in the model for bounded face degree (paper section 5): each face is measured
// once, pinching compares edge pairs within a face, chains are found by walks over
// flagged elements only.
//
// detect_near() finds the problems anchored near what repairs touched, at a cost that
// depends on that neighbourhood, not on the body: between passes the pipeline replaces
// the problems anchored there by what detect_near finds (spec/problems.md, "Detecting
// near a repair").
#pragma once

#include "geometry/tolerance.h"
#include "invariants/element_geometry.h"
#include "invariants/loop_index.h"
#include "kernel/body.h"
#include "problems/problem.h"
#include "repair/touched.h"

#include <array>
#include <optional>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace kintsugi {

struct Detection {
  std::vector<Problem> problems;  // in the paper's order of types
  std::array<int, 11> counts{};   // indexed by problem_order(type) - 1

  int count(ProblemType t) const { return counts[std::size_t(problem_order(t) - 1)]; }
};

Detection detect(const Body& b, const geo::Tolerances& tol);
// detect's problems of the given types only, by running only the detectors that find them
// (for callers that want a few types: the tolerance suggestion's probe).
Detection detect_types(const Body& b, const geo::Tolerances& tol, const std::vector<ProblemType>& types);
// The same, with faces already measured (area and bounding box, indexed by face slot;
// nullopt: not measured, or not measurable) taken instead of measuring them again. The
// measures must be at least as fine as detection's own (geo::Tolerances::measure_chordal).
Detection detect_types(const Body& b, const geo::Tolerances& tol, const std::vector<ProblemType>& types,
                       const std::vector<std::optional<AreaAndBounds>>& measured);

// The neighbourhood of touched elements: the faces touched, on a touched edge or around
// a touched vertex (the core); the edges and vertices of these faces, and the border
// cycles across those edges. It does not reach across the core's edges: a face beside a
// repair whose own boundary did not change keeps its problems (spec/problems.md,
// "Detecting near a repair"), and a plate under thousands of features stays out of the
// neighbourhood of a repair on one of them. A face in the core with many loops (that
// plate, when the repair is on its boundary) brings only the edges, vertices and border
// cycles of its loops near the change (invariants/region_validity.h, loops_near), unless
// the repair set its surface; the face itself is in the core all the same.
struct Neighbourhood {
  std::unordered_set<FaceH> faces;
  std::unordered_set<EdgeH> edges;
  std::unordered_set<VertexH> vertices;
  std::unordered_set<LoopH> borders;
  std::unordered_set<FaceH> partial;  // faces of `faces` added with some of their loops only
  struct Bounds {
    double area_lo, diagonal_hi;
  };
  // Faces of `partial` shown neither small nor a sliver, with the bounds that showed it:
  // detection takes that instead of measuring them (a plate's measure is O(plate)).
  std::unordered_map<FaceH, Bounds> ordinary;

  bool empty() const { return faces.empty() && edges.empty() && vertices.empty() && borders.empty(); }
  // Whether p is anchored here: its elements of the kind its detector starts from
  // (faces; edges for short edges; the vertex for mergeable edges; the border cycle for
  // gaps) lie in the neighbourhood. A problem with a dead element is anchored anywhere.
  bool anchors(const Body& b, const Problem& p) const;
  // Adds a live face with its edges, vertices and the border cycles across its edges
  // (those of `loops` only, when given).
  void add_face(const Body& b, FaceH f, const std::vector<LoopH>* loops = nullptr);
  // Adds p's live elements: faces as add_face does, edges, vertices, border cycles.
  void add_elements_of(const Body& b, const Problem& p);
};
// What is known of faces with many loops between neighbourhoods: for each, lower and
// upper bounds on its area and box diagonal that hold now, each later change shrinking
// them by what fits in its box (spec/problems.md, "A face with many loops"). So a plate
// is measured once, not after every repair beside it. Valid only while every change to
// the body is followed by a `neighbourhood` call with the memo (beautify's pipeline).
struct FaceBoundsMemo {
  using Bounds = Neighbourhood::Bounds;
  std::unordered_map<FaceH, Bounds> faces;
  // Where the loops of such faces are, brought up to date by each neighbourhood call
  // (invariants/loop_index.h); the validity gate reads it.
  LoopBoxIndex loops;
};
Neighbourhood neighbourhood(const Body& b, const Touched& t, const geo::Tolerances& tol, FaceBoundsMemo* memo = nullptr);

// Replacing known problems by what detection finds near a repair. Drops from each list
// the problems anchored in n and grows n by their live elements: what is left of a
// problem the repair changed is found again from them (the pieces of a chain of small
// faces cut by a face that stopped being small, which the core alone does not reach).
// Then drops what the grown n anchors too, so that detect_near(b, tol, n) finds each
// dropped problem that still exists and nothing that was kept. Problems in `grow_only`
// grow n when anchored but stay where they are (a pass's own pending queue).
void drop_anchored(const Body& b, Neighbourhood& n, const std::vector<std::vector<Problem>*>& lists,
                   const std::vector<const Problem*>& grow_only = {});

// Every problem anchored in `n` (in the paper's order of types).
Detection detect_near(const Body& b, const geo::Tolerances& tol, const Neighbourhood& n);
// Only the problems of type t anchored in `n`: exactly detect_near's of that type, by
// running only the detector that finds them (detectors share measures, never results).
std::vector<Problem> detect_near_of_type(const Body& b, const geo::Tolerances& tol, const Neighbourhood& n,
                                         ProblemType t);

}  // namespace kintsugi
