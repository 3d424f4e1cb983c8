// Pass 7, chains of short edges (paper 4.3): the chain is replaced by one edge between
// its end vertices: jekv at every inner vertex (each lies on exactly two edges of the
// chain), then the survivor gets the curve where the two faces beside the chain meet
// (the line through its end vertices for two planes; a piece cut from one curve keeps
// that curve). A closed chain keeps one vertex and becomes a closed edge.
#include "kernel/euler.h"
#include "repair/beautify_detail.h"

#include <algorithm>

namespace kintsugi::detail {

namespace {

std::string repair_short_edge_chain(RepairContext& c) {
  Body& b = c.b;
  std::set<EdgeH> chain;
  for (EdgeH e : c.problem.all<EdgeH>()) {
    if (!b.alive(e)) return "no longer present: " + e.str() + " was removed by an earlier repair";
    chain.insert(e);
  }
  if (chain.size() < 2) return "a chain needs two edges";
  const geo::Curve first_curve = b.curve(*chain.begin());
  bool one_curve = true;
  for (EdgeH e : chain) one_curve = one_curve && b.curve(e) == first_curve;
  // Inner vertices: on exactly two edges, both in the chain.
  std::vector<VertexH> inner;
  std::set<VertexH> all;
  for (EdgeH e : chain)
    for (unsigned s = 0; s < 2; ++s) all.insert(b.origin(halfedge_of(e, s)));
  for (VertexH v : all) {
    auto outs = b.outgoing(v);
    if (outs.size() == 2 && edge_of(outs[0]) != edge_of(outs[1]) && chain.count(edge_of(outs[0])) &&
        chain.count(edge_of(outs[1])))
      inner.push_back(v);
  }
  if (inner.size() + 1 < chain.size()) return "the edges no longer form a chain";
  if (inner.size() == chain.size()) inner.pop_back();  // a closed chain keeps one vertex
  for (VertexH v : inner) {
    HalfedgeH h = b.prev(b.out(v));
    auto r = euler::jekv(b, h);
    if (!r) return std::string("jekv refused at ") + v.str() + ": " + r.error().message;
  }
  EdgeH keep;
  for (EdgeH e : chain)
    if (b.alive(e)) keep = e;
  c.touched.edges.insert(keep);
  return refit_joined_edge(b, keep, one_curve, c.tol);
}

}  // namespace
}  // namespace kintsugi::detail

KINTSUGI_PASS(short_edge_chain) = {kintsugi::ProblemType::short_edge_chain, "short-edge chains",
                                   "the chain becomes one edge between its end vertices",
                                   kintsugi::detail::repair_short_edge_chain};
