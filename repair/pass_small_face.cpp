// Pass 9, small faces (paper 4.6): the face is replaced by one vertex where the faces
// around it meet. Topology: kev along the face's loop until it has two edges, kef to
// kill the face across one of them, kev of the last; that vertex is then put at the
// meeting point of the neighbouring faces (geo::meet_point, least squares for more than
// three, starting from the centroid of the face's vertices) and the edges at it get
// curves through it. A neighbour that would be left with fewer than three sides makes
// the repair refuse.
#include "kernel/euler.h"
#include "repair/beautify_detail.h"

#include <map>

namespace kintsugi::detail {

namespace {

std::string repair_small_face(RepairContext& c) {
  Body& b = c.b;
  FaceH f = c.problem.first<FaceH>();
  if (!b.alive(f)) return "no face named";
  if (!b.rings_of(f).empty()) return f.str() + " has inner loops";
  LoopH l = b.outer_loop(f);
  if (b.is_lone(l)) return f.str() + " has no edges";
  if (!(face_area(b, f, c.tol) < c.tol.length * c.tol.length)) return f.str() + " is no longer small";
  auto hs = b.loop_halfedges(l);
  geo::Vec3 centroid = geo::Vec3::Zero();
  std::map<FaceH, int> shared;
  for (HalfedgeH h : hs) {
    centroid += b.point(b.origin(h));
    FaceH g = b.face(twin(h));
    if (!g.valid()) return f.str() + " borders a gap";
    if (g == f) return f.str() + " meets itself along " + edge_of(h).str();
    shared[g]++;
  }
  centroid /= double(hs.size());
  for (auto [g, n] : shared)
    if (b.loop_halfedges(b.outer_loop(g)).size() < std::size_t(n) + 2 + 1 && b.rings_of(g).empty())
      return "neighbour " + g.str() + " would be left with fewer than three sides";
  // kev until two edges are left.
  while (b.loop_halfedges(b.outer_loop(f)).size() > 2) {
    HalfedgeH h = b.first(b.outer_loop(f));
    if (b.degree(b.origin(h)) == 1) h = twin(h);  // kev keeps origin(h): keep the one with edges
    auto r = euler::kev(b, h);
    if (!r) return std::string("kev refused: ") + r.error().message;
  }
  auto two = b.loop_halfedges(b.outer_loop(f));
  if (two.size() != 2) return f.str() + " did not reduce to two edges";
  // Kill f across its first edge; the second edge then separates two neighbours.
  auto k = euler::kef(b, twin(two[0]));
  if (!k) return std::string("kef refused: ") + k.error().message;
  HalfedgeH last = two[1];
  if (b.degree(b.origin(last)) == 1) last = twin(last);
  VertexH keep = b.origin(last);
  auto r = euler::kev(b, last);
  if (!r) return std::string("kev refused: ") + r.error().message;
  for (FaceH g : faces_around(b, keep)) c.touched.faces.insert(g);
  return place_vertices(b, {{keep, centroid}}, c.tol, c.tol.max_vertex_move(), c.touched);
}

}  // namespace
}  // namespace kintsugi::detail

KINTSUGI_PASS(small_face) = {kintsugi::ProblemType::small_face, "small faces",
                             "the face is replaced by one vertex where the faces around it meet",
                             kintsugi::detail::repair_small_face};
