// Short edges (paper 4.3, 4.6) and mergeable edges (paper 4.5).
//   short_edge_chain: two or more consecutive short edges joined by vertices on exactly
//                     two edges; a closed ring of them is one chain.
//   short_edge:       a short edge in no chain.
// An edge that bounds a small face, a sliver or a gap is not reported on its own: it goes
// when that face or gap is repaired (paper 3.2), and reporting it twice would misstate
// the model.
//   mergeable_edges:  a vertex on exactly two different edges that separate the same
//                     pair of faces (a border cycle is not a face: gap boundaries are
//                     gaps); not one inside or at an end of a short-edge chain (the
//                     chain's own repair moves or removes it).
#include "repair/detect_detail.h"

#include <algorithm>
#include <set>

namespace kintsugi::detail {

namespace {

// The two distinct edges at v when v lies on exactly two edges; else none.
bool two_edges(const Body& b, VertexH v, HalfedgeH* a, HalfedgeH* c) {
  HalfedgeH o = b.out(v);
  if (!o.valid()) return false;
  HalfedgeH o2 = b.next(twin(o));
  if (o2 == o || b.next(twin(o2)) != o) return false;  // degree 1, or more than 2
  if (edge_of(o) == edge_of(o2)) return false;          // a self-loop's single edge
  *a = o;
  *c = o2;
  return true;
}

}  // namespace

void detect_short_edges(DetectContext& c, std::vector<Problem>& out) {
  const Body& b = c.b;
  auto covered = [&](EdgeH e) {
    for (unsigned s = 0; s < 2; ++s) {
      FaceH f = b.face(halfedge_of(e, s));
      if (!f.valid() || c.face(f).small || c.face(f).sliver) return true;
    }
    return false;
  };
  auto is_short = [&](EdgeH e) { return c.edge_length(e) < c.tol.length && !covered(e); };
  // Links between short edges through two-edge vertices.
  auto neighbours = [&](EdgeH e) {
    std::vector<std::pair<EdgeH, VertexH>> out_n;
    HalfedgeH h = halfedge_of(e, 0);
    for (VertexH v : {b.origin(h), b.target(h)}) {
      HalfedgeH a, d;
      if (!two_edges(b, v, &a, &d)) continue;
      EdgeH other = edge_of(a) == e ? edge_of(d) : edge_of(a);
      if (other != e && is_short(other)) out_n.push_back({other, v});
    }
    return out_n;
  };
  Marks seen = c.marks_edges();
  for (EdgeH e : c.scope.edges) {
    if (!is_short(e) || seen.test(e.idx())) continue;
    // Collect the component: it is a path or a ring, as every link vertex has two edges.
    std::vector<EdgeH> comp{e};
    seen.set(e.idx());
    for (std::size_t i = 0; i < comp.size(); ++i)
      for (auto [n, v] : neighbours(comp[i]))
        if (!seen.test(n.idx())) {
          seen.set(n.idx());
          comp.push_back(n);
        }
    double total = 0;
    for (EdgeH x : comp) total += c.edge_length(x);
    Problem p;
    p.type = comp.size() >= 2 ? ProblemType::short_edge_chain : ProblemType::short_edge;
    std::sort(comp.begin(), comp.end());
    for (EdgeH x : comp) p.elements.push_back(x);
    p.measure = total;
    p.measure_kind = Measure::length;
    out.push_back(std::move(p));
  }
}

void detect_mergeable(DetectContext& c, std::vector<Problem>& out) {
  const Body& b = c.b;
  auto is_short = [&](EdgeH e) { return c.edge_length(e) < c.tol.length; };
  // A short edge with a short neighbour across a two-edge vertex.
  auto in_chain = [&](EdgeH e) {
    if (!is_short(e)) return false;
    HalfedgeH h = halfedge_of(e, 0);
    for (VertexH w : {b.origin(h), b.target(h)}) {
      HalfedgeH x, y;
      if (!two_edges(b, w, &x, &y)) continue;
      EdgeH other = edge_of(x) == e ? edge_of(y) : edge_of(x);
      if (other != e && is_short(other)) return true;
    }
    return false;
  };
  for (VertexH v : c.scope.vertices) {
    HalfedgeH a, d;
    if (!two_edges(b, v, &a, &d)) continue;
    // A gap's boundary is not a pair of faces: its vertices are the gap's, not mergeable.
    if (b.is_border(a) || b.is_border(twin(a)) || b.is_border(d) || b.is_border(twin(d))) continue;
    // The faces on either side of each edge, as unordered pairs.
    std::set<FaceH> fa{b.face(a), b.face(twin(a))}, fd{b.face(d), b.face(twin(d))};
    if (fa != fd) continue;
    // Inside a short-edge chain or at one of its ends: the chain's repair (pass 7, before
    // this one's pass 10) moves or removes the vertex, and what is left to merge is found
    // afresh after it. A lone short edge is different: merging it into its neighbour on
    // the same curve is how it goes (pass 10 runs before pass 11), so its end is reported.
    if (in_chain(edge_of(a)) || in_chain(edge_of(d))) continue;
    Problem p;
    p.type = ProblemType::mergeable_edges;
    // The two edges in index order: which of v's half-edges comes first depends on the
    // operators' history, and a problem found again later must name them the same way.
    EdgeH e1 = std::min(edge_of(a), edge_of(d)), e2 = std::max(edge_of(a), edge_of(d));
    p.elements = {v, e1, e2};
    p.measure = c.edge_length(e1) + c.edge_length(e2);
    p.measure_kind = Measure::length;
    out.push_back(std::move(p));
  }
}

}  // namespace kintsugi::detail
