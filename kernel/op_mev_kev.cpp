// mev / mev_split / kev — make (kill) an edge and a vertex: a strut or a lone vertex's
// first edge, a vertex split in two, and the collapse of an edge onto one end.
// Contracts: kernel/euler.h, spec/operators.md.
#include "kernel/euler_impl.h"

namespace kintsugi {

using I = EulerImpl;
using pre::err;

namespace {
// Does h2 lie on the rotation of origin(h1), from h1? Bounded by the slot count.
bool in_rotation(const Body& b, HalfedgeH h1, HalfedgeH h2) {
  HalfedgeH o = h1;
  for (std::size_t i = 0; i <= b.halfedge_slots(); ++i) {
    if (o == h2) return true;
    o = b.next(twin(o));
    if (o == h1) return false;
  }
  return false;
}
}  // namespace

// ---- mev, mev_split ------------------------------------------------------------------

std::optional<Error> euler::can_mev(const Body& b, Corner c, const geo::Vec3&) {
  if (auto e = pre::corner(b, c)) return e;
  if (c.lone.valid()) {
    if (b.is_border(c.lone)) return err(ErrorCode::border, "loop " + c.lone.str() + " is a border cycle");
    return std::nullopt;
  }
  if (b.is_border(c.he))
    return err(ErrorCode::border, "a strut before " + c.he.str() + " would lie in a border cycle");
  return std::nullopt;
}

std::optional<Error> euler::can_mev_split(const Body& b, HalfedgeH h1, HalfedgeH h2, const geo::Vec3& p) {
  if (auto e = pre::alive(b, h1, "half-edge")) return e;
  if (auto e = pre::alive(b, h2, "half-edge")) return e;
  if (h1 == h2) return can_mev(b, Corner::before(h1), p);
  if (b.origin(h1) != b.origin(h2))
    return err(ErrorCode::wrong_vertex, h1.str() + " and " + h2.str() + " leave different vertices");
  if (!in_rotation(b, h1, h2))
    return err(ErrorCode::wrong_vertex, h2.str() + " is not in the rotation of " + b.origin(h1).str());
  if (b.is_border(h1) && b.is_border(h2))
    return err(ErrorCode::border, "both sides of the new edge would be border cycles");
  return std::nullopt;
}

MevResult EulerImpl::raw_mev(Body& b, MevKind k, HalfedgeH h1, HalfedgeH h2, LoopH lone,
                             const geo::Vec3& p, const Reuse& r, TouchedElements& t) {
  VertexH w = new_vertex(b, p, r.vertex);
  EdgeH e = new_edge(b, r.edge);
  HalfedgeH x = halfedge_of(e, r.x_side), y = twin(x);
  VertexH v;
  if (k == MevKind::lone) {
    v = lp(b, lone).lone;
    he(b, x) = {v, y, y, lone};
    he(b, y) = {w, x, x, lone};
    set_first(b, lone, x);
    lp(b, lone).lone = VertexH{};
    set_out(b, v, x);
    t.loops.push_back(lone);
  } else if (k == MevKind::strut) {
    v = he(b, h1).origin;
    LoopH l = he(b, h1).loop;
    HalfedgeH p1 = he(b, h1).prev;
    he(b, x).origin = v;
    he(b, y).origin = w;
    he(b, x).loop = he(b, y).loop = l;
    link(b, p1, x);
    link(b, x, y);
    link(b, y, h1);
    t.loops.push_back(l);
  } else {
    v = he(b, h1).origin;
    HalfedgeH p1 = he(b, h1).prev, p2 = he(b, h2).prev;
    // Move the arc h1 .. h2 (exclusive) of v's rotation to w.
    HalfedgeH o = h1;
    std::size_t guard = b.halfedge_slots() + 1;
    while (o != h2 && --guard > 0) {
      he(b, o).origin = w;
      o = he(b, twin(o)).next;
    }
    he(b, x).origin = v;
    he(b, y).origin = w;
    he(b, x).loop = he(b, h1).loop;
    he(b, y).loop = he(b, h2).loop;
    link(b, p1, x);
    link(b, x, h1);
    link(b, p2, y);
    link(b, y, h2);
    set_out(b, v, x);
    t.loops.push_back(he(b, h1).loop);
    t.loops.push_back(he(b, h2).loop);
  }
  set_out(b, w, y);
  t.vertices.push_back(v);
  t.vertices.push_back(w);
  return {w, e, x, y};
}

namespace {
Result<MevResult> apply_mev(Body& b, MevKind k, HalfedgeH h1, HalfedgeH h2, LoopH lone, const geo::Vec3& p) {
  TouchedElements t;
  I::keep_around(b, h1, lone);
  I::keep_around(b, h2);
  MevResult r = I::raw_mev(b, k, h1, h2, lone, p, {}, t);
  JournalEntry e{MevRecord{r.vertex, r.edge, r.x}};
  if (auto bad = I::finish(b, e, t)) return *bad;
  return r;
}
}  // namespace

Result<MevResult> euler::mev(Body& b, Corner c, const geo::Vec3& p) {
  if (auto e = can_mev(b, c, p)) return *e;
  if (c.lone.valid()) return apply_mev(b, MevKind::lone, {}, {}, c.lone, p);
  return apply_mev(b, MevKind::strut, c.he, c.he, {}, p);
}

Result<MevResult> euler::mev_split(Body& b, HalfedgeH h1, HalfedgeH h2, const geo::Vec3& p) {
  if (auto e = can_mev_split(b, h1, h2, p)) return *e;
  if (h1 == h2) return apply_mev(b, MevKind::strut, h1, h1, {}, p);
  return apply_mev(b, MevKind::split, h1, h2, {}, p);
}

void EulerImpl::undo(Body& b, const MevRecord& r, const JournalEntry&) {
  TouchedElements t;
  raw_kev(b, r.x, t);
}

// ---- kev -----------------------------------------------------------------------------

std::optional<Error> euler::can_kev(const Body& b, HalfedgeH x) {
  if (auto e = pre::alive(b, x, "half-edge")) return e;
  HalfedgeH y = twin(x);
  VertexH v = b.origin(x), w = b.origin(y);
  if (v == w) return err(ErrorCode::self_loop, "edge " + edge_of(x).str() + " is a self-loop at " + v.str());
  bool lone = b.next(x) == y && b.next(y) == x;
  if (!lone && b.next(y) == x)
    return err(ErrorCode::degree, v.str() + " dangles at the end of " + edge_of(x).str() + "; use kev(" +
                                      y.str() + ")");
  return std::nullopt;
}

void EulerImpl::raw_kev(Body& b, HalfedgeH x, TouchedElements& t) {
  HalfedgeH y = twin(x);
  VertexH v = he(b, x).origin, w = he(b, y).origin;
  LoopH lx = he(b, x).loop, ly = he(b, y).loop;
  HalfedgeH px = he(b, x).prev, nx = he(b, x).next, py = he(b, y).prev, ny = he(b, y).next;
  if (nx == y && ny == x) {  // the loop is just this edge: it becomes v alone
    set_first(b, lx, HalfedgeH{});
    lp(b, lx).lone = v;
    set_out(b, v, HalfedgeH{});
  } else {
    // Everything leaving w except y now leaves v.
    for (HalfedgeH o = nx; o != y; o = he(b, twin(o)).next) he(b, o).origin = v;
    if (nx == y) {  // strut: w dangles
      link(b, px, ny);
    } else {
      link(b, px, nx);
      link(b, py, ny);
    }
    if (lp(b, lx).first == x) set_first(b, lx, (nx == y) ? ny : nx);
    if (lp(b, ly).first == y) set_first(b, ly, ny);
    if (vx(b, v).out == x) set_out(b, v, ny);
  }
  kill(b, w);
  kill(b, edge_of(x));
  t.loops.push_back(lx);
  if (ly != lx) t.loops.push_back(ly);
  t.vertices.push_back(v);
}

Result<Done> euler::kev(Body& b, HalfedgeH x) {
  if (auto e = can_kev(b, x)) return *e;
  HalfedgeH y = twin(x);
  VertexH v = b.origin(x), w = b.origin(y);
  HalfedgeH nx = b.next(x), ny = b.next(y);
  // The mev that undoes this one: into the loop that collapses to v, a strut before
  // next(y) when w dangles, else a split of v between next(x) and next(y).
  KevRecord rec{MevKind::split, v, w, x, nx, ny, LoopH{}};
  if (nx == y && ny == x) {
    rec.kind = MevKind::lone;
    rec.before1 = rec.before2 = HalfedgeH{};
    rec.lone = b.loop(x);
  } else if (nx == y) {
    rec.kind = MevKind::strut;
    rec.before1 = rec.before2 = ny;
  }
  JournalEntry e{rec};
  e.saved = I::save(b, &b.point(w), &b.curve(edge_of(x)), nullptr, 1);
  TouchedElements t;
  I::keep_around(b, x);
  I::raw_kev(b, x, t);
  if (auto bad = I::finish(b, e, t)) return *bad;
  return Done{};
}

void EulerImpl::undo(Body& b, const KevRecord& r, const JournalEntry& e) {
  TouchedElements t;
  Reuse reuse;
  reuse.vertex = r.killed.idx();
  reuse.edge = edge_of(r.x).idx();
  reuse.x_side = int(r.x.idx() & 1u);
  raw_mev(b, r.kind, r.before1, r.before2, r.lone, saved_point(b, e), reuse, t);
  curve(b, edge_of(r.x)) = saved_curve(b, e);
}

}  // namespace kintsugi
