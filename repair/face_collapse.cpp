#include "repair/face_collapse.h"

#include "kernel/euler.h"
#include "repair/beautify_detail.h"

#include <algorithm>
#include <map>
#include <set>

namespace kintsugi::detail {

namespace {

// The half-edge leaving v in loop l, when v occurs there exactly once.
HalfedgeH only_out_in(const Body& b, VertexH v, LoopH l, int* occurrences) {
  HalfedgeH found;
  *occurrences = 0;
  for (HalfedgeH h : b.loop_halfedges(l))
    if (b.origin(h) == v) {
      found = h;
      ++*occurrences;
    }
  return found;
}

// An edge of loop l joining u and w, or invalid.
EdgeH loop_edge_between(const Body& b, LoopH l, VertexH u, VertexH w) {
  for (HalfedgeH h : b.loop_halfedges(l))
    if ((b.origin(h) == u && b.target(h) == w) || (b.origin(h) == w && b.target(h) == u)) return edge_of(h);
  return EdgeH{};
}

}  // namespace

std::string collapsible(const Body& b, FaceH f) {
  if (!b.alive(f)) return "no longer present: " + f.str() + " was removed by an earlier repair";
  if (!b.rings_of(f).empty()) return f.str() + " has inner loops";
  LoopH l = b.outer_loop(f);
  if (b.is_lone(l)) return f.str() + " has no edges";
  for (HalfedgeH h : b.loop_halfedges(l)) {
    FaceH g = b.face(twin(h));
    if (!g.valid()) return f.str() + " borders a gap along " + edge_of(h).str();
    if (g == f) return f.str() + " meets itself along " + edge_of(h).str();
  }
  return "";
}

std::string drop_bare_vertices(Body& b, FaceH f) {
  // Each jekv shortens the loop by one; a loop that would drop below two vertices has
  // no vertex left that the faces around could meet in.
  bool again = true;
  while (again) {
    again = false;
    auto hs = b.loop_halfedges(b.outer_loop(f));
    if (hs.size() <= 2) break;
    for (HalfedgeH h : hs) {
      VertexH m = b.target(h);
      if (b.degree(m) != 2 || edge_of(h) == edge_of(b.next(h))) continue;
      auto r = euler::jekv(b, h);
      if (!r) return "jekv refused at " + m.str() + ": " + r.error().message;
      again = true;
      break;
    }
  }
  return "";
}

bool chords_cross(const std::vector<VertexH>& loop, const std::vector<std::pair<VertexH, VertexH>>& tree) {
  std::map<VertexH, int> pos;
  for (std::size_t i = 0; i < loop.size(); ++i) pos[loop[i]] = int(i);
  const int n = int(loop.size());
  std::vector<std::pair<int, int>> chords;
  for (auto [u, w] : tree) {
    if (!pos.count(u) || !pos.count(w)) continue;  // the junction: checked by the caller
    int a = pos[u], c = pos[w];
    if (a > c) std::swap(a, c);
    if (c - a == 1 || (a == 0 && c == n - 1)) continue;  // an edge of the loop
    chords.push_back({a, c});
  }
  for (std::size_t i = 0; i < chords.size(); ++i)
    for (std::size_t j = 0; j < i; ++j) {
      auto [a, c] = chords[i];
      auto [x, y] = chords[j];
      if (a == x || a == y || c == x || c == y) continue;
      bool x_in = a < x && x < c, y_in = a < y && y < c;
      if (x_in != y_in) return true;
    }
  return false;
}

std::string collapse_onto_tree(Body& b, FaceH f, const std::vector<std::pair<VertexH, VertexH>>& tree_in,
                               VertexH* junction, const geo::Vec3& junction_at) {
  const LoopH outer = b.outer_loop(f);
  std::vector<std::pair<VertexH, VertexH>> tree = tree_in;
  std::set<EdgeH> tree_edges;
  // Tree edges already on the loop.
  std::vector<std::pair<VertexH, VertexH>> chords;
  for (auto [u, w] : tree) {
    EdgeH e = (u.valid() && w.valid()) ? loop_edge_between(b, outer, u, w) : EdgeH{};
    if (e.valid() && !tree_edges.count(e))
      tree_edges.insert(e);
    else
      chords.push_back({u, w});
  }
  // The junction first (a strut from its first neighbour, then its other edges at once, so
  // that no vertex occurs twice in a loop a later chord goes into).
  std::stable_partition(chords.begin(), chords.end(),
                        [](const auto& p) { return !p.first.valid() || !p.second.valid(); });
  std::vector<FaceH> pieces{f};
  bool strut_made = false;
  for (auto [u, w] : chords) {
    if (!u.valid()) std::swap(u, w);
    if (!w.valid()) {  // an edge to the junction
      if (!junction) return "a tree edge names no vertex";
      if (!strut_made) {
        int occ = 0;
        HalfedgeH h = only_out_in(b, u, outer, &occ);
        if (occ != 1) return u.str() + " is not once on the loop of " + f.str();
        auto r = euler::mev(b, Corner::before(h), junction_at);
        if (!r) return "mev refused at " + u.str() + ": " + r.error().message;
        *junction = r->vertex;
        tree_edges.insert(r->edge);
        strut_made = true;
        continue;
      }
      w = *junction;
    }
    // The piece holding both ends, each once in its loop.
    HalfedgeH hu, hw;
    for (FaceH p : pieces) {
      int ou = 0, ow = 0;
      HalfedgeH a = only_out_in(b, u, b.outer_loop(p), &ou), c = only_out_in(b, w, b.outer_loop(p), &ow);
      if (ou >= 1 && ow >= 1) {
        if (ou != 1 || ow != 1) return "a chord from " + u.str() + " to " + w.str() + " has no unique corner";
        hu = a, hw = c;
        break;
      }
    }
    if (!hu.valid()) return "no piece of " + f.str() + " holds both " + u.str() + " and " + w.str();
    auto m = euler::mef(b, Corner::before(hu), Corner::before(hw));
    if (!m) return "mef refused from " + u.str() + " to " + w.str() + ": " + m.error().message;
    tree_edges.insert(m->edge);
    pieces.push_back(m->face);
  }
  if (junction && !strut_made) return "the junction has no edges";
  // Every piece borders exactly one edge outside the tree; kill it across that edge.
  std::set<FaceH> piece_set(pieces.begin(), pieces.end());
  for (FaceH p : pieces) {
    HalfedgeH across;
    int n = 0;
    for (HalfedgeH h : b.loop_halfedges(b.outer_loop(p)))
      if (!tree_edges.count(edge_of(h))) across = h, ++n;
    if (n != 1) return "a piece of " + f.str() + " borders " + std::to_string(n) + " edges outside the tree";
    FaceH beyond = b.face(twin(across));
    if (piece_set.count(beyond)) return "a piece of " + f.str() + " borders another piece";
    auto k = euler::kef(b, twin(across));
    if (!k) return "kef refused across " + edge_of(across).str() + ": " + k.error().message;
  }
  // Each tree edge now separates two faces, and they must differ.
  for (EdgeH e : tree_edges) {
    if (!b.alive(e)) return "a tree edge was removed";
    if (b.face(halfedge_of(e, 0)) == b.face(halfedge_of(e, 1)))
      return e.str() + " would have " + b.face(halfedge_of(e, 0)).str() + " on both sides";
  }
  return "";
}

std::string collapse_to_vertex(Body& b, FaceH f, const geo::Tolerances& tol, Touched& touched) {
  auto hs = b.loop_halfedges(b.outer_loop(f));
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
  for (FaceH g : faces_around(b, keep)) touched.faces.insert(g);
  return place_vertices(b, {{keep, centroid}}, tol, tol.max_vertex_move(), touched);
}

FaceH join_patch(Body& b, const std::vector<FaceH>& faces, std::string* why) {
  const FaceH u = faces.front();
  const std::set<FaceH> members(faces.begin(), faces.end());
  for (FaceH f : faces)
    if (!b.rings_of(f).empty()) {
      *why = f.str() + " has inner loops";
      return FaceH();
    }
  for (bool again = true; again;) {
    again = false;
    for (HalfedgeH h : b.loop_halfedges(b.outer_loop(u))) {
      const FaceH g = b.face(twin(h));
      if (g == u) {
        // A strut inside the joined face: the edges round its inner end were killed.
        HalfedgeH in = b.degree(b.target(h)) == 1 ? h : b.degree(b.origin(h)) == 1 ? twin(h) : HalfedgeH();
        if (!in.valid()) continue;
        auto r = euler::kev(b, in);  // the end on no other edge goes
        if (!r) {
          *why = "kev refused on " + edge_of(h).str() + ": " + r.error().message;
          return FaceH();
        }
        again = true;
        break;
      }
      if (!members.count(g)) continue;
      auto k = euler::kef(b, h);  // g is killed, its loop joins U's
      if (!k) {
        *why = "kef refused across " + edge_of(h).str() + ": " + k.error().message;
        return FaceH();
      }
      again = true;
      break;
    }
  }
  for (FaceH f : faces)
    if (f != u && b.alive(f)) {
      *why = "the small faces did not join into one";
      return FaceH();
    }
  for (HalfedgeH h : b.loop_halfedges(b.outer_loop(u)))
    if (b.face(twin(h)) == u) {
      *why = "the patch of small faces encloses " + edge_of(h).str() + ": not a disc";
      return FaceH();
    }
  if (!b.rings_of(u).empty()) {
    *why = "the patch of small faces encloses a hole: not a disc";
    return FaceH();
  }
  if (std::string w = drop_bare_vertices(b, u); !w.empty()) {
    *why = w;
    return FaceH();
  }
  return u;
}

}  // namespace kintsugi::detail
