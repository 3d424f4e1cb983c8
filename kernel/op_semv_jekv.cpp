// semv / jekv — split an edge, make a vertex on it; join two edges, kill the vertex
// between them. Contracts: kernel/euler.h, spec/operators.md.
#include "kernel/euler_impl.h"

namespace kintsugi {

using I = EulerImpl;
using pre::err;

// ---- semv ----------------------------------------------------------------------------

std::optional<Error> euler::can_semv(const Body& b, HalfedgeH h, const geo::Vec3&) {
  return pre::alive(b, h, "half-edge");
}

SemvResult EulerImpl::raw_semv(Body& b, HalfedgeH h, const geo::Vec3& p, const Reuse& r, TouchedElements& t) {
  HalfedgeH tw = twin(h);
  VertexH w = he(b, tw).origin;
  VertexH m = new_vertex(b, p, r.vertex);
  EdgeH e = new_edge(b, r.edge);
  // The new edge's curve runs the same way as the old one's: its x half-edge has the
  // same direction as the old edge's x half-edge.
  int side = r.x_side >= 0 ? r.x_side : int(h.idx() & 1u);
  HalfedgeH nh = halfedge_of(e, unsigned(side)), nt = twin(nh);
  curve(b, e) = curve(b, edge_of(h));
  HalfedgeH n_h = he(b, h).next, p_t = he(b, tw).prev;
  he(b, nh).origin = m;
  he(b, nh).loop = he(b, h).loop;
  he(b, nt).origin = w;
  he(b, nt).loop = he(b, tw).loop;
  he(b, tw).origin = m;
  if (n_h == tw) {  // w dangled at the end of h
    link(b, h, nh);
    link(b, nh, nt);
    link(b, nt, tw);
  } else {
    link(b, h, nh);
    link(b, nh, n_h);
    link(b, p_t, nt);
    link(b, nt, tw);
  }
  set_out(b, m, nh);
  if (vx(b, w).out == tw) set_out(b, w, nt);
  t.loops.push_back(he(b, h).loop);
  if (he(b, tw).loop != he(b, h).loop) t.loops.push_back(he(b, tw).loop);
  t.vertices.push_back(he(b, h).origin);
  t.vertices.push_back(m);
  t.vertices.push_back(w);
  return {m, e, nh};
}

Result<SemvResult> euler::semv(Body& b, HalfedgeH h, const geo::Vec3& p) {
  if (auto e = can_semv(b, h, p)) return *e;
  TouchedElements t;
  I::Reuse r;
  r.x_side = -1;  // choose by the direction of h
  I::keep_around(b, h);
  SemvResult res = I::raw_semv(b, h, p, r, t);
  JournalEntry e{SemvRecord{h, res.vertex, res.edge, res.next}};
  if (auto bad = I::finish(b, e, t)) return *bad;
  return res;
}

void EulerImpl::undo(Body& b, const SemvRecord& r, const JournalEntry&) {
  TouchedElements t;
  raw_jekv(b, r.h, t);
}

// ---- jekv ----------------------------------------------------------------------------

std::optional<Error> euler::can_jekv(const Body& b, HalfedgeH h) {
  if (auto e = pre::alive(b, h, "half-edge")) return e;
  HalfedgeH nh = b.next(h);
  VertexH m = b.target(h);
  if (nh == twin(h)) return err(ErrorCode::degree, m.str() + " dangles at the end of " + edge_of(h).str());
  if (edge_of(nh) == edge_of(h))
    return err(ErrorCode::self_loop, "edge " + edge_of(h).str() + " meets itself at " + m.str());
  if (b.next(twin(nh)) != twin(h))
    return err(ErrorCode::degree,
               m.str() + " lies on more than the two edges " + edge_of(h).str() + ", " + edge_of(nh).str());
  return std::nullopt;
}

void EulerImpl::raw_jekv(Body& b, HalfedgeH h, TouchedElements& t) {
  HalfedgeH tw = twin(h), nh = he(b, h).next, nt = twin(nh);
  VertexH m = he(b, nh).origin, w = he(b, nt).origin;
  HalfedgeH n_nh = he(b, nh).next, p_nt = he(b, nt).prev;
  LoopH lh = he(b, h).loop, lt = he(b, tw).loop;
  if (n_nh == nt) {  // w dangles at the end of nh
    link(b, h, tw);
  } else {
    link(b, h, n_nh);
    link(b, p_nt, tw);
  }
  he(b, tw).origin = w;
  if (lp(b, lh).first == nh) set_first(b, lh, h);
  if (lp(b, lt).first == nt) set_first(b, lt, tw);
  if (vx(b, w).out == nt) set_out(b, w, tw);
  kill(b, m);
  kill(b, edge_of(nh));
  t.loops.push_back(lh);
  if (lt != lh) t.loops.push_back(lt);
  t.vertices.push_back(he(b, h).origin);
  t.vertices.push_back(w);
}

Result<Done> euler::jekv(Body& b, HalfedgeH h) {
  if (auto e = can_jekv(b, h)) return *e;
  HalfedgeH nh = b.next(h);
  VertexH m = b.target(h);
  JournalEntry e{JekvRecord{h, m, edge_of(nh), nh}};
  e.saved = I::save(b, &b.point(m), &b.curve(edge_of(nh)), nullptr, 1);
  TouchedElements t;
  I::keep_around(b, h);
  I::keep_around(b, b.next(h));
  I::raw_jekv(b, h, t);
  if (auto bad = I::finish(b, e, t)) return *bad;
  return Done{};
}

void EulerImpl::undo(Body& b, const JekvRecord& r, const JournalEntry& e) {
  TouchedElements t;
  Reuse reuse;
  reuse.vertex = r.killed.idx();
  reuse.edge = r.killed_edge.idx();
  reuse.x_side = int(r.killed_next.idx() & 1u);
  raw_semv(b, r.h, saved_point(b, e), reuse, t);
  curve(b, r.killed_edge) = saved_curve(b, e);
}

}  // namespace kintsugi
