// Pass 6, sliver faces (paper 4.4, Figure 23; branched slivers, paper 7 and Figure
// 32(a)): a long thin face is replaced by edges along which the faces on either side of
// it meet.
//
// Accepts: sliver_face [the face]. Topology (repair/face_collapse.h):
//   1. jekv away the sliver's vertices that lie on no other edge;
//   2. the edge sequence through the rest (paper 4.4): the two closest vertices first,
//      then always the vertex closest to one end of the growing sequence;
//   3. its edges that are not edges of the sliver become chords (mef), and every piece
//      the chords cut the sliver into is killed (kef) into the face beyond its one edge
//      outside the sequence.
// A branched sliver (three or more arms) has no such sequence: its chords cross, or a
// vertex would have to move farther than the tolerance to where its new faces meet. It
// is then collapsed onto a tree instead: a junction vertex where the faces around the
// sliver meet, joined to the vertices of each arm (Prim's tree from the junction, so each
// vertex hangs from the nearest vertex already joined).
// Geometry: every vertex of the sequence or tree goes to where its faces now meet
// (place_vertices, at most twice the tolerance from where it was), and every edge there
// gets the curve where its two faces meet (derive_edge_curve).
// A vertex left on two edges between the same two faces (where the sliver's short end
// edge now continues the edge beyond it) is joined away (jekv), so the sliver's ends do
// not stay as short edges or mergeable vertices.
// May leave (Table 1, column 6): short edges and chains of them, adjacent faces with the
// same geometry.
#include "geometry/meet_point.h"
#include "geometry/surface.h"
#include "invariants/element_geometry.h"
#include "kernel/euler.h"
#include "kernel/transaction.h"
#include "repair/beautify_detail.h"
#include "repair/detect_detail.h"
#include "repair/face_collapse.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <map>
#include <optional>

