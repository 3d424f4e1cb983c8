// Internal to detection: the scope a detection covers (the whole body, or the
// neighbourhood of what repairs touched) and per-element measures computed once, on first
// use, and shared by the detectors.
#pragma once

#include <algorithm>

#include "geometry/area.h"
#include "geometry/tolerance.h"
#include "kernel/body.h"
#include "problems/problem.h"

#include <optional>
#include <span>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace kintsugi::detail {

struct FaceInfo {
  bool measured = false;
  double area = 0.0;
  double bbox_diagonal = 0.0;
  double length = 0.0;  // what the width is area over: sliver_length
  bool small = false;   // area < tol²
  bool sliver = false;  // area / length < tol, and not small
};

// The length of a face that its width is its area over. The paper (4.4) takes the box's
// diagonal; for a band round a periodic surface — one loop that crosses itself along its
// seam, [c1, s, c2, s⁻¹], as a scanned chamfer or fillet of a circular edge makes — that
// is the band's diameter, and the width came out π times too wide (a 0.03 chamfer of a
// 10-mm cylinder's edge, 0.042 wide, measured 0.094). Such a band's length is half its
// boundary without the seam: its mean circumference. `edge_length` measures an edge.
template <class EdgeLength>
double sliver_length(const Body& b, FaceH f, double diagonal, EdgeLength edge_length) {
  LoopH l = b.outer_loop(f);
  if (!l.valid() || b.next_in_face(l).valid() || b.is_lone(l)) return diagonal;
  std::vector<EdgeH> es;
  b.for_each_halfedge(l, [&](HalfedgeH h) { es.push_back(edge_of(h)); });
  double rim = 0.0;
  bool seam = false;
  for (std::size_t i = 0; i < es.size(); ++i) {
    const bool twice = std::count(es.begin(), es.end(), es[i]) > 1;
    seam = seam || twice;
    if (!twice) rim += edge_length(es[i]);
  }
  return seam ? std::max(diagonal, 0.5 * rim) : diagonal;
}

// A face measured with its boundary sampled at `chordal` (no coarse first pass): the
// reference DetectContext::face() decides as.
FaceInfo measure_face(const Body& b, FaceH f, const geo::Tolerances& tol, double chordal);

// The elements detection starts from. Each detector starts only from elements of its
// anchor kind (spec/problems.md, "Detecting near a repair"): faces for face problems and
// pinching, edges for short edges and same geometry, vertices for mergeable edges,
// border cycles for gaps. Walks (chains) may leave the scope.
struct Scope {
  std::vector<FaceH> faces;
  std::vector<EdgeH> edges;
  std::vector<VertexH> vertices;
  std::vector<LoopH> borders;
};

// Marks by slot: a dense array for a whole-body detection, a hash set for a local one
// (which must cost what the neighbourhood costs, not what the body does).
class Marks {
 public:
  Marks(std::size_t slots, bool dense) : dense_(dense) {
    if (dense) bits_.assign(slots, 0);
  }
  bool test(std::uint32_t i) const { return dense_ ? bits_[i] != 0 : set_.count(i) != 0; }
  void set(std::uint32_t i) {
    if (dense_)
      bits_[i] = 1;
    else
      set_.insert(i);
  }

 private:
  bool dense_;
  std::vector<std::uint8_t> bits_;
  std::unordered_set<std::uint32_t> set_;
};

class DetectContext {
 public:
  DetectContext(const Body& b, const geo::Tolerances& tol, Scope scope, bool whole);

  const Body& b;
  geo::Tolerances tol;
  double chordal;  // for sampling curved boundaries
  Scope scope;
  bool whole;  // the scope is the whole body

  const FaceInfo& face(FaceH f) const;     // measured on first use
  // What is already known of f, in place of measuring it (a face with many loops shown
  // neither small nor a sliver by bounds: Neighbourhood::ordinary).
  void know(FaceH f, const FaceInfo& fi);
  double edge_length(EdgeH e) const;       // measured on first use
  Marks marks_faces() const { return Marks(b.face_slots(), whole); }
  // A whole-body detection's measures taken ahead on `threads` threads: every analytic
  // edge's length, then every face's measure where the face and its edges have analytic
  // geometry, and the faces with free-form geometry by evaluation group (free-form
  // evaluation keeps per-surface state: repair/freeform_groups.h) when there are enough
  // groups. The answers are the ones face() and edge_length() would give.
  void measure_ahead(int threads);
  // How many threads the detectors may share after measure_ahead: more than one only
  // when it measured every face and edge of the scope (then face() and edge_length()
  // only read) and no element is free-form (whose evaluation keeps state); else 1.
  int threads_for_detectors() const { return detector_threads_; }
  Marks marks_edges() const { return Marks(b.edge_slots(), whole); }

 private:
  FaceInfo measure(FaceH f) const;  // coarse first, finely where that cannot decide
  void measure_freeform_ahead(int threads);  // measure_ahead's faces with free-form geometry

  int detector_threads_ = 1;
  mutable std::vector<FaceInfo> face_dense_;
  mutable std::vector<std::uint8_t> face_done_;
  mutable std::vector<double> length_dense_;
  mutable std::unordered_map<std::uint32_t, FaceInfo> face_sparse_;
  mutable std::unordered_map<std::uint32_t, double> length_sparse_;
};

// A border cycle's half-edges split into simple cycles at repeated vertices: each is one
// gap (paper 4.1, "fundamental cycles"); the gap passes find their gap again with it.
std::vector<std::vector<HalfedgeH>> simple_cycles(const Body& b, const std::vector<HalfedgeH>& hs);

void detect_gaps(DetectContext& c, std::vector<Problem>& out);
// Pinching and same geometry are found face by face and edge by edge, the largest parts
// of a detection: each takes a part of the scope (all of it, or a block of a whole-body
// detection run on its own thread; see DetectContext::threads_for_detectors).
void detect_pinched(DetectContext& c, std::vector<Problem>& out, std::span<const FaceH> faces);
void detect_small_and_sliver(DetectContext& c, std::vector<Problem>& out);  // types 5, 6, 9
void detect_short_edges(DetectContext& c, std::vector<Problem>& out);       // types 7, 11
void detect_same_geometry(DetectContext& c, std::vector<Problem>& out, std::span<const EdgeH> edges);
void detect_mergeable(DetectContext& c, std::vector<Problem>& out);

}  // namespace kintsugi::detail
