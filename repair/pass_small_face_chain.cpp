// Pass 5, chains of small faces (paper 3.2 item 5, 4.3, Figures 4 and 12; networks of
// small faces, paper 7): each face of the chain is replaced by a vertex, and the vertices
// are joined in the chain's order; every edge that met the chain's faces moves to the
// new vertex nearest where it met them. The chain becomes a chain of short edges, which
// pass 7 joins into one edge (or pass 11 collapses into a vertex at a corner). A network
// (small faces whose adjacency is a tree with branches) becomes the same tree of edges.
//
// Accepts: small_face_chain [its faces]. Topology (a zip, Euler operators only):
//   1. kef across the edges between the chain's faces: one face U;
//   2. jekv away U's vertices on no other edge; every other vertex of U is labelled with
//      the chain face nearest to it (among the faces it was on: "the nearest new vertex");
//   3. kev along U's loop between consecutive vertices with one label, and semv a vertex
//      into an edge whose ends' faces are not adjacent (a face with no vertex of its own,
//      such as the middle of a notch), so that consecutive labels are adjacent faces;
//   4. zip from a tip: where the loop runs x1 → m → x2 with x1, x2 of one label and m the
//      only vertex of its own, a chord x1–x2 (mef), kev of the chord, and kef of the
//      two-sided piece left between m and the merged vertex, into the face beyond;
//   5. the last two-sided face is killed (kef) into one of its neighbours.
// A patch (adjacency with a cycle: small triangles round a cut corner) is joined into one
// face and collapsed into one vertex where the faces around it meet, as pass 9 does.
// Refused with the reason: closed rings of small faces (a patch that is not a disc),
// faces meeting along more than one edge, a loop whose labels do not come apart at a tip.
// Geometry: each new vertex goes to where its faces meet, starting from the centroid of
// its face's vertices (place_vertices, at most twice the tolerance away); consecutive
// vertices that would meet in one point are one vertex (kev), as at a corner. A new
// vertex left on two faces only, between two edges that both run between them, marks
// nothing and is removed (jekv; drop_free_vertices says why): a notch of small faces
// between two faces becomes one edge between them, not a chain of short edges.
// May leave (Table 1, column 5): short-edge chains, short edges, same-geometry faces,
// mergeable edges.
#include "geometry/meet_point.h"
#include "kernel/euler.h"
#include "repair/beautify_detail.h"
#include "repair/detect_detail.h"
#include "repair/face_collapse.h"

#include <algorithm>
#include <deque>
#include <map>
#include <set>

