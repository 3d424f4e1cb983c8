#include "kernel/body.h"

#include "kernel/euler_impl.h"

#include <algorithm>
#include <set>

namespace kintsugi {

namespace {
template <class H>
std::vector<H> live(const std::vector<std::uint8_t>& alive) {
  std::vector<H> out;
  for (std::size_t i = 0; i < alive.size(); ++i)
    if (alive[i]) out.push_back(H(static_cast<std::uint32_t>(i)));
  return out;
}
}  // namespace

std::vector<VertexH> Body::vertices() const { return live<VertexH>(v_alive_); }
std::vector<EdgeH> Body::edges() const { return live<EdgeH>(e_alive_); }
std::vector<LoopH> Body::loops() const { return live<LoopH>(l_alive_); }
std::vector<FaceH> Body::faces() const { return live<FaceH>(f_alive_); }
std::vector<ShellH> Body::shells() const { return live<ShellH>(s_alive_); }

std::vector<HalfedgeH> Body::halfedges() const {
  std::vector<HalfedgeH> out;
  for (EdgeH e : edges()) {
    out.push_back(halfedge_of(e, 0));
    out.push_back(halfedge_of(e, 1));
  }
  return out;
}

std::vector<LoopH> Body::border_cycles() const {
  std::vector<LoopH> out;
  for (LoopH l : loops())
    if (is_border(l)) out.push_back(l);
  return out;
}

Counts Body::counts() const {
  Counts c;
  for (auto a : v_alive_) c.vertices += a;
  for (auto a : e_alive_) c.edges += a;
  for (auto a : f_alive_) c.faces += a;
  for (auto a : s_alive_) c.shells += a;
  for (std::size_t i = 0; i < loops_.size(); ++i) {
    if (!l_alive_[i]) continue;
    if (loops_[i].face.valid())
      c.loops++;
    else
      c.border_cycles++;
  }
  return c;
}

std::vector<LoopH> Body::loops_of(FaceH f) const {
  std::vector<LoopH> out;
  for (LoopH l = outer_loop(f); l.valid() && out.size() <= loops_.size(); l = next_in_face(l)) out.push_back(l);
  return out;
}

std::vector<LoopH> Body::rings_of(FaceH f) const {
  std::vector<LoopH> out = loops_of(f);
  if (!out.empty()) out.erase(out.begin());
  return out;
}

ShellH Body::shell(LoopH l) const {
  if (!is_border(l)) return shell(face(l));
  HalfedgeH h = first(l);
  if (!h.valid()) return ShellH{};
  FaceH f = face(twin(h));
  return f.valid() ? shell(f) : ShellH{};
}

std::vector<HalfedgeH> Body::loop_halfedges(LoopH l) const {
  std::vector<HalfedgeH> out;
  HalfedgeH start = first(l);
  if (!start.valid()) return out;
  HalfedgeH h = start;
  do {
    out.push_back(h);
    h = next(h);
  } while (h != start && h.valid() && h.idx() < halfedges_.size() && out.size() <= halfedges_.size());
  return out;
}

std::vector<VertexH> Body::loop_vertices(LoopH l) const {
  if (is_lone(l)) return {lone_vertex(l)};
  std::vector<VertexH> out;
  for (HalfedgeH h : loop_halfedges(l)) out.push_back(origin(h));
  return out;
}

std::vector<HalfedgeH> Body::outgoing(VertexH v) const {
  std::vector<HalfedgeH> out;
  HalfedgeH start = vertices_[v.idx()].out;
  if (!start.valid()) return out;
  HalfedgeH h = start;
  do {
    out.push_back(h);
    h = next(twin(h));
  } while (h != start && h.valid() && h.idx() < halfedges_.size() && out.size() <= halfedges_.size());
  return out;
}

// ---- geometry (journaled) --------------------------------------------------------------

void Body::set_point(VertexH v, const geo::Vec3& p) {
  if (journaling_) {
    JournalEntry e{SetPointRecord{v}};
    e.saved = EulerImpl::save(*this, &points_[v.idx()], nullptr, nullptr, 1);
    journal_.entries_.push_back(e);
  }
  points_[v.idx()] = p;
}

void Body::set_curve(EdgeH e, geo::Curve c) {
  if (journaling_) {
    JournalEntry j{SetCurveRecord{e}};
    j.saved = EulerImpl::save(*this, nullptr, &curves_[e.idx()], nullptr, 1);
    journal_.entries_.push_back(j);
  }
  curves_[e.idx()] = std::move(c);
}

void Body::set_surface(FaceH f, geo::Surface s, bool same_sense) {
  if (journaling_) {
    JournalEntry j{SetSurfaceRecord{f}};
    j.saved = EulerImpl::save(*this, nullptr, nullptr, &surfaces_[f.idx()], senses_[f.idx()]);
    journal_.entries_.push_back(j);
  }
  surfaces_[f.idx()] = std::move(s);
  senses_[f.idx()] = same_sense ? 1 : 0;
}

// ---- journal -------------------------------------------------------------------------------

bool Body::clear_journal() {
  if (open_transactions_ > 0) return false;
  journal_.clear();
  return true;
}

bool Body::set_journaling(bool on) {
  if (open_transactions_ > 0) return false;
  journaling_ = on;
  return true;
}

// ---- compaction ------------------------------------------------------------------------------

Body::Renumbering Body::compact() {
  Renumbering map;
  if (open_transactions_ > 0) return map;
  auto make_map = [](const std::vector<std::uint8_t>& alive) {
    std::vector<std::uint32_t> m(alive.size(), kNone);
    std::uint32_t n = 0;
    for (std::size_t i = 0; i < alive.size(); ++i)
      if (alive[i]) m[i] = n++;
    return m;
  };
  map.vertex = make_map(v_alive_);
  map.edge = make_map(e_alive_);
  map.loop = make_map(l_alive_);
  map.face = make_map(f_alive_);
  map.shell = make_map(s_alive_);
  auto mv = [&](VertexH v) { return v.valid() ? VertexH(map.vertex[v.idx()]) : v; };
  auto mh = [&](HalfedgeH h) {
    return h.valid() ? HalfedgeH(2 * map.edge[h.idx() >> 1] + (h.idx() & 1u)) : h;
  };
  auto ml = [&](LoopH l) { return l.valid() ? LoopH(map.loop[l.idx()]) : l; };
  auto mf = [&](FaceH f) { return f.valid() ? FaceH(map.face[f.idx()]) : f; };
  auto ms = [&](ShellH s) { return s.valid() ? ShellH(map.shell[s.idx()]) : s; };

  Body nb;
  for (std::size_t i = 0; i < vertices_.size(); ++i) {
    if (!v_alive_[i]) continue;
    nb.vertices_.push_back({mh(vertices_[i].out)});
    nb.points_.push_back(points_[i]);
    nb.v_alive_.push_back(1);
  }
  for (std::size_t i = 0; i < e_alive_.size(); ++i) {
    if (!e_alive_[i]) continue;
    for (int s = 0; s < 2; ++s) {
      const HalfedgeRec& r = halfedges_[2 * i + s];
      nb.halfedges_.push_back({mv(r.origin), mh(r.next), mh(r.prev), ml(r.loop)});
    }
    nb.curves_.push_back(curves_[i]);
    nb.e_alive_.push_back(1);
  }
  for (std::size_t i = 0; i < loops_.size(); ++i) {
    if (!l_alive_[i]) continue;
    const LoopRec& r = loops_[i];
    nb.loops_.push_back({mf(r.face), mh(r.first), mv(r.lone), ml(r.next_in_face)});
    nb.l_alive_.push_back(1);
  }
  for (std::size_t i = 0; i < faces_.size(); ++i) {
    if (!f_alive_[i]) continue;
    nb.faces_.push_back({ms(faces_[i].shell), ml(faces_[i].outer)});
    nb.surfaces_.push_back(surfaces_[i]);
    nb.senses_.push_back(senses_[i]);
    nb.f_alive_.push_back(1);
  }
  for (std::size_t i = 0; i < shells_.size(); ++i) {
    if (!s_alive_[i]) continue;
    nb.shells_.push_back(shells_[i]);
    nb.s_alive_.push_back(1);
  }
  nb.journaling_ = journaling_;
  *this = std::move(nb);
  return map;
}

// ---- equality -----------------------------------------------------------------------------------

bool Body::equals(const Body& o, std::string* why) const {
  auto fail = [&](const std::string& m) {
    if (why) *why = m;
    return false;
  };
  if (counts() != o.counts()) return fail("different counts");
  if (vertices() != o.vertices()) return fail("different live vertices");
  if (edges() != o.edges()) return fail("different live edges");
  if (loops() != o.loops()) return fail("different live loops");
  if (faces() != o.faces()) return fail("different live faces");
  if (shells() != o.shells()) return fail("different live shells");
  for (VertexH v : vertices()) {
    if (points_[v.idx()] != o.points_[v.idx()]) return fail("point of " + v.str());
    auto a = outgoing(v), b = o.outgoing(v);
    if (std::set<HalfedgeH>(a.begin(), a.end()) != std::set<HalfedgeH>(b.begin(), b.end()))
      return fail("rotation of " + v.str());
  }
  for (HalfedgeH h : halfedges()) {
    const HalfedgeRec &a = halfedges_[h.idx()], &b = o.halfedges_[h.idx()];
    if (a.origin != b.origin || a.next != b.next || a.prev != b.prev || a.loop != b.loop)
      return fail("incidences of " + h.str());
  }
  for (EdgeH e : edges())
    if (curves_[e.idx()] != o.curves_[e.idx()]) return fail("curve of " + e.str());
  for (LoopH l : loops()) {
    const LoopRec &a = loops_[l.idx()], &b = o.loops_[l.idx()];
    if (a.face != b.face || a.lone != b.lone || a.first.valid() != b.first.valid())
      return fail("loop " + l.str());
    if (a.first.valid() && halfedges_[b.first.idx()].loop != l) return fail("first half-edge of " + l.str());
  }
  for (FaceH f : faces()) {
    if (faces_[f.idx()].shell != o.faces_[f.idx()].shell) return fail("shell of " + f.str());
    if (outer_loop(f) != o.outer_loop(f)) return fail("outer loop of " + f.str());
    auto a = rings_of(f), b = o.rings_of(f);
    if (std::set<LoopH>(a.begin(), a.end()) != std::set<LoopH>(b.begin(), b.end())) return fail("rings of " + f.str());
    if (surfaces_[f.idx()] != o.surfaces_[f.idx()] || senses_[f.idx()] != o.senses_[f.idx()])
      return fail("surface of " + f.str());
  }
  for (ShellH s : shells())
    if (shells_[s.idx()].faces != o.shells_[s.idx()].faces || shells_[s.idx()].genus != o.shells_[s.idx()].genus)
      return fail("shell " + s.str());
  return true;
}

}  // namespace kintsugi
