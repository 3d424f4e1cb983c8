// Where the loops of a face with many loops are (a plate with a ring per feature), kept
// through a run of repairs so that finding the loops near a change costs what is near it,
// not what the face holds (issue 18; loops_near in invariants/region_validity.h scans them
// all). A uniform grid of the loops' boxes per face, built from the body as it is when
// first asked after a committed change, and brought up to date after each later one.
//
// The contract: between two calls of `committed` for a face, only the loops that hold an
// element the caller names as changed may differ from what the index recorded; `near`
// evaluates those as they are. Whatever `near` is asked during a repair that is then
// rolled back leaves the index as it was.
#pragma once

#include "geometry/box.h"
#include "kernel/body.h"

#include <cstdint>
#include <set>
#include <unordered_map>
#include <vector>

namespace kintsugi {

class LoopBoxIndex {
 public:
  // Whether f is indexed (near() can answer for it).
  bool has(FaceH f) const { return faces_.count(f) != 0; }

  // The outer loop of f and every other live loop of f whose box meets `box`, outer
  // first, then in handle order: the loops recorded there, and the loops of f through
  // the changed elements (`vertices`, `edges`: the edges themselves and those at the
  // vertices) as they are now. f must be indexed.
  std::vector<LoopH> near(const Body& b, FaceH f, const geo::Box& box, const std::set<VertexH>& vertices,
                          const std::set<EdgeH>& edges, double chordal) const;

  // After a change is committed: indexes f from the body as it is when f is new to the
  // index; otherwise records the loops of f through the changed elements as they are now.
  void committed(const Body& b, FaceH f, const std::set<VertexH>& vertices, const std::set<EdgeH>& edges,
                 double chordal);

  // Forgets f (its surface was set: the caller takes it whole).
  void forget(FaceH f) { faces_.erase(f); }

 private:
  struct FaceGrid {
    geo::Vec3 origin;
    double cell = 1.0;
    std::unordered_map<std::uint64_t, std::vector<LoopH>> cells;
    std::vector<LoopH> big;                     // loops over too many cells: always candidates
    std::unordered_map<LoopH, geo::Box> boxes;  // the recorded box of each loop
  };
  void record(FaceGrid& g, LoopH l, const geo::Box& box);
  std::unordered_map<FaceH, FaceGrid> faces_;
};

// The box of a loop (halfedge_box of its sides; a lone vertex's point).
geo::Box loop_box(const Body& b, LoopH l, double chordal);

// Calls on_side(h) for each half-edge of f on a changed element (an edge of `edges`, or
// an edge at a vertex of `vertices`), and on_lone(v) for each vertex of `vertices` on no
// edge. Costs what the elements do, not what f holds.
template <class OnSide, class OnLone>
void for_each_changed_side(const Body& b, FaceH f, const std::set<VertexH>& vertices, const std::set<EdgeH>& edges,
                           OnSide on_side, OnLone on_lone) {
  auto edge = [&](EdgeH e) {
    for (unsigned s = 0; s < 2; ++s)
      if (HalfedgeH h = halfedge_of(e, s); b.face(h) == f) on_side(h);
  };
  for (EdgeH e : edges)
    if (b.alive(e)) edge(e);
  for (VertexH v : vertices) {
    if (!b.alive(v)) continue;
    bool any = false;
    for (HalfedgeH h : b.outgoing(v)) edge(edge_of(h)), any = true;
    if (!any) on_lone(v);
  }
}

// Whether f has more than `n` loops (walks at most n + 1 of them).
bool has_more_loops_than(const Body& b, FaceH f, std::size_t n);

// The loops of f through the changed elements (the edges, and the edges at the vertices).
std::set<LoopH> loops_through(const Body& b, FaceH f, const std::set<VertexH>& vertices, const std::set<EdgeH>& edges);

}  // namespace kintsugi
