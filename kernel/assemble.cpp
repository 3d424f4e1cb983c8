#include "kernel/assemble.h"

#include "kernel/threads.h"


namespace kintsugi {

class BodyReader {
 public:
  static std::optional<Body> run(BodyDescription&& d, AssembleError* error);
};

namespace {

// Edges from which the body's arrays are made on two threads: below, a thread costs more
// than it saves.
constexpr std::size_t kArraysOnTwoThreadsFrom = 20000;

bool fail(AssembleError* e, std::string element, std::string message) {
  if (e) *e = {std::move(element), std::move(message)};
  return false;
}

// Checks ids are unique and bounded; returns the slot count.
template <class T>
bool slots_for(const std::vector<T>& items, const char* kind, std::size_t* n, AssembleError* e) {
  std::uint64_t limit = 2 * std::uint64_t(items.size()) + 1024;
  std::uint64_t top = 0;
  for (const T& it : items) {
    if (it.id >= limit)
      return fail(e, std::string(kind) + " " + std::to_string(it.id),
                  "id is too large for " + std::to_string(items.size()) + " " + kind + "s (ids must be below " +
                      std::to_string(limit) + ")");
    top = std::max<std::uint64_t>(top, it.id + 1);
  }
  *n = std::size_t(top);
  std::vector<std::uint8_t> seen(*n, 0);
  for (const T& it : items) {
    if (seen[it.id]) return fail(e, std::string(kind) + " " + std::to_string(it.id), "id used twice");
    seen[it.id] = 1;
  }
  return true;
}

}  // namespace

// Takes the description's geometry (moved, not copied: a million edges' curves). The
// places in messages are spelled only for the element that is wrong.
std::optional<Body> BodyReader::run(BodyDescription&& d, AssembleError* error) {
  std::size_t nv, ne, nl, nf, ns;
  if (!slots_for(d.vertices, "vertex", &nv, error) || !slots_for(d.edges, "edge", &ne, error) ||
      !slots_for(d.loops, "loop", &nl, error) || !slots_for(d.faces, "face", &nf, error) ||
      !slots_for(d.shells, "shell", &ns, error))
    return std::nullopt;
  Body b;
  // The body's arrays, the half-edges and curves on a second thread where two may be used
  // and the body is large: filling fresh memory is most of the cost here (a page's first
  // touch costs more than writing it), and the arrays are independent.
  auto edge_arrays = [&] {
    b.halfedges_.assign(2 * ne, HalfedgeRec{});
    b.curves_.assign(ne, geo::Curve{});
  };
  {
    OtherThread edges(edge_arrays, ne >= kArraysOnTwoThreadsFrom && threads_from_environment() >= 2);
    b.vertices_.assign(nv, VertexRec{});
    b.v_alive_.assign(nv, 0);
    b.points_.assign(nv, geo::Vec3::Zero());
    b.e_alive_.assign(ne, 0);
    b.loops_.assign(nl, LoopRec{});
    b.l_alive_.assign(nl, 0);
    b.faces_.assign(nf, FaceRec{});
    b.f_alive_.assign(nf, 0);
    b.surfaces_.assign(nf, geo::Surface{});
    b.senses_.assign(nf, 1);
    b.shells_.assign(ns, ShellRec{});
    b.s_alive_.assign(ns, 0);
    edges.join();
  }

  for (const auto& v : d.vertices) {
    if (!v.point.allFinite()) return fail(error, "vertex " + std::to_string(v.id), "point is not finite"), std::nullopt;
    b.v_alive_[v.id] = 1;
    b.points_[v.id] = v.point;
  }
  for (const auto& s : d.shells) {
    b.s_alive_[s.id] = 1;
    b.shells_[s.id].genus = s.genus;
  }
  for (const auto& e : d.edges) b.e_alive_[e.id] = 1;
  for (const auto& l : d.loops) b.l_alive_[l.id] = 1;
  for (const auto& f : d.faces) b.f_alive_[f.id] = 1;

  auto live_v = [&](std::uint32_t i) { return i < nv && b.v_alive_[i]; };
  auto live_h = [&](std::uint32_t i) { return i < 2 * ne && b.e_alive_[i >> 1]; };
  auto live_l = [&](std::uint32_t i) { return i < nl && b.l_alive_[i]; };
  auto live_f = [&](std::uint32_t i) { return i < nf && b.f_alive_[i]; };
  auto live_s = [&](std::uint32_t i) { return i < ns && b.s_alive_[i]; };

  for (auto& e : d.edges) {
    for (int side = 0; side < 2; ++side) {
      const HalfedgeDesc& h = e.he[side];
      auto where = [&] { return "edge " + std::to_string(e.id) + " half-edge " + std::to_string(side); };
      if (!live_v(h.origin)) return fail(error, where(), "origin " + std::to_string(h.origin) + " is not a vertex"), std::nullopt;
      if (!live_h(h.next)) return fail(error, where(), "next " + std::to_string(h.next) + " is not a half-edge"), std::nullopt;
      if (!live_l(h.loop)) return fail(error, where(), "loop " + std::to_string(h.loop) + " is not a loop"), std::nullopt;
      HalfedgeRec& r = b.halfedges_[2 * e.id + side];
      r.origin = VertexH(h.origin);
      r.next = HalfedgeH(h.next);
      r.loop = LoopH(h.loop);
    }
    b.curves_[e.id] = std::move(e.curve);
  }
  // prev is derived from next; a half-edge named as next twice is an error.
  std::vector<std::uint8_t> has_prev(2 * ne, 0);
  for (const auto& e : d.edges)
    for (int side = 0; side < 2; ++side) {
      std::uint32_t h = 2 * e.id + side, n = b.halfedges_[h].next.idx();
      if (has_prev[n]) return fail(error, "edge " + std::to_string(e.id) + " half-edge " + std::to_string(side),
                                   "half-edge " + std::to_string(n) + " is already the next of another"), std::nullopt;
      has_prev[n] = 1;
      b.halfedges_[n].prev = HalfedgeH(h);
      if (!b.vertices_[b.halfedges_[h].origin.idx()].out.valid()) b.vertices_[b.halfedges_[h].origin.idx()].out = HalfedgeH(h);
    }
  for (const auto& l : d.loops) {
    auto where = [&] { return "loop " + std::to_string(l.id); };
    LoopRec& r = b.loops_[l.id];
    if (l.face) {
      if (!live_f(*l.face)) return fail(error, where(), "face " + std::to_string(*l.face) + " is not a face"), std::nullopt;
      r.face = FaceH(*l.face);
    }
    if (l.first.has_value() == l.lone.has_value())
      return fail(error, where(), "needs exactly one of a first half-edge and a lone vertex"), std::nullopt;
    if (l.first) {
      if (!live_h(*l.first)) return fail(error, where(), "first " + std::to_string(*l.first) + " is not a half-edge"), std::nullopt;
      r.first = HalfedgeH(*l.first);
    } else {
      if (!live_v(*l.lone)) return fail(error, where(), "lone vertex " + std::to_string(*l.lone) + " is not a vertex"), std::nullopt;
      r.lone = VertexH(*l.lone);
    }
  }
  for (auto& f : d.faces) {
    auto where = [&] { return "face " + std::to_string(f.id); };
    if (!live_s(f.shell)) return fail(error, where(), "shell " + std::to_string(f.shell) + " is not a shell"), std::nullopt;
    if (f.loops.empty()) return fail(error, where(), "has no loops"), std::nullopt;
    FaceRec& r = b.faces_[f.id];
    r.shell = ShellH(f.shell);
    r.outer = LoopH(f.loops[0]);
    for (std::size_t i = 0; i < f.loops.size(); ++i) {
      std::uint32_t l = f.loops[i];
      if (!live_l(l)) return fail(error, where(), "loop " + std::to_string(l) + " is not a loop"), std::nullopt;
      if (b.loops_[l].face != FaceH(f.id))
        return fail(error, where(), "loop " + std::to_string(l) + " does not name this face"), std::nullopt;
      if (b.loops_[l].next_in_face.valid() || (i > 0 && LoopH(l) == r.outer))
        return fail(error, where(), "loop " + std::to_string(l) + " is listed twice"), std::nullopt;
      b.loops_[l].next_in_face = i + 1 < f.loops.size() ? LoopH(f.loops[i + 1]) : LoopH{};
    }
    b.surfaces_[f.id] = std::move(f.surface);
    b.senses_[f.id] = f.same_sense ? 1 : 0;
    b.shells_[f.shell].faces++;
  }
  return b;
}

std::optional<Body> assemble_references(BodyDescription d, AssembleError* error) {
  return BodyReader::run(std::move(d), error);
}

BodyDescription describe(const Body& b) {
  BodyDescription d;
  for (VertexH v : b.vertices()) d.vertices.push_back({v.idx(), b.point(v)});
  for (EdgeH e : b.edges()) {
    EdgeDesc ed;
    ed.id = e.idx();
    for (unsigned s = 0; s < 2; ++s) {
      HalfedgeH h = halfedge_of(e, s);
      ed.he[s] = {b.origin(h).idx(), b.next(h).idx(), b.loop(h).idx()};
    }
    ed.curve = b.curve(e);
    d.edges.push_back(std::move(ed));
  }
  for (LoopH l : b.loops()) {
    LoopDesc ld;
    ld.id = l.idx();
    if (!b.is_border(l)) ld.face = b.face(l).idx();
    if (b.is_lone(l))
      ld.lone = b.lone_vertex(l).idx();
    else
      ld.first = b.first(l).idx();
    d.loops.push_back(ld);
  }
  for (FaceH f : b.faces()) {
    FaceDesc fd;
    fd.id = f.idx();
    fd.shell = b.shell(f).idx();
    for (LoopH l : b.loops_of(f)) fd.loops.push_back(l.idx());
    fd.surface = b.surface(f);
    fd.same_sense = b.same_sense(f);
    d.faces.push_back(std::move(fd));
  }
  for (ShellH s : b.shells()) d.shells.push_back({s.idx(), b.shell_genus(s)});
  return d;
}

}  // namespace kintsugi
