// kemr / mekr — kill (make) an edge, make (kill) a ring: removing a bridge edge inside
// one loop splits off an inner loop of the same face, and an edge joins a ring back to
// another loop of its face. Contracts: kernel/euler.h, spec/operators.md.
#include "kernel/euler_impl.h"

namespace kintsugi {

using I = EulerImpl;
using pre::err;

// ---- kemr ----------------------------------------------------------------------------

std::optional<Error> euler::can_kemr(const Body& b, HalfedgeH x) {
  if (auto e = pre::alive(b, x, "half-edge")) return e;
  HalfedgeH y = twin(x);
  LoopH l = b.loop(x);
  if (b.loop(y) != l)
    return err(ErrorCode::wrong_loop, "the sides of " + edge_of(x).str() + " are in different loops");
  if (b.is_border(l)) return err(ErrorCode::border, "loop " + l.str() + " is a border cycle");
  if (b.next(x) == y && b.next(y) == x && b.origin(x) == b.origin(y))
    return err(ErrorCode::self_loop, "a self-loop alone in " + l.str() + " cannot make a ring");
  return std::nullopt;
}

KemrResult EulerImpl::raw_kemr(Body& b, HalfedgeH x, const Reuse& r, TouchedElements& t) {
  HalfedgeH y = twin(x);
  LoopH l = he(b, x).loop;
  FaceH f = lp(b, l).face;
  VertexH v = he(b, x).origin, w = he(b, y).origin;
  HalfedgeH px = he(b, x).prev, nx = he(b, x).next, py = he(b, y).prev, ny = he(b, y).next;
  LoopH ring = new_loop(b, f, r.loop);
  add_ring(b, f, ring);
  if (nx != y) {
    link(b, py, nx);
    relabel(b, nx, nx, ring);
    set_first(b, ring, nx);
  } else {
    lp(b, ring).lone = w;
  }
  if (ny != x) {
    link(b, px, ny);
    set_first(b, l, ny);
  } else {
    set_first(b, l, HalfedgeH{});
    lp(b, l).lone = v;
  }
  // Representatives: v and w keep any surviving half-edge leaving them.
  if (vx(b, v).out == x || vx(b, v).out == y) set_out(b, v, (ny != x) ? ny : HalfedgeH{});
  if (vx(b, w).out == y || vx(b, w).out == x) set_out(b, w, (nx != y) ? nx : HalfedgeH{});
  kill(b, edge_of(x));
  t.loops.push_back(l);
  t.loops.push_back(ring);
  t.vertices.push_back(v);
  if (w != v) t.vertices.push_back(w);
  t.faces.push_back(f);
  return {ring};
}

Result<KemrResult> euler::kemr(Body& b, HalfedgeH x) {
  if (auto e = can_kemr(b, x)) return *e;
  HalfedgeH y = twin(x);
  LoopH l = b.loop(x);
  HalfedgeH nx = b.next(x), ny = b.next(y);
  // The mekr that undoes this one joins `l` before next(y) (or at its lone vertex) to
  // the ring before next(x) (or at its lone vertex); the ring's handle is known after.
  KemrRecord rec{x, LoopH{}, ny != x ? ny : HalfedgeH{}, nx != y ? nx : HalfedgeH{}, l};
  JournalEntry e{rec};
  e.saved = I::save(b, nullptr, &b.curve(edge_of(x)), nullptr, 1);
  TouchedElements t;
  I::keep_around(b, x);
  KemrResult r = I::raw_kemr(b, x, {}, t);
  std::get<KemrRecord>(e.record).ring = r.ring;
  if (auto bad = I::finish(b, e, t)) return *bad;
  return r;
}

void EulerImpl::undo(Body& b, const KemrRecord& r, const JournalEntry& e) {
  TouchedElements t;
  Reuse reuse;
  reuse.edge = edge_of(r.x).idx();
  reuse.x_side = int(r.x.idx() & 1u);
  Corner c1 = r.before1.valid() ? Corner::before(r.before1) : Corner::in_lone(r.loop);
  Corner c2 = r.before2.valid() ? Corner::before(r.before2) : Corner::in_lone(r.ring);
  raw_mekr(b, c1, c2, reuse, t);
  curve(b, edge_of(r.x)) = saved_curve(b, e);
}

// ---- mekr ----------------------------------------------------------------------------

std::optional<Error> euler::can_mekr(const Body& b, Corner c1, Corner c2) {
  if (auto e = pre::corner(b, c1)) return e;
  if (auto e = pre::corner(b, c2)) return e;
  LoopH l1 = pre::corner_loop(b, c1), l2 = pre::corner_loop(b, c2);
  if (l1 == l2) return err(ErrorCode::wrong_loop, "both corners are in loop " + l1.str() + "; use mef");
  if (b.is_border(l1) || b.is_border(l2))
    return err(ErrorCode::border, "mekr joins loops of a face, not border cycles");
  if (b.face(l1) != b.face(l2))
    return err(ErrorCode::wrong_face, "loops " + l1.str() + " and " + l2.str() + " are in different faces");
  if (b.is_outer(l2)) return err(ErrorCode::outer_loop, "loop " + l2.str() + " is an outer loop; pass it first");
  return std::nullopt;
}

MekrResult EulerImpl::raw_mekr(Body& b, Corner c1, Corner c2, const Reuse& r, TouchedElements& t) {
  LoopH l1 = c1.lone.valid() ? c1.lone : he(b, c1.he).loop;
  LoopH l2 = c2.lone.valid() ? c2.lone : he(b, c2.he).loop;
  FaceH f = lp(b, l1).face;
  VertexH v1 = c1.lone.valid() ? lp(b, l1).lone : he(b, c1.he).origin;
  VertexH v2 = c2.lone.valid() ? lp(b, l2).lone : he(b, c2.he).origin;
  EdgeH e = new_edge(b, r.edge);
  HalfedgeH a = halfedge_of(e, r.x_side), bb = twin(a);
  he(b, a).origin = v1;
  he(b, bb).origin = v2;
  if (!c2.lone.valid()) relabel(b, c2.he, c2.he, l1);
  he(b, a).loop = he(b, bb).loop = l1;
  // The merged cycle: prev(c1) → a → [L2 from c2] → b → c1.
  HalfedgeH after_a = c2.lone.valid() ? bb : c2.he;
  HalfedgeH before_b = c2.lone.valid() ? a : he(b, c2.he).prev;
  HalfedgeH before_a = c1.lone.valid() ? bb : he(b, c1.he).prev;
  HalfedgeH after_b = c1.lone.valid() ? a : c1.he;
  link(b, before_a, a);
  link(b, a, after_a);
  link(b, before_b, bb);
  link(b, bb, after_b);
  if (c1.lone.valid()) lp(b, l1).lone = VertexH{};
  set_first(b, l1, a);
  if (!vx(b, v1).out.valid()) set_out(b, v1, a);
  if (!vx(b, v2).out.valid()) set_out(b, v2, bb);
  remove_ring(b, f, l2);
  kill(b, l2);
  t.loops.push_back(l1);
  t.vertices.push_back(v1);
  if (v2 != v1) t.vertices.push_back(v2);
  t.faces.push_back(f);
  return {e, a, bb};
}

Result<MekrResult> euler::mekr(Body& b, Corner c1, Corner c2) {
  if (auto e = can_mekr(b, c1, c2)) return *e;
  LoopH ring = pre::corner_loop(b, c2);
  TouchedElements t;
  I::keep_around(b, c1.he, c1.lone);
  I::keep_around(b, c2.he, c2.lone);
  MekrResult r = I::raw_mekr(b, c1, c2, {}, t);
  JournalEntry e{MekrRecord{r.edge, r.a, ring}};
  if (auto bad = I::finish(b, e, t)) return *bad;
  return r;
}

void EulerImpl::undo(Body& b, const MekrRecord& r, const JournalEntry&) {
  TouchedElements t;
  Reuse reuse;
  reuse.loop = r.ring.idx();
  raw_kemr(b, r.a, reuse, t);
}

}  // namespace kintsugi
