// Pass 11, short edges (paper 4.6): kev collapses the edge onto one of its vertices,
// which then moves to the point that best fits all the faces around it
// (geo::meet_point, least squares for more than three), and the edges there get curves
// through it. A collapse that would leave a face with two straight sides is refused.
#include "invariants/element_geometry.h"
#include "kernel/euler.h"
#include "repair/beautify_detail.h"

namespace kintsugi::detail {

std::string repair_short_edge(RepairCall& c) {
  Body& b = c.b;
  if (c.problem.elements.empty()) return "no edge named";
  EdgeH e = parse_edge(c.problem.elements[0]);
  if (!b.alive(e)) return "no longer present: " + c.problem.elements[0] + " was removed by an earlier repair";
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
  return place_vertices(b, {{keep, mid}}, c.tol, 2 * c.tol.length, c.touched);
}

std::vector<Problem> short_edge_follow_ups(const Body& b, const geo::Tolerances& tol, const Touched& touched) {
  std::vector<Problem> out;
  for (VertexH v : touched.vertices) {
    if (!b.alive(v)) continue;
    for (HalfedgeH h : b.outgoing(v)) {
      EdgeH e = edge_of(h);
      double len = edge_length(b, e);
      if (!(len < tol.length)) continue;
      bool face_small = false;  // an edge of a small face goes with that face, not here
      for (HalfedgeH s : {h, twin(h)})
        if (!b.face(s).valid() || face_area(b, b.face(s), tol) < tol.length * tol.length) face_small = true;
      if (!face_small) out.push_back({ProblemType::short_edge, {e.str()}, len, "length", ""});
    }
  }
  return out;
}

}  // namespace kintsugi::detail
