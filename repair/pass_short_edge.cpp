// Pass 11, short edges (paper 4.6): kev collapses the edge onto one of its vertices,
// which then moves to the point that best fits all the faces around it
// (geo::meet_point, least squares for more than three), and the edges there get curves
// through it. A collapse that would leave a face with two straight sides is refused.
#include "invariants/element_geometry.h"
#include "kernel/euler.h"
#include "repair/beautify_detail.h"

namespace kintsugi::detail {

namespace {

std::string repair_short_edge(RepairContext& c) {
  Body& b = c.b;
  EdgeH e = c.problem.first<EdgeH>();
  if (!b.alive(e)) return "no edge named";
  if (!(edge_length(b, e) < c.tol.length)) return e.str() + " is no longer short";
  HalfedgeH h = halfedge_of(e, 0);
  if (b.origin(h) == b.target(h)) return e.str() + " is a closed edge: no vertex to collapse it to";
  if (b.degree(b.origin(h)) == 1) h = twin(h);  // keep the vertex that has other edges
  const geo::Vec3 mid = 0.5 * (b.point(b.origin(h)) + b.point(b.target(h)));
  for (HalfedgeH s : {h, twin(h)})
    if (b.face(s).valid()) c.touched.faces.insert(b.face(s));
  VertexH keep = b.origin(h);
  auto r = euler::kev(b, h);
  if (!r) return std::string("kev refused: ") + r.error().message;
  return place_vertices(b, {{keep, mid}}, c.tol, c.tol.max_vertex_move(), c.touched);
}

}  // namespace
}  // namespace kintsugi::detail

KINTSUGI_PASS(short_edge) = {kintsugi::ProblemType::short_edge, "short edges",
                             "the edge collapses to one vertex where the faces around it meet",
                             kintsugi::detail::repair_short_edge};