namespace kintsugi::detail {

namespace {

struct Network {
  std::vector<FaceH> faces;
  std::vector<std::vector<int>> adjacent;  // by index into faces
  std::vector<geo::Vec3> centroid;
};

// Labels are indices into the network's faces; a path between two of them in the
// (tree-shaped) adjacency.
std::vector<int> tree_path(const Network& n, int from, int to) {
  std::vector<int> parent(n.faces.size(), -1);
  std::deque<int> q{from};
  parent[std::size_t(from)] = from;
  while (!q.empty()) {
    int x = q.front();
    q.pop_front();
    for (int y : n.adjacent[std::size_t(x)])
      if (parent[std::size_t(y)] < 0) parent[std::size_t(y)] = x, q.push_back(y);
  }
  std::vector<int> path;
  if (parent[std::size_t(to)] < 0) return path;
  for (int x = to; x != from; x = parent[std::size_t(x)]) path.push_back(x);
  path.push_back(from);
  std::reverse(path.begin(), path.end());
  return path;
}

std::string read_network(const Body& b, const std::vector<FaceH>& faces, Network& n, bool* cycle) {
  *cycle = false;
  n.faces = faces;
  std::map<FaceH, int> index;
  for (std::size_t i = 0; i < faces.size(); ++i) index[faces[i]] = int(i);
  n.adjacent.assign(faces.size(), {});
  std::size_t links = 0;
  for (std::size_t i = 0; i < faces.size(); ++i) {
    FaceH f = faces[i];
    if (auto why = collapsible(b, f); !why.empty()) return why;
    geo::Vec3 c = geo::Vec3::Zero();
    auto vs = b.loop_vertices(b.outer_loop(f));
    for (VertexH v : vs) c += b.point(v);
    n.centroid.push_back(c / double(vs.size()));
    std::map<int, int> shared;
    for (HalfedgeH h : b.loop_halfedges(b.outer_loop(f))) {
      auto it = index.find(b.face(twin(h)));
      if (it != index.end()) shared[it->second]++;
    }
    for (auto [j, count] : shared) {
      if (count > 1) return f.str() + " and " + faces[std::size_t(j)].str() + " meet along more than one edge";
      n.adjacent[i].push_back(j);
      links++;
    }
  }
  links /= 2;
  if (links + 1 != faces.size()) {
    if (links + 1 > faces.size()) {
      *cycle = true;
      return "the small faces' adjacency has a cycle";
    }
    return "the small faces are not connected";
  }
  if (tree_path(n, 0, int(faces.size()) - 1).empty()) return "the small faces are not connected";
  return "";
}

// The label of vertex v: the nearest of the network's faces it lies on.
int label_of(const Body& b, const Network& n, const std::map<VertexH, std::vector<int>>& on, VertexH v) {
  auto it = on.find(v);
  if (it == on.end()) return -1;
  int best = -1;
  double best_d = HUGE_VAL;
  for (int i : it->second) {
    double d = (b.point(v) - n.centroid[std::size_t(i)]).norm();
    if (d < best_d) best_d = d, best = i;
  }
  return best;
}

// A new vertex on two faces only, between two edges that both run between them, lies
// anywhere along their meeting curve: place_vertices puts it nearest its face's centroid,
// and the region solve moves it with its neighbours. Along a notch of small faces those
// points need not come in the chain's order, and the chain of short edges then folds
// back on itself; the face beside it, walked round, comes back within the tolerance of
// itself: a pinch, made behind its pass (Table 1 audit, counterexample small_face_chain
// -> pinched_face beside a sliver, seed 2027: the fold appeared only after the solve had
// moved the chain's end). Such a vertex marks nothing (pass 10 would remove it as a
// mergeable vertex, after pass 7 joined its edges), so it is removed here (jekv) and the
// joined edge's curve derived again.
std::string drop_free_vertices(Body& b, const std::set<VertexH>& kept, RepairContext& c) {
  for (bool again = true; again;) {
    again = false;
    for (VertexH v : kept) {
      if (!b.alive(v)) continue;
      std::vector<HalfedgeH> out = b.outgoing(v);
      if (out.size() != 2 || faces_around(b, v).size() != 2) continue;
      const HalfedgeH in = twin(out[0]);  // ends at v; next(in) leaves v
      if (edge_of(b.next(in)) == edge_of(in) || b.origin(in) == b.target(b.next(in))) continue;
      const EdgeH keep = edge_of(in);
      const geo::Vec3 at = b.point(v);
      const geo::Curve first = b.curve(keep), second = b.curve(edge_of(b.next(in)));
      if (auto r = euler::jekv(b, in); !r) return "jekv refused at " + v.str() + ": " + r.error().message;
      if (std::string why = refit_joined_edge(b, keep, false, c.tol); !why.empty()) {
        // The two edges are not one curve (two branches of the faces' meeting): the vertex
        // stays (a new one in its place, with the edges' curves as they were).
        auto s = euler::semv(b, in, at);
        if (!s) return "semv refused on " + keep.str() + ": " + s.error().message;
        b.set_curve(keep, first);
        b.set_curve(edge_of(s->next), second);
        continue;
      }
      c.touched.edges.insert(keep);
      again = true;
      break;
    }
  }
  return "";
}

std::string repair_small_face_chain(RepairContext& c) {
  Body& b = c.b;
  std::vector<FaceH> faces = c.problem.all<FaceH>();
  if (faces.size() < 2) return "a chain needs two faces";
  for (FaceH f : faces)
    if (!b.alive(f)) return "no longer present: " + f.str() + " was removed by an earlier repair";
  for (FaceH f : faces)
    if (!(face_area(b, f, c.tol) < c.tol.length * c.tol.length)) return f.str() + " is no longer small";
  Network n;
  bool cycle = false;
  if (auto why = read_network(b, faces, n, &cycle); !why.empty()) {
    if (!cycle) return why;
    // A patch (three small triangles round a cut corner, each beside the other two): no
    // order to zip its faces in, and no edge of it stands for anything the tolerance can
    // see. It is one small region: joined into one face, it becomes one vertex where the
    // faces around it meet, as a small face does (pass 9 could not take it: its faces
    // are a chain's). A ring round something, or a patch whose neighbours do not meet in
    // one point near it, is refused.
    std::string not_joined;
    const FaceH u = join_patch(b, faces, &not_joined);
    if (!u.valid()) return "a patch of small faces (their adjacency has a cycle) that cannot be one face: " + not_joined;
    return collapse_to_vertex(b, u, c.tol, c.touched);
  }
  std::map<VertexH, std::vector<int>> on;
  for (std::size_t i = 0; i < faces.size(); ++i)
    for (VertexH v : b.loop_vertices(b.outer_loop(faces[i]))) on[v].push_back(int(i));

  // 1. One face U: kef across every edge between two faces of the network (a tree, so
  // each kef joins two different faces).
  FaceH u = faces[0];
  std::set<FaceH> members(faces.begin(), faces.end());
  for (bool again = true; again;) {
    again = false;
    for (HalfedgeH h : b.loop_halfedges(b.outer_loop(u))) {
      FaceH g = b.face(twin(h));
      if (g == u || !members.count(g)) continue;
      auto k = euler::kef(b, h);  // g is killed, its loop joins U's
      if (!k) return "kef refused across " + edge_of(h).str() + ": " + k.error().message;
      again = true;
      break;
    }
  }
  for (FaceH f : faces)
    if (f != u && b.alive(f)) return "the small faces did not join into one";
  // 2. Vertices on no other edge go; the others are labelled.
  if (auto why = drop_bare_vertices(b, u); !why.empty()) return why;
  auto label = [&](VertexH v) { return label_of(b, n, on, v); };
  // 3. Consecutive vertices of one label become one vertex; faces with no vertex get one.
  std::map<VertexH, int> made;  // vertices made by semv, with their label
  auto lab = [&](VertexH v) {
    auto it = made.find(v);
    return it != made.end() ? it->second : label(v);
  };
  for (bool again = true; again;) {
    again = false;
    auto hs = b.loop_halfedges(b.outer_loop(u));
    if (hs.size() <= 2) break;
    for (HalfedgeH h : hs) {
      if (lab(b.origin(h)) < 0 || lab(b.target(h)) < 0) return "a vertex of the chain has no face";
      if (lab(b.origin(h)) != lab(b.target(h))) continue;
      auto r = euler::kev(b, h);
      if (!r) return "kev refused on " + edge_of(h).str() + ": " + r.error().message;
      again = true;
      break;
    }
  }
  for (HalfedgeH h : b.loop_halfedges(b.outer_loop(u))) {
    std::vector<int> path = tree_path(n, lab(b.origin(h)), lab(b.target(h)));
    HalfedgeH at = h;
    for (std::size_t i = 1; i + 1 < path.size(); ++i) {
      auto s = euler::semv(b, at, n.centroid[std::size_t(path[i])]);
      if (!s) return "semv refused on " + edge_of(at).str() + ": " + s.error().message;
      made[s->vertex] = path[i];
      at = s->next;
    }
  }
  // 4. Zip from the tips.
  std::set<VertexH> kept;
  while (true) {
    auto hs = b.loop_halfedges(b.outer_loop(u));
    for (HalfedgeH h : hs) kept.insert(b.origin(h));
    if (hs.size() <= 2) break;
    std::map<int, int> count;
    for (HalfedgeH h : hs) count[lab(b.origin(h))]++;
    HalfedgeH in;  // x1 -> m
    for (HalfedgeH h : hs) {
      VertexH m = b.target(h);
      if (count[lab(m)] == 1 && lab(b.origin(h)) == lab(b.target(b.next(h)))) {
        in = h;
        break;
      }
    }
    if (!in.valid()) return "the faces of the chain do not come apart at a tip: no order to collapse them in";
    HalfedgeH out = b.next(in);
    VertexH x1 = b.origin(in), x2 = b.target(out);
    if (b.face(twin(in)) == b.face(twin(out)))
      return b.target(in).str() + " has " + b.face(twin(in)).str() + " on both sides";
    auto m = euler::mef(b, Corner::before(in), Corner::before(b.next(out)));  // x1 -> x2 stays in U
    if (!m) return "mef refused from " + x1.str() + " to " + x2.str() + ": " + m.error().message;
    HalfedgeH chord = m->a;  // x1 -> x2 in U
    if (b.origin(chord) != x1) chord = twin(chord);
    auto k = euler::kev(b, chord);  // x2 joins x1
    if (!k) return "kev refused on the chord from " + x1.str() + ": " + k.error().message;
    kept.erase(x2);
    auto g = euler::kef(b, twin(in));  // the two-sided piece joins the face beyond x1 -> m
    if (!g) return "kef refused across " + edge_of(in).str() + ": " + g.error().message;
  }
  // 5. The last two-sided face.
  auto two = b.loop_halfedges(b.outer_loop(u));
  if (two.size() != 2) return "the chain did not close up";
  if (b.face(twin(two[0])) == b.face(twin(two[1]))) return "the chain's last edge would have one face on both sides";
  auto k = euler::kef(b, twin(two[0]));
  if (!k) return "kef refused across " + edge_of(two[0]).str() + ": " + k.error().message;

  // Geometry: each label's vertex where its faces meet, from its face's centroid.
  std::map<int, VertexH> vertex_of;
  for (VertexH v : kept)
    if (b.alive(v)) vertex_of[lab(v)] = v;
  // Two neighbours whose faces meet in one point are one vertex (a chain at a corner).
  for (bool again = true; again;) {
    again = false;
    for (auto& [i, v] : vertex_of) {
      for (HalfedgeH h : b.outgoing(v)) {
        VertexH w = b.target(h);
        if (w == v || !kept.count(w) || !b.alive(w)) continue;
        std::vector<geo::Surface> sv, sw, both;
        std::set<FaceH> all;
        for (FaceH g : faces_around(b, v)) sv.push_back(b.surface(g)), all.insert(g);
        for (FaceH g : faces_around(b, w)) sw.push_back(b.surface(g)), all.insert(g);
        for (FaceH g : all) both.push_back(b.surface(g));
        auto pv = geo::meet_point(sv, n.centroid[std::size_t(i)], c.tol.length, c.tol.precision);
        auto pw = geo::meet_point(sw, n.centroid[std::size_t(lab(w))], c.tol.length, c.tol.precision);
        auto met = [](const geo::MeetPoint& m) {
          return m.status != geo::MeetStatus::no_point && m.status != geo::MeetStatus::degenerate;
        };
        if (!met(pv) || !met(pw)) continue;
        if ((pv.point - pw.point).norm() > 10 * c.tol.precision) {
          // A vertex on two faces only takes the point of their meeting curve nearest its
          // face's centroid, which can stop short of where its neighbour's faces meet (a
          // pyramid's apex cut off by two small faces: the second vertex came to rest 0.1
          // tolerance down an edge). When the edge between them would be shorter than the
          // tolerance and all their faces together meet in one point (within the
          // tolerance, as a gap's faces must; the region solve then makes it exact), that
          // point is the corner: keeping two vertices left a short edge at the corner's
          // tip, which pass 4 then saw as a spike — a pinched face created behind its pass
          // (the Table 1 audit's counterexamples small_face_chain -> pinched_face, once on
          // the exact pyramid, once after a pinch repair had moved its planes by a hair).
          if ((pv.point - pw.point).norm() >= c.tol.length) continue;
          auto pu = geo::meet_point(both, 0.5 * (pv.point + pw.point), c.tol.length, c.tol.precision);
          const bool corner = pu.status == geo::MeetStatus::exact || pu.status == geo::MeetStatus::least_squares;
          if (!corner) continue;
        }
        auto r = euler::kev(b, h);
        if (!r) return "kev refused on " + edge_of(h).str() + ": " + r.error().message;
        kept.erase(w);
        for (auto it = vertex_of.begin(); it != vertex_of.end(); ++it)
          if (it->second == w) {
            vertex_of.erase(it);
            break;
          }
        again = true;
        break;
      }
      if (again) break;
    }
  }
  std::vector<std::pair<VertexH, geo::Vec3>> guesses;
  for (auto [i, v] : vertex_of) {
    guesses.push_back({v, n.centroid[std::size_t(i)]});
    for (FaceH g : faces_around(b, v)) c.touched.faces.insert(g);
  }
  if (std::string why = place_vertices(b, guesses, c.tol, 2 * c.tol.length, c.touched); !why.empty()) {
    // A small face or a sliver beside the chain (a strip of small faces along an edge, some
    // of which a nearby repair made larger) has a plane fitted to a few points, nearly
    // parallel to the edge the chain stands for: where it meets that edge is
    // ill-conditioned (scan parts, roofed_block 1201003614: 0.49 down the edge at a
    // tolerance of 0.069). Its own pass removes it later; the vertices go where the other
    // faces meet, and the region solve tilts its plane through them.
    std::set<FaceH> minor;
    for (auto [v, guess] : guesses)
      for (FaceH g : faces_around(b, v))
        if (FaceInfo fi = measure_face(b, g, c.tol, c.tol.measure_chordal()); fi.small || fi.sliver) minor.insert(g);
    if (minor.empty() || !place_vertices(b, guesses, c.tol, 2 * c.tol.length, c.touched, minor).empty()) return why;
  }
  return drop_free_vertices(b, kept, c);
}

}  // namespace
}  // namespace kintsugi::detail

KINTSUGI_PASS(small_face_chain) = {kintsugi::ProblemType::small_face_chain, "small-face chains",
                                   "each small face becomes a vertex, joined in the chain's order by short edges",
                                   kintsugi::detail::repair_small_face_chain};
