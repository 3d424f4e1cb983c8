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
#include "kernel/body.h"
#include "problems/problem.h"
#include "repair/touched.h"

#include <array>
#include <unordered_set>
#include <vector>

namespace kintsugi {

struct Detection {
  std::vector<Problem> problems;  // in the paper's order of types
  std::array<int, 11> counts{};   // indexed by problem_order(type) - 1

  int count(ProblemType t) const { return counts[std::size_t(problem_order(t) - 1)]; }
};

Detection detect(const Body& b, const geo::Tolerances& tol);

// The neighbourhood of touched elements: the faces touched, on a touched edge or around
// a touched vertex (the core), and the faces across the core's edges; the edges and
// vertices of all these faces, and the border cycles across those edges.
struct Neighbourhood {
  std::unordered_set<FaceH> faces;
  std::unordered_set<EdgeH> edges;
  std::unordered_set<VertexH> vertices;
  std::unordered_set<LoopH> borders;

  bool empty() const { return faces.empty() && edges.empty() && vertices.empty() && borders.empty(); }
  // Whether p is anchored here: its elements of the kind its detector starts from
  // (faces; edges for short edges; the vertex for mergeable edges; the border cycle for
  // gaps) lie in the neighbourhood. A problem with a dead element is anchored anywhere.
  bool anchors(const Body& b, const Problem& p) const;
};
Neighbourhood neighbourhood(const Body& b, const Touched& t);

// Every problem anchored in `n` (in the paper's order of types).
Detection detect_near(const Body& b, const geo::Tolerances& tol, const Neighbourhood& n);
// Only the problems of type t anchored in `n`: exactly detect_near's of that type, by
// running only the detector that finds them (detectors share measures, never results).
std::vector<Problem> detect_near_of_type(const Body& b, const geo::Tolerances& tol, const Neighbourhood& n,
                                         ProblemType t);

}  // namespace kintsugi
