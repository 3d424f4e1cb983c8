// Pass 8, adjacent faces with the same geometry (paper 4.5): every edge between the two
// faces is removed (kef for the first, which kills the second face; then struts left
// hanging are killed with kev and edges that still separate the face from itself become
// rings with kemr, unless the face goes round its surface's axis across one: that edge
// is its seam and stays). The union's surface is a least-squares fit over both faces'
// boundary samples (geo::fit_surface_like, the type of the surviving face); the merged
// face's vertices move to where their faces now meet (at most the tolerance), and the
// edges there get curves through them. Vertices left on two edges are for pass 10.
#include "geometry/same_geometry.h"
#include "invariants/element_geometry.h"
#include "kernel/euler.h"
#include "repair/beautify_detail.h"

#include <cmath>
#include <map>
#include <set>
#include <variant>

namespace kintsugi::detail {

namespace {

// What detection compared (invariants/element_geometry.h): the fit over them is within
// the tolerance of the whole faces exactly when it is within it of these points.
std::vector<geo::Vec3> samples(const Body& b, FaceH f, const geo::Tolerances& tol) {
  return surface_samples(b, f, tol.probe_chordal());
}

// Edges with f on one side and g on the other.
std::vector<EdgeH> common_edges(const Body& b, FaceH f, FaceH g) {
  std::vector<EdgeH> out;
  for (LoopH l : b.loops_of(f))
    for (HalfedgeH h : b.loop_halfedges(l))
      if (b.face(twin(h)) == g) out.push_back(edge_of(h));
  return out;
}

// Whether the half-edges from next(h) to prev(twin(h)) — the loop kemr(h) would make —
// go once round the axis of the face's surface. Then edge_of(h) is not a bridge to an
// inner boundary but the face's seam: two faces of one cylinder split along two rulings
// have both rulings in common, and once the first is killed the second joins the face to
// itself the way a seam does. Made into a ring instead, it left a cylinder bounded by two
// circles and no seam, which OpenCASCADE cannot orient.
bool goes_round_axis(const Body& b, HalfedgeH h, const geo::Surface& s, const geo::Tolerances& tol) {
  const geo::Frame* frame = seam_frame(s);
  if (!frame) return false;
  const geo::Vec3 x = frame->x, y = frame->y();
  double turn = 0, last = 0;
  bool started = false;
  for (HalfedgeH e = b.next(h); e != twin(h); e = b.next(e))
    for (const geo::Vec3& p : halfedge_polyline(b, e, tol.region_chordal())) {
      const geo::Vec3 r = p - frame->origin;
      const double a = std::atan2(r.dot(y), r.dot(x));
      if (started) turn += std::remainder(a - last, 2 * M_PI);
      last = a;
      started = true;
    }
  return std::abs(std::abs(turn) - 2 * M_PI) < 0.5;
}

}  // namespace

std::string repair_same_geometry(RepairContext& c) {
  Body& b = c.b;
  auto faces = c.problem.all<FaceH>();
  if (faces.size() != 2) return "two faces needed";
  FaceH f = faces[0], g = faces[1];
  if (!b.alive(f) || !b.alive(g)) return "no longer present: a face was removed by an earlier repair";
  if (f == g) return "one face";
  if (b.surface(f).index() != b.surface(g).index()) return "the surfaces are of different types";
  auto common = common_edges(b, f, g);
  if (common.empty()) return f.str() + " and " + g.str() + " are no longer adjacent";
  std::vector<geo::Vec3> pts = samples(b, f, c.tol), pg = samples(b, g, c.tol);
  if (geo::surface_deviation(b.surface(f), b.surface(g), pts, pg, c.tol.length) > c.tol.length)
    return "the surfaces of " + f.str() + " and " + g.str() + " no longer agree within tolerance";
  // Neighbours with nearly the same surface as either face (detected pairs still queued
  // for merging) stay out of the vertices' meeting points: nearly parallel surfaces meet
  // ill-conditioned.
  std::set<FaceH> alike;
  for (auto [x, px] : {std::pair{f, &pts}, std::pair{g, &pg}})
    for (LoopH l : b.loops_of(x))
      for (HalfedgeH h : b.loop_halfedges(l)) {
        FaceH n = b.face(twin(h));
        if (n.valid() && n != f && n != g && !alike.count(n) && b.surface(n).index() == b.surface(x).index() &&
            geo::surface_deviation(b.surface(x), b.surface(n), *px, samples(b, n, c.tol), c.tol.length) <= c.tol.length)
          alike.insert(n);
      }
  pts.insert(pts.end(), pg.begin(), pg.end());
  // On a surface with a seam, two pieces split along two rulings (a face fitted in
  // pieces round its axis) share both, and the one not killed stays as the merged face's
  // seam. Keep the one whose ends carry the most edges: the killed one's ends are then
  // left on two edges each and pass 10 joins them away, while the kept one's ends are
  // vertices anyway (a chamfer's cone whose seam met the shaft's seam at one vertex kept
  // another ruling, and the circle between them had a vertex too many: scan parts,
  // stepped_shaft). A ruling may be several common edges, joined at vertices on no other
  // edge (a gap closed across it, for pass 10 to join): its ends are those of the run
  // (scan parts, cone_boss with a gap on the seam: its middle piece, whose own ends carry
  // two edges each, was killed first, and the ruling with it).
  if (seam_frame(b.surface(f)) && common.size() > 1) {
    const std::set<EdgeH> in_common(common.begin(), common.end());
    // The far end of the run of common edges leaving v along e.
    auto run_end = [&](VertexH v, EdgeH e) {
      for (std::size_t guard = 0; guard < common.size(); ++guard) {
        auto outs = b.outgoing(v);
        if (outs.size() != 2) break;
        const EdgeH next = edge_of(outs[0]) == e ? edge_of(outs[1]) : edge_of(outs[0]);
        if (next == e || !in_common.count(next)) break;
        const HalfedgeH h = halfedge_of(next, 0);
        v = b.origin(h) == v ? b.target(h) : b.origin(h);
        e = next;
      }
      return v;
    };
    std::map<EdgeH, std::size_t> carried;
    for (EdgeH e : common) {
      const HalfedgeH h = halfedge_of(e, 0);
      carried[e] = b.degree(run_end(b.origin(h), e)) + b.degree(run_end(b.target(h), e));
    }
    std::stable_sort(common.begin(), common.end(), [&](EdgeH x, EdgeH y) { return carried[x] < carried[y]; });
  }
  // Kill the first common edge whose side in g is g's outer loop (kef's precondition);
  // else the other way round.
  HalfedgeH first;
  for (EdgeH e : common)
    for (unsigned s = 0; s < 2 && !first.valid(); ++s) {
      HalfedgeH h = halfedge_of(e, s);
      if (b.face(h) == f && b.is_outer(b.loop(twin(h)))) first = h;
    }
  if (!first.valid()) {
    std::swap(f, g);
    for (EdgeH e : common)
      for (unsigned s = 0; s < 2 && !first.valid(); ++s) {
        HalfedgeH h = halfedge_of(e, s);
        if (b.face(h) == f && b.is_outer(b.loop(twin(h)))) first = h;
      }
  }
  if (!first.valid()) return "no common edge lies on either face's outer loop";
  geo::SurfaceFit fit = geo::fit_surface_like(b.surface(f), pts);
  if (!fit.converged) return "no surface fits both faces: " + fit.problem;
  if (fit.max_deviation > c.tol.length) return "the best common surface is " + std::to_string(fit.max_deviation) + " from the faces";
  std::vector<VertexH> ends;
  for (EdgeH e : common)
    for (unsigned s = 0; s < 2; ++s) ends.push_back(b.origin(halfedge_of(e, s)));
  EdgeH first_edge = edge_of(first);
  auto k = euler::kef(b, first);
  if (!k) return std::string("kef refused: ") + k.error().message;
  // The rest: f on both sides now. Struts first (kev towards the hanging vertex), then rings.
  std::vector<EdgeH> rest;
  for (EdgeH e : common)
    if (e != first_edge) rest.push_back(e);
  for (std::size_t guard = 0; !rest.empty() && guard < 4 * common.size() + 4; ++guard) {
    bool progress = false;
    for (std::size_t i = 0; i < rest.size(); ++i) {
      HalfedgeH h = halfedge_of(rest[i], 0);
      HalfedgeH toward;  // kev(toward) kills target(toward)
      if (b.degree(b.target(h)) == 1) toward = h;
      else if (b.degree(b.origin(h)) == 1) toward = twin(h);
      if (!toward.valid()) continue;
      auto r = euler::kev(b, toward);
      if (!r) return std::string("kev refused: ") + r.error().message;
      rest.erase(rest.begin() + std::ptrdiff_t(i));
      progress = true;
      break;
    }
    if (progress) continue;
    // kemr(h) makes the ring of the half-edges from next(h) to prev(twin(h)): pick the
    // side whose piece encloses less (the inner one). A boss whose pinch was zipped to the
    // edge between the two faces has its footprint bounded by both: removing their last
    // common edge leaves the footprint as a ring, and taking the outer boundary for the
    // ring turned the merged face inside out.
    auto enclosed = [&](HalfedgeH h) {
      geo::Vec3 n = geo::Vec3::Zero();
      std::vector<geo::Vec3> pts;
      for (HalfedgeH x = b.next(h); x != twin(h); x = b.next(x)) pts.push_back(b.point(b.origin(x)));
      for (std::size_t i = 0; i < pts.size(); ++i) n += pts[i].cross(pts[(i + 1) % pts.size()]);
      return n.norm();
    };
    HalfedgeH cut = halfedge_of(rest.front(), 0);
    if (goes_round_axis(b, cut, b.surface(f), c.tol)) {
      rest.erase(rest.begin());  // the merged face's seam
      continue;
    }
    if (enclosed(twin(cut)) < enclosed(cut)) cut = twin(cut);
    auto r = euler::kemr(b, cut);
    if (!r) return std::string("kemr refused: ") + r.error().message;
    rest.erase(rest.begin());
  }
  if (!rest.empty()) return "common edges could not all be removed";
  b.set_surface(f, fit.surface, b.same_sense(f));
  c.touched.faces.insert(f);
  std::vector<std::pair<VertexH, geo::Vec3>> guesses;
  std::set<VertexH> seen;
  for (LoopH l : b.loops_of(f))
    for (VertexH v : b.loop_vertices(l))
      if (seen.insert(v).second) guesses.push_back({v, b.point(v)});
  for (VertexH v : ends)
    if (b.alive(v) && seen.insert(v).second) guesses.push_back({v, b.point(v)});
  return place_vertices(b, guesses, c.tol, c.tol.max_refit_move(), c.touched, alike);
}

}  // namespace kintsugi::detail

KINTSUGI_PASS(same_geometry) = {kintsugi::ProblemType::same_geometry_faces, "adjacent faces with the same geometry",
                                "the edges between the faces are removed and one surface fitted to both",
                                kintsugi::detail::repair_same_geometry};
