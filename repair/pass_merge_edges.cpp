// Pass 10, mergeable edges (paper 4.5): a vertex on exactly two edges that separate the
// same two faces is removed by jekv, and the union gets the curve where the two faces
// meet (the line through its vertices for two planes). A closed curve keeps one vertex:
// jekv refuses to join an edge with itself, so a self-loop is never joined.
#include "kernel/euler.h"
#include "repair/beautify_detail.h"

namespace kintsugi::detail {

namespace {

std::string repair_mergeable_edges(RepairContext& c) {
  Body& b = c.b;
  VertexH v = c.problem.first<VertexH>();
  if (!b.alive(v)) return "no vertex named";
  auto outs = b.outgoing(v);
  if (outs.size() != 2) return v.str() + " no longer lies on exactly two edges";
  if (edge_of(outs[0]) == edge_of(outs[1])) return v.str() + " is the only vertex of a closed edge: kept";
  HalfedgeH h = b.prev(outs[0]);  // ends at v; next(h) = outs[0] leaves it
  EdgeH keep = edge_of(h), gone = edge_of(outs[0]);
  const bool same_curve = b.curve(keep) == b.curve(gone);
  auto r = euler::jekv(b, h);
  if (!r) return std::string("jekv refused: ") + r.error().message;
  c.touched.edges.insert(keep);
  return refit_joined_edge(b, keep, same_curve, c.tol);
}

}  // namespace
}  // namespace kintsugi::detail

KINTSUGI_PASS(merge_edges) = {kintsugi::ProblemType::mergeable_edges, "mergeable edges",
                              "a vertex on two edges between the same two faces is removed and the edges joined",
                              kintsugi::detail::repair_mergeable_edges};