namespace kintsugi::detail {

namespace {

using Tree = std::vector<std::pair<VertexH, VertexH>>;

// Paper 4.4: the closest pair first, then the vertex closest to either end.
std::vector<VertexH> edge_sequence(const Body& b, std::vector<VertexH> rest) {
  auto d = [&](VertexH x, VertexH y) { return (b.point(x) - b.point(y)).norm(); };
  std::size_t bi = 0, bj = 1;
  for (std::size_t i = 0; i < rest.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (d(rest[i], rest[j]) < d(rest[bi], rest[bj])) bi = i, bj = j;
  std::deque<VertexH> seq{rest[bi], rest[bj]};
  rest.erase(rest.begin() + std::ptrdiff_t(std::max(bi, bj)));
  rest.erase(rest.begin() + std::ptrdiff_t(std::min(bi, bj)));
  while (!rest.empty()) {
    std::size_t best = 0;
    bool front = true;
    double best_d = HUGE_VAL;
    for (std::size_t i = 0; i < rest.size(); ++i) {
      if (d(rest[i], seq.front()) < best_d) best_d = d(rest[i], seq.front()), best = i, front = true;
      if (d(rest[i], seq.back()) < best_d) best_d = d(rest[i], seq.back()), best = i, front = false;
    }
    if (front)
      seq.push_front(rest[best]);
    else
      seq.push_back(rest[best]);
    rest.erase(rest.begin() + std::ptrdiff_t(best));
  }
  return {seq.begin(), seq.end()};
}

Tree path_edges(const std::vector<VertexH>& seq) {
  Tree t;
  for (std::size_t i = 0; i + 1 < seq.size(); ++i) t.push_back({seq[i], seq[i + 1]});
  return t;
}

// Places the vertices of the collapsed sliver where their faces meet. A vertex left on
// two edges between the same two faces (an end of the sliver whose short end edge now
// continues the edge beyond it) is joined away first: the paper's Table 1 has sliver
// removal create no mergeable edges, and this is why.
std::string place(RepairContext& c, const std::vector<VertexH>& vs) {
  Body& b = c.b;
  std::vector<std::pair<VertexH, geo::Vec3>> guesses;
  for (VertexH v : vs) {
    auto outs = b.outgoing(v);
    if (outs.size() == 2 && edge_of(outs[0]) != edge_of(outs[1])) {
      // By value: std::minmax of two temporaries returns references to them, dangling
      // once the lambda returns (AddressSanitizer: stack-use-after-scope).
      auto pair = [&](HalfedgeH h) {
        const FaceH x = b.face(h), y = b.face(twin(h));
        return std::pair<FaceH, FaceH>(std::min(x, y), std::max(x, y));
      };
      if (pair(outs[0]) == pair(outs[1])) {
        // The longer edge (the one beyond the sliver) keeps its handle: a problem at its
        // far end keeps its identity.
        HalfedgeH keep = edge_length(b, edge_of(outs[0])) >= edge_length(b, edge_of(outs[1])) ? outs[0] : outs[1];
        auto r = euler::jekv(b, twin(keep));
        if (!r) return "jekv refused at " + v.str() + ": " + r.error().message;
        continue;
      }
    }
    guesses.push_back({v, b.point(v)});
  }
  for (auto [v, p] : guesses)
    for (FaceH g : faces_around(b, v)) c.touched.faces.insert(g);
  return place_vertices(b, guesses, c.tol, 2 * c.tol.length, c.touched, {}, c.coincide);
}

std::string unbranched(RepairContext& c, FaceH f, const std::vector<VertexH>& loop) {
  std::vector<VertexH> seq = edge_sequence(c.b, loop);
  Tree tree = path_edges(seq);
  if (chords_cross(loop, tree)) return "its edge sequence crosses itself (a branched sliver)";
  if (auto why = collapse_onto_tree(c.b, f, tree); !why.empty()) return why;
  return place(c, seq);
}

// The point where the faces around a branched sliver meet: the faces it shares the most
// boundary with (its sides, not its short ends), as many as it has arms.
std::optional<geo::Vec3> junction_point(const Body& b, FaceH f, const geo::Tolerances& tol, std::size_t arms,
                                        const geo::Vec3& guess) {
  std::map<FaceH, double> shared;
  for (HalfedgeH h : b.loop_halfedges(b.outer_loop(f))) shared[b.face(twin(h))] += edge_length(b, edge_of(h));
  std::vector<std::pair<double, FaceH>> by_length;
  for (auto [g, len] : shared) by_length.push_back({len, g});
  std::sort(by_length.rbegin(), by_length.rend());
  if (by_length.size() < 3) return std::nullopt;
  std::vector<geo::Surface> sides;
  for (std::size_t i = 0; i < std::min(arms, by_length.size()); ++i) sides.push_back(b.surface(by_length[i].second));
  geo::MeetPoint m = geo::meet_point(sides, guess, tol.length, tol.precision);
  if (m.status == geo::MeetStatus::no_point || m.status == geo::MeetStatus::degenerate) return std::nullopt;
  return m.point;
}

std::string branched(RepairContext& c, FaceH f, const std::vector<VertexH>& loop) {
  Body& b = c.b;
  // Arms: runs of the loop between its sharp turns back (the tips). Counted as the loop
  // vertices whose two loop neighbours lie on the same side, seen from the centroid.
  geo::Vec3 centre = geo::Vec3::Zero();
  for (VertexH v : loop) centre += b.point(v);
  centre /= double(loop.size());
  // Faces it shares boundary with beyond its two sides: at least three sides make a branch.
  std::size_t sides = 0;
  {
    std::map<FaceH, double> shared;
    for (HalfedgeH h : b.loop_halfedges(b.outer_loop(f))) shared[b.face(twin(h))] += edge_length(b, edge_of(h));
    for (auto [g, len] : shared) sides += len > 2 * c.tol.length;
  }
  if (sides < 3) return "fewer than three faces run along it: not a branched sliver";
  auto j = junction_point(b, f, c.tol, sides, centre);
  if (!j) return "the faces along its arms do not meet in a point";
  // Prim's tree from the junction over the loop's vertices.
  std::vector<geo::Vec3> at{*j};
  std::vector<VertexH> in{VertexH{}};
  std::vector<VertexH> rest = loop;
  Tree tree;
  while (!rest.empty()) {
    std::size_t bi = 0, bj = 0;
    double best = HUGE_VAL;
    for (std::size_t i = 0; i < rest.size(); ++i)
      for (std::size_t k = 0; k < in.size(); ++k) {
        double d = (b.point(rest[i]) - at[k]).norm();
        if (d < best) best = d, bi = i, bj = k;
      }
    tree.push_back({in[bj], rest[bi]});
    in.push_back(rest[bi]);
    at.push_back(b.point(rest[bi]));
    rest.erase(rest.begin() + std::ptrdiff_t(bi));
  }
  std::size_t spokes = 0;
  for (auto [u, w] : tree) spokes += !u.valid();
  if (spokes < 2) return "its tree has a single arm";
  if (chords_cross(loop, tree)) return "its tree of edges crosses itself";
  VertexH junction;
  if (auto why = collapse_onto_tree(b, f, tree, &junction, *j); !why.empty()) return why;
  std::vector<VertexH> vs = loop;
  vs.push_back(junction);
  return place(c, vs);
}

// Where a surface of revolution meets a plane square to its axis, the point of that circle
// in the axial half-plane through p: the ring's vertex on c2 goes there, so that it stays
// on the seam's ruling. The meeting point's solve, given p 0.05 off both, slid it 0.003 rad
// round the circle, and the seam from the side's far end became a chord 3e-5 off the
// cylinder (the scan-parts score, shaft). p itself where the surfaces are not of that
// kind, or the ray does not meet the surface.
geo::Vec3 on_both_at_its_angle(const geo::Surface& side, const geo::Surface& cap, const geo::Vec3& p,
                               const geo::Tolerances& tol) {
  const auto* plane = std::get_if<geo::Plane>(&cap);
  std::optional<geo::Frame> axis;
  if (const auto* s = std::get_if<geo::Cylinder>(&side)) axis = s->frame;
  if (const auto* s = std::get_if<geo::Cone>(&side)) axis = s->frame;
  if (const auto* s = std::get_if<geo::Torus>(&side)) axis = s->frame;
  if (!plane || !axis) return p;
  const geo::Vec3 n = plane->frame.z.normalized(), z = axis->z.normalized();
  if (std::abs(std::abs(n.dot(z)) - 1) > 1e-9) return p;
  // The axis meets the plane at o; the ray from o through p's projection.
  const geo::Vec3 o = axis->origin + (plane->frame.origin - axis->origin).dot(n) / z.dot(n) * z;
  geo::Vec3 d = p - o;
  d -= d.dot(n) * n;
  double t = d.norm();
  if (!(t > 0)) return p;
  d /= t;
  // Secant on the distance to the side along the ray.
  auto f = [&](double x) { return geo::signed_distance(side, o + x * d); };
  double t0 = t, f0 = f(t0), t1 = t + 1e-3 * tol.length, f1 = f(t1);
  for (int i = 0; i < 50 && std::abs(f1) > 0.01 * tol.precision; ++i) {
    if (!(std::abs(f1 - f0) > 0)) break;
    const double t2 = t1 - f1 * (t1 - t0) / (f1 - f0);
    t0 = t1, f0 = f1, t1 = t2, f1 = f(t1);
  }
  if (!(std::abs(f1) <= tol.precision) || !(std::abs(t1 - t) <= 2 * tol.length)) return p;
  return o + t1 * d;
}

// A ring sliver: a narrow band round a periodic surface — a scanned chamfer or fillet of a
// circular edge, a cone's or torus's band between a cylinder's side and a cap — bounded
// by two closed edges and joined across by its seam: its one loop is [c1, s, c2, s⁻¹].
// It has no two ends to collapse (the general collapse stops at "meets itself along"
// its seam). It becomes the closed edge where the faces across c1 and c2 meet: c1 is
// killed (kef), the band joining the face across it; the seam's vertex on c1, now on
// that face's seam and the band's only, is joined away (jekv), so the seams make one;
// the vertex on c2 goes to where the two faces meet (place_vertices), and c2 and the
// seam get the curves there. Applies when both closed edges are single edges once their
// pieces are joined (the seams of the band and of the face across c1 meet c1 at one
// vertex, as OpenCASCADE's chamfers and fillets of a circle make them); nullopt when f
// is not such a band.
std::optional<std::string> ring_sliver(RepairContext& c, FaceH f) {
  Body& b = c.b;
  std::vector<LoopH> loops = b.loops_of(f);
  if (loops.size() != 1 || b.is_lone(loops[0])) return std::nullopt;
  std::vector<HalfedgeH> hs = b.loop_halfedges(loops[0]);
  // A closed edge may come in pieces: vertices on two edges only, both between f and one
  // other face (a short-edge chain cut into the circle, or a vertex pass 10 would join;
  // both later passes). Such a band is a ring all the same: the pieces are joined first.
  auto joinable = [&](HalfedgeH h) {
    const HalfedgeH n = b.next(h);
    return b.degree(b.target(h)) == 2 && edge_of(h) != edge_of(n) && b.face(twin(h)) == b.face(twin(n)) &&
           b.face(twin(h)).valid() && b.face(twin(h)) != f;
  };
  // Joined only when the loop is [c1 pieces, s, c2 pieces, s⁻¹]: the seam s the one edge
  // it runs along both ways, each side between them a run of joinable pieces.
  auto pieces_of_a_ring = [&]() {
    const std::size_t n = hs.size();
    std::size_t s1 = n, s2 = n;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j)
        if (edge_of(hs[i]) == edge_of(hs[j])) {
          if (s1 != n) return false;  // a second edge run both ways
          s1 = i, s2 = j;
        }
    if (s1 == n || s2 == s1 + 1 || (s1 == 0 && s2 == n - 1)) return false;
    // Within each side every vertex but the side's last joins two pieces.
    for (std::size_t i = (s1 + 1) % n; (i + 1) % n != s2; i = (i + 1) % n)
      if (!joinable(hs[i])) return false;
    for (std::size_t i = (s2 + 1) % n; (i + 1) % n != s1; i = (i + 1) % n)
      if (!joinable(hs[i])) return false;
    return true;
  };
  if (hs.size() > 4 && pieces_of_a_ring()) {
    for (std::size_t guard = hs.size(); guard > 0; --guard) {
      auto it = std::find_if(hs.begin(), hs.end(), joinable);
      if (it == hs.end()) break;
      if (auto r = euler::jekv(b, *it); !r) return "jekv refused at " + b.target(*it).str() + ": " + r.error().message;
      hs = b.loop_halfedges(loops[0]);
    }
  }
  if (hs.size() != 4) return std::nullopt;
  // Rotate so that hs[1] and hs[3] are the seam's two sides.
  std::size_t k = 0;
  while (k < 4 && edge_of(hs[(k + 1) % 4]) != edge_of(hs[(k + 3) % 4])) ++k;
  if (k == 4) return std::nullopt;
  std::rotate(hs.begin(), hs.begin() + std::ptrdiff_t(k), hs.end());
  HalfedgeH c1 = hs[0], c2 = hs[2];
  if (edge_of(c1) == edge_of(c2) || b.origin(c1) != b.target(c1) || b.origin(c2) != b.target(c2)) return std::nullopt;
  // The band joins the face across c1 along it, which kef cannot do where c1 is that
  // face's whole loop (a plate's hole round a boss): then across c2.
  if (b.loop_halfedges(b.loop(twin(c1))).size() == 1) std::swap(c1, c2);
  const FaceH a = b.face(twin(c1)), p = b.face(twin(c2));
  if (!a.valid() || !p.valid() || a == f || p == f || a == p) return std::nullopt;
  const VertexH v1 = b.origin(c1), v2 = b.origin(c2);
  // The band joins the face across c1: kef keeps h's face, a.
  if (auto r = euler::kef(b, twin(c1)); !r) return "kef refused at " + edge_of(c1).str() + ": " + r.error().message;
  // v1 now lies on a's seam and the band's only: one seam from a's far edge to v2.
  std::vector<HalfedgeH> outs = b.outgoing(v1);
  if (outs.size() != 2 || edge_of(outs[0]) == edge_of(outs[1]))
    return v1.str() + " is left on " + std::to_string(outs.size()) + " edges, not on two seams";
  const HalfedgeH keep = edge_length(b, edge_of(outs[0])) >= edge_length(b, edge_of(outs[1])) ? outs[0] : outs[1];
  if (auto r = euler::jekv(b, twin(keep)); !r) return "jekv refused at " + v1.str() + ": " + r.error().message;
  c.touched.faces.insert(a);
  c.touched.faces.insert(p);
  c.note = "a ring: " + f.str() + " became the closed edge where " + a.str() + " and " + p.str() + " meet";
  return place_vertices(b, {{v2, on_both_at_its_angle(b.surface(a), b.surface(p), b.point(v2), c.tol)}}, c.tol,
                        2 * c.tol.length, c.touched);
}

std::string repair_sliver_face(RepairContext& c) {
  Body& b = c.b;
  FaceH f = c.problem.first<FaceH>();
  if (!f.valid()) return "no face named";
  if (auto why = ring_sliver(c, f)) return *why;
  if (auto why = collapsible(b, f); !why.empty()) return why;
  auto m = face_area_and_bounds(b, f, 1e-3 * c.tol.length);
  const double length = m ? sliver_length(b, f, m->bounds.diagonal(), [&](EdgeH e) { return edge_length(b, e); }) : 0.0;
  if (!m || !(length > 0) || !(m->area / length < c.tol.length)) return f.str() + " is no longer a sliver";
  if (auto why = drop_bare_vertices(b, f); !why.empty()) return why;
  std::vector<VertexH> loop = b.loop_vertices(b.outer_loop(f));
  if (loop.size() < 2) return f.str() + " has fewer than two vertices on other edges";
  for (std::size_t i = 0; i < loop.size(); ++i)
    for (std::size_t k = 0; k < i; ++k)
      if (loop[i] == loop[k]) return f.str() + " passes " + loop[i].str() + " twice";
  std::string first;
  {
    Transaction attempt(b);
    Touched before = c.touched;
    first = unbranched(c, f, loop);
    if (first.empty()) {
      attempt.commit();
      return "";
    }
    attempt.rollback();
    c.touched = before;
  }
  std::string second = branched(c, f, loop);
  if (second.empty()) return "";
  return "as a sequence: " + first + "; as a branched sliver: " + second;
}

}  // namespace

}  // namespace kintsugi::detail

KINTSUGI_PASS(sliver_face) = {kintsugi::ProblemType::sliver_face, "sliver faces",
                              "a long thin face becomes the edges where the faces on either side of it meet",
                              kintsugi::detail::repair_sliver_face};
