// Pass 2, edge gaps (paper 4.1, Figure 17): a gap across the edge between two faces. The
// gap's loop is removed and the two faces meet again along one edge between the two
// junctions (the vertices where the gap crosses the interrupted edge), on the curve where
// their surfaces meet (line, circle, or what the geometry layer gives). Topology: each
// side of the gap is joined into one edge (jekv), kef of one side lets its face grow over
// the gap, the other side is then the new edge (repair/gap_closing.h, collapse_gap).
// The junctions are left on two edges each: pass 10 joins the pieces of the interrupted
// edge (Table 1: an edge gap's repair can make mergeable edges).
#include "repair/gap_closing.h"

namespace kintsugi::detail {

namespace {

std::string repair_edge_gap(RepairCall& c) {
  std::string why;
  auto g = find_gap(c.b, c.problem, &why);
  if (!g) return why;
  if (g->runs.size() != 2)
    return "the gap's border changes face " + std::to_string(g->runs.size()) + " times, not twice";
  const geo::Vec3 a = c.b.point(g->junction(c.b, 0)), b = c.b.point(g->junction(c.b, 1));
  return collapse_gap(c, *g, {0, 1}, {a, b});
}

}  // namespace
}  // namespace kintsugi::detail

KINTSUGI_PASS(edge_gap) = {kintsugi::ProblemType::edge_gap, "edge gaps",
                     "the gap becomes one edge between the two junctions, where the two faces meet",
                     kintsugi::detail::repair_edge_gap};
