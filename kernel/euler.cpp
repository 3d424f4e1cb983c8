// Forward Euler operators: preconditions, raw application, journaling, local check.
// Contracts are in kernel/euler.h and spec/operators.md; the raw operators (no checks,
// optional slot reuse) are shared with the rollback code in kernel/undo.cpp.
#include "kernel/euler.h"

#include "invariants/violation.h"
#include "kernel/euler_impl.h"

#include <algorithm>

namespace kintsugi {

const char* error_code_name(ErrorCode c) {
  switch (c) {
    case ErrorCode::dead_handle: return "dead_handle";
    case ErrorCode::wrong_vertex: return "wrong_vertex";
    case ErrorCode::wrong_loop: return "wrong_loop";
    case ErrorCode::wrong_face: return "wrong_face";
    case ErrorCode::not_lone: return "not_lone";
    case ErrorCode::is_lone: return "is_lone";
    case ErrorCode::not_strut: return "not_strut";
    case ErrorCode::self_loop: return "self_loop";
    case ErrorCode::degree: return "degree";
    case ErrorCode::border: return "border";
    case ErrorCode::outer_loop: return "outer_loop";
    case ErrorCode::has_rings: return "has_rings";
    case ErrorCode::last_face: return "last_face";
    case ErrorCode::different_shell: return "different_shell";
    case ErrorCode::genus: return "genus";
    case ErrorCode::disconnects: return "disconnects";
    case ErrorCode::transaction_open: return "transaction_open";
    case ErrorCode::postcondition: return "postcondition";
  }
  return "?";
}

// ---- storage -----------------------------------------------------------------------

namespace {
template <class Vec, class Rec>
std::uint32_t take_slot(Vec& recs, std::vector<std::uint8_t>& alive, std::uint32_t reuse, const Rec& init) {
  std::uint32_t i;
  if (reuse != kNone) {
    i = reuse;  // rollback revives exactly this (dead) slot
  } else {
    i = static_cast<std::uint32_t>(recs.size());
    recs.emplace_back();
    alive.push_back(0);
  }
  recs[i] = init;
  alive[i] = 1;
  return i;
}
}  // namespace

VertexH EulerImpl::new_vertex(Body& b, const geo::Vec3& p, std::uint32_t reuse) {
  std::uint32_t i = take_slot(b.vertices_, b.v_alive_, reuse, VertexRec{});
  if (i >= b.points_.size()) b.points_.resize(i + 1);
  b.points_[i] = p;
  return VertexH(i);
}

EdgeH EulerImpl::new_edge(Body& b, std::uint32_t reuse) {
  std::uint32_t i;
  if (reuse != kNone) {
    i = reuse;
  } else {
    i = static_cast<std::uint32_t>(b.e_alive_.size());
    b.e_alive_.push_back(0);
    b.halfedges_.resize(2 * std::size_t(i) + 2);
    b.curves_.emplace_back();
  }
  b.e_alive_[i] = 1;
  b.halfedges_[2 * i] = HalfedgeRec{};
  b.halfedges_[2 * i + 1] = HalfedgeRec{};
  b.curves_[i] = geo::Curve{};
  return EdgeH(i);
}

LoopH EulerImpl::new_loop(Body& b, FaceH f, std::uint32_t reuse) {
  LoopRec r;
  r.face = f;
  return LoopH(take_slot(b.loops_, b.l_alive_, reuse, r));
}

FaceH EulerImpl::new_face(Body& b, ShellH s, std::uint32_t reuse) {
  FaceRec r;
  r.shell = s;
  std::uint32_t i = take_slot(b.faces_, b.f_alive_, reuse, r);
  if (i >= b.surfaces_.size()) {
    b.surfaces_.resize(i + 1);
    b.senses_.resize(i + 1, 1);
  }
  b.surfaces_[i] = geo::Surface{};
  b.senses_[i] = 1;
  sh(b, s).faces++;
  return FaceH(i);
}

ShellH EulerImpl::new_shell(Body& b, std::uint32_t reuse) {
  return ShellH(take_slot(b.shells_, b.s_alive_, reuse, ShellRec{}));
}

void EulerImpl::kill(Body& b, VertexH v) { b.v_alive_[v.idx()] = 0; }
void EulerImpl::kill(Body& b, EdgeH e) { b.e_alive_[e.idx()] = 0; }
void EulerImpl::kill(Body& b, LoopH l) { b.l_alive_[l.idx()] = 0; }
void EulerImpl::kill(Body& b, FaceH f) {
  sh(b, fc(b, f).shell).faces--;
  b.f_alive_[f.idx()] = 0;
}
void EulerImpl::kill(Body& b, ShellH s) { b.s_alive_[s.idx()] = 0; }

void EulerImpl::relabel(Body& b, HalfedgeH from, HalfedgeH stop, LoopH l) {
  HalfedgeH h = from;
  std::size_t guard = b.halfedges_.size() + 1;
  do {
    he(b, h).loop = l;
    h = he(b, h).next;
  } while (h != stop && --guard > 0);
}

void EulerImpl::add_ring(Body& b, FaceH f, LoopH l) {
  LoopH outer = fc(b, f).outer;
  lp(b, l).face = f;
  lp(b, l).next_in_face = lp(b, outer).next_in_face;
  lp(b, outer).next_in_face = l;
}

void EulerImpl::remove_ring(Body& b, FaceH f, LoopH l) {
  LoopH cur = fc(b, f).outer;
  while (cur.valid() && lp(b, cur).next_in_face != l) cur = lp(b, cur).next_in_face;
  if (cur.valid()) lp(b, cur).next_in_face = lp(b, l).next_in_face;
  lp(b, l).next_in_face = LoopH{};
}

// ---- raw operators ------------------------------------------------------------------

MvfsResult EulerImpl::raw_mvfs(Body& b, const geo::Vec3& p, const Reuse& r, Touched& t) {
  ShellH s = new_shell(b, r.shell);
  FaceH f = new_face(b, s, r.face);
  LoopH l = new_loop(b, f, r.loop);
  VertexH v = new_vertex(b, p, r.vertex);
  fc(b, f).outer = l;
  lp(b, l).lone = v;
  t.loops.push_back(l);
  t.vertices.push_back(v);
  t.faces.push_back(f);
  return {s, f, l, v};
}

void EulerImpl::raw_kvfs(Body& b, FaceH f, Touched&) {
  LoopH l = fc(b, f).outer;
  VertexH v = lp(b, l).lone;
  ShellH s = fc(b, f).shell;
  kill(b, v);
  kill(b, l);
  kill(b, f);
  kill(b, s);
}

MevResult EulerImpl::raw_mev(Body& b, MevKind k, HalfedgeH h1, HalfedgeH h2, LoopH lone,
                             const geo::Vec3& p, const Reuse& r, Touched& t) {
  VertexH w = new_vertex(b, p, r.vertex);
  EdgeH e = new_edge(b, r.edge);
  HalfedgeH x = halfedge_of(e, r.x_side), y = twin(x);
  VertexH v;
  if (k == MevKind::lone) {
    v = lp(b, lone).lone;
    he(b, x) = {v, y, y, lone};
    he(b, y) = {w, x, x, lone};
    lp(b, lone).first = x;
    lp(b, lone).lone = VertexH{};
    vx(b, v).out = x;
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
    std::size_t guard = b.halfedges_.size() + 1;
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
    vx(b, v).out = x;
    t.loops.push_back(he(b, h1).loop);
    t.loops.push_back(he(b, h2).loop);
  }
  vx(b, w).out = y;
  t.vertices.push_back(v);
  t.vertices.push_back(w);
  return {w, e, x, y};
}

void EulerImpl::raw_kev(Body& b, HalfedgeH x, Touched& t) {
  HalfedgeH y = twin(x);
  VertexH v = he(b, x).origin, w = he(b, y).origin;
  LoopH lx = he(b, x).loop, ly = he(b, y).loop;
  HalfedgeH px = he(b, x).prev, nx = he(b, x).next, py = he(b, y).prev, ny = he(b, y).next;
  if (nx == y && ny == x) {  // the loop is just this edge: it becomes v alone
    lp(b, lx).first = HalfedgeH{};
    lp(b, lx).lone = v;
    vx(b, v).out = HalfedgeH{};
  } else {
    // Everything leaving w except y now leaves v.
    for (HalfedgeH o = nx; o != y; o = he(b, twin(o)).next) he(b, o).origin = v;
    if (nx == y) {  // strut: w dangles
      link(b, px, ny);
    } else {
      link(b, px, nx);
      link(b, py, ny);
    }
    if (lp(b, lx).first == x) lp(b, lx).first = (nx == y) ? ny : nx;
    if (lp(b, ly).first == y) lp(b, ly).first = ny;
    if (vx(b, v).out == x) vx(b, v).out = ny;
  }
  kill(b, w);
  kill(b, edge_of(x));
  t.loops.push_back(lx);
  if (ly != lx) t.loops.push_back(ly);
  t.vertices.push_back(v);
}

MefResult EulerImpl::raw_mef(Body& b, Corner c1, Corner c2, const Reuse& r, Touched& t) {
  LoopH l = c1.lone.valid() ? c1.lone : he(b, c1.he).loop;
  ShellH s = b.shell(l);
  EdgeH e = new_edge(b, r.edge);
  HalfedgeH a = halfedge_of(e, r.x_side), bb = twin(a);
  FaceH nf = new_face(b, s, r.face);
  LoopH nl = new_loop(b, nf, r.loop);
  fc(b, nf).outer = nl;
  if (c1.lone.valid()) {
    VertexH v = lp(b, l).lone;
    he(b, a) = {v, a, a, l};
    he(b, bb) = {v, bb, bb, nl};
    lp(b, l).first = a;
    lp(b, l).lone = VertexH{};
    vx(b, v).out = a;
    t.vertices.push_back(v);
  } else if (c1.he == c2.he) {  // empty range: the new face is bounded by b alone
    HalfedgeH h1 = c1.he;
    VertexH v = he(b, h1).origin;
    he(b, a).origin = v;
    he(b, a).loop = l;
    link(b, he(b, h1).prev, a);
    link(b, a, h1);
    he(b, bb) = {v, bb, bb, nl};
    t.vertices.push_back(v);
  } else {
    HalfedgeH h1 = c1.he, h2 = c2.he;
    HalfedgeH p1 = he(b, h1).prev, p2 = he(b, h2).prev;
    he(b, a).origin = he(b, h1).origin;
    he(b, bb).origin = he(b, h2).origin;
    he(b, a).loop = l;
    link(b, p1, a);
    link(b, a, h2);
    link(b, p2, bb);
    link(b, bb, h1);
    relabel(b, bb, bb, nl);
    t.vertices.push_back(he(b, a).origin);
    t.vertices.push_back(he(b, bb).origin);
  }
  lp(b, l).first = a;
  lp(b, nl).first = bb;
  t.loops.push_back(l);
  t.loops.push_back(nl);
  t.faces.push_back(nf);
  return {e, a, bb, nf, nl};
}

void EulerImpl::raw_kef(Body& b, HalfedgeH h, Touched& t) {
  HalfedgeH tw = twin(h);
  LoopH lh = he(b, h).loop, lt = he(b, tw).loop;
  FaceH fh = lp(b, lh).face, ft = lp(b, lt).face;
  VertexH v = he(b, h).origin, w = he(b, tw).origin;
  HalfedgeH ph = he(b, h).prev, nh = he(b, h).next, pt = he(b, tw).prev, nt = he(b, tw).next;
  bool h_alone = nh == h, t_alone = nt == tw;
  if (h_alone && t_alone) {  // a self-loop between two one-edge loops: v alone remains
    lp(b, lh).first = HalfedgeH{};
    lp(b, lh).lone = v;
    vx(b, v).out = HalfedgeH{};
  } else if (t_alone) {  // the self-loop tw bounded its face alone
    link(b, ph, nh);
    lp(b, lh).first = nh;
    if (vx(b, v).out == h || vx(b, v).out == tw) vx(b, v).out = nh;
  } else {
    relabel(b, nt, tw, lh);
    link(b, ph, nt);
    link(b, pt, nh);
    lp(b, lh).first = nh;
    if (vx(b, v).out == h) vx(b, v).out = nt;
    if (vx(b, w).out == tw) vx(b, w).out = nh;
  }
  if (ft.valid()) {
    if (fh.valid()) {
      for (LoopH r = lp(b, lt).next_in_face; r.valid();) {
        LoopH nxt = lp(b, r).next_in_face;
        add_ring(b, fh, r);
        r = nxt;
      }
    }
    kill(b, ft);
  }
  kill(b, lt);
  kill(b, edge_of(h));
  t.loops.push_back(lh);
  t.vertices.push_back(v);
  if (w != v) t.vertices.push_back(w);
  if (fh.valid()) t.faces.push_back(fh);
}

KemrResult EulerImpl::raw_kemr(Body& b, HalfedgeH x, const Reuse& r, Touched& t) {
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
    lp(b, ring).first = nx;
  } else {
    lp(b, ring).lone = w;
  }
  if (ny != x) {
    link(b, px, ny);
    lp(b, l).first = ny;
  } else {
    lp(b, l).first = HalfedgeH{};
    lp(b, l).lone = v;
  }
  // Representatives: v and w keep any surviving half-edge leaving them.
  if (vx(b, v).out == x || vx(b, v).out == y) vx(b, v).out = (ny != x) ? ny : HalfedgeH{};
  if (vx(b, w).out == y || vx(b, w).out == x) vx(b, w).out = (nx != y) ? nx : HalfedgeH{};
  kill(b, edge_of(x));
  t.loops.push_back(l);
  t.loops.push_back(ring);
  t.vertices.push_back(v);
  if (w != v) t.vertices.push_back(w);
  t.faces.push_back(f);
  return {ring};
}

MekrResult EulerImpl::raw_mekr(Body& b, Corner c1, Corner c2, const Reuse& r, Touched& t) {
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
  lp(b, l1).first = a;
  if (!vx(b, v1).out.valid()) vx(b, v1).out = a;
  if (!vx(b, v2).out.valid()) vx(b, v2).out = bb;
  remove_ring(b, f, l2);
  kill(b, l2);
  t.loops.push_back(l1);
  t.vertices.push_back(v1);
  if (v2 != v1) t.vertices.push_back(v2);
  t.faces.push_back(f);
  return {e, a, bb};
}

void EulerImpl::raw_kfmrh(Body& b, FaceH keep, FaceH kf, Touched& t) {
  LoopH l = fc(b, kf).outer;
  ShellH s = fc(b, kf).shell;
  add_ring(b, keep, l);
  kill(b, kf);
  sh(b, s).genus++;
  t.loops.push_back(l);
  t.faces.push_back(keep);
}

MfkrhResult EulerImpl::raw_mfkrh(Body& b, LoopH ring, const Reuse& r, Touched& t) {
  FaceH f = lp(b, ring).face;
  ShellH s = fc(b, f).shell;
  remove_ring(b, f, ring);
  FaceH nf = new_face(b, s, r.face);
  fc(b, nf).outer = ring;
  lp(b, ring).face = nf;
  sh(b, s).genus--;
  t.loops.push_back(ring);
  t.faces.push_back(f);
  t.faces.push_back(nf);
  return {nf};
}

KfmbResult EulerImpl::raw_kfmb(Body& b, FaceH f, Touched& t) {
  LoopH l = fc(b, f).outer;
  kill(b, f);
  lp(b, l).face = FaceH{};
  t.loops.push_back(l);
  return {l};
}

MfkbResult EulerImpl::raw_mfkb(Body& b, LoopH l, const Reuse& r, Touched& t) {
  ShellH s = b.shell(l);
  FaceH nf = new_face(b, s, r.face);
  fc(b, nf).outer = l;
  lp(b, l).face = nf;
  lp(b, l).next_in_face = LoopH{};
  t.loops.push_back(l);
  t.faces.push_back(nf);
  return {nf};
}

SemvResult EulerImpl::raw_semv(Body& b, HalfedgeH h, const geo::Vec3& p, const Reuse& r, Touched& t) {
  HalfedgeH tw = twin(h);
  VertexH w = he(b, tw).origin;
  VertexH m = new_vertex(b, p, r.vertex);
  EdgeH e = new_edge(b, r.edge);
  // The new edge's curve runs the same way as the old one's: its x half-edge has the
  // same direction as the old edge's x half-edge.
  int side = r.x_side >= 0 ? r.x_side : int(h.idx() & 1u);
  HalfedgeH nh = halfedge_of(e, unsigned(side)), nt = twin(nh);
  b.curves_[e.idx()] = b.curves_[edge_of(h).idx()];
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
  vx(b, m).out = nh;
  if (vx(b, w).out == tw) vx(b, w).out = nt;
  t.loops.push_back(he(b, h).loop);
  if (he(b, tw).loop != he(b, h).loop) t.loops.push_back(he(b, tw).loop);
  t.vertices.push_back(he(b, h).origin);
  t.vertices.push_back(m);
  t.vertices.push_back(w);
  return {m, e, nh};
}

void EulerImpl::raw_jekv(Body& b, HalfedgeH h, Touched& t) {
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
  if (lp(b, lh).first == nh) lp(b, lh).first = h;
  if (lp(b, lt).first == nt) lp(b, lt).first = tw;
  if (vx(b, w).out == nt) vx(b, w).out = tw;
  kill(b, m);
  kill(b, edge_of(nh));
  t.loops.push_back(lh);
  if (lt != lh) t.loops.push_back(lt);
  t.vertices.push_back(he(b, h).origin);
  t.vertices.push_back(w);
}

// ---- journal helpers -------------------------------------------------------------------

std::uint32_t EulerImpl::save(Body& b, const geo::Vec3* p, const geo::Curve* c, const geo::Surface* s,
                              std::uint8_t sense) {
  Journal& j = b.journal_;
  auto i = static_cast<std::uint32_t>(j.points_.size());
  j.points_.push_back(p ? *p : geo::Vec3::Zero());
  j.curves_.push_back(c ? *c : geo::Curve{});
  j.surfaces_.push_back(s ? *s : geo::Surface{});
  j.senses_.push_back(sense);
  return i;
}

std::uint32_t EulerImpl::save_list(Body& b, std::vector<std::uint32_t> list) {
  b.journal_.lists_.push_back(std::move(list));
  return static_cast<std::uint32_t>(b.journal_.lists_.size() - 1);
}

std::optional<Error> EulerImpl::finish(Body& b, JournalEntry e, const Touched& t) {
  std::vector<Violation> bad = check_local(b, t);
  if (!bad.empty()) {
    undo(b, e);
    std::string msg = std::string(op_name(e.op)) + " broke an invariant: " + to_string(bad.front());
    return Error{ErrorCode::postcondition, msg};
  }
  if (b.journaling_) {
    b.journal_.entries_.push_back(e);
  } else if (e.saved != kNone) {
    // Not recording: drop the geometry saved for an undo that will never come.
    b.journal_.points_.pop_back();
    b.journal_.curves_.pop_back();
    b.journal_.surfaces_.pop_back();
    b.journal_.senses_.pop_back();
  }
  if (!b.journaling_ && e.extra != kNone) b.journal_.lists_.pop_back();
  return std::nullopt;
}

// ---- public operators -------------------------------------------------------------------

namespace {

using I = EulerImpl;

Error err(ErrorCode c, std::string msg) { return Error{c, std::move(msg)}; }

template <class H>
std::optional<Error> need_alive(const Body& b, H h, const char* what) {
  if (!b.alive(h)) return err(ErrorCode::dead_handle, std::string(what) + " " + h.str() + " does not exist");
  return std::nullopt;
}

std::optional<Error> need_corner(const Body& b, Corner c) {
  if (c.lone.valid()) {
    if (auto e = need_alive(b, c.lone, "loop")) return e;
    if (!b.is_lone(c.lone)) return err(ErrorCode::not_lone, "loop " + c.lone.str() + " is not a lone-vertex loop");
    return std::nullopt;
  }
  return need_alive(b, c.he, "half-edge");
}

LoopH corner_loop(const Body& b, Corner c) { return c.lone.valid() ? c.lone : b.loop(c.he); }

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

// Would the face made from `ring` still reach the ring's face `f` through edges, faces
// and border cycles? Walks outward from the ring; O(size of the shell), and mfkrh is rare.
bool reaches_after_detach(const Body& b, LoopH ring, FaceH f) {
  std::vector<std::uint8_t> seen_face(b.face_slots(), 0), seen_loop(b.loop_slots(), 0);
  std::vector<LoopH> todo;  // loops whose half-edges' twins lead onward
  auto enter = [&](LoopH l) -> bool {
    if (l == ring || seen_loop[l.idx()]) return false;
    if (b.is_border(l)) {
      seen_loop[l.idx()] = 1;
      todo.push_back(l);
      return false;
    }
    FaceH g = b.face(l);
    if (g == f) return true;
    if (seen_face[g.idx()]) return false;
    seen_face[g.idx()] = 1;
    for (LoopH k : b.loops_of(g)) {
      seen_loop[k.idx()] = 1;
      todo.push_back(k);
    }
    return false;
  };
  for (HalfedgeH h : b.loop_halfedges(ring))
    if (enter(b.loop(twin(h)))) return true;
  while (!todo.empty()) {
    LoopH l = todo.back();
    todo.pop_back();
    for (HalfedgeH h : b.loop_halfedges(l))
      if (enter(b.loop(twin(h)))) return true;
  }
  return false;
}

JournalEntry entry(Op op) {
  JournalEntry e;
  e.op = op;
  return e;
}


}  // namespace

namespace euler {

Result<MvfsResult> mvfs(Body& b, const geo::Vec3& p) {
  Touched t;
  MvfsResult r = I::raw_mvfs(b, p, {}, t);
  JournalEntry e = entry(Op::mvfs);
  e.h = {r.shell.idx(), r.face.idx(), r.loop.idx(), r.vertex.idx(), kNone, kNone, kNone};
  if (auto bad = I::finish(b, e, t)) return *bad;
  return r;
}

Result<Done> kvfs(Body& b, FaceH f) {
  if (auto e = need_alive(b, f, "face")) return *e;
  LoopH l = b.outer_loop(f);
  if (b.next_in_face(l).valid()) return err(ErrorCode::has_rings, "face " + f.str() + " has rings");
  if (!b.is_lone(l)) return err(ErrorCode::not_lone, "face " + f.str() + " is not bounded by a lone vertex");
  ShellH s = b.shell(f);
  if (b.shell_face_count(s) != 1) return err(ErrorCode::last_face, "shell " + s.str() + " has other faces");
  VertexH v = b.lone_vertex(l);
  JournalEntry e = entry(Op::kvfs);
  e.h = {s.idx(), f.idx(), l.idx(), v.idx(), kNone, kNone, kNone};
  e.saved = I::save(b, &b.point(v), nullptr, &b.surface(f), b.same_sense(f));
  Touched t;
  I::raw_kvfs(b, f, t);
  if (auto bad = I::finish(b, e, t)) return *bad;
  return Done{};
}

Result<MevResult> mev(Body& b, Corner c, const geo::Vec3& p) {
  if (auto e = need_corner(b, c)) return *e;
  Touched t;
  if (c.lone.valid()) {
    if (b.is_border(c.lone)) return err(ErrorCode::border, "loop " + c.lone.str() + " is a border cycle");
    MevResult r = I::raw_mev(b, I::MevKind::lone, {}, {}, c.lone, p, {}, t);
    JournalEntry e = entry(Op::mev);
    e.h = {r.vertex.idx(), r.edge.idx(), r.x.idx(), kNone, kNone, c.lone.idx(), 0};
    if (auto bad = I::finish(b, e, t)) return *bad;
    return r;
  }
  if (b.is_border(c.he))
    return err(ErrorCode::border, "a strut before " + c.he.str() + " would lie in a border cycle");
  MevResult r = I::raw_mev(b, I::MevKind::strut, c.he, c.he, {}, p, {}, t);
  JournalEntry e = entry(Op::mev);
  e.h = {r.vertex.idx(), r.edge.idx(), r.x.idx(), c.he.idx(), c.he.idx(), kNone, 1};
  if (auto bad = I::finish(b, e, t)) return *bad;
  return r;
}

Result<MevResult> mev_split(Body& b, HalfedgeH h1, HalfedgeH h2, const geo::Vec3& p) {
  if (auto e = need_alive(b, h1, "half-edge")) return *e;
  if (auto e = need_alive(b, h2, "half-edge")) return *e;
  if (h1 == h2) return mev(b, Corner::before(h1), p);
  if (b.origin(h1) != b.origin(h2))
    return err(ErrorCode::wrong_vertex, h1.str() + " and " + h2.str() + " leave different vertices");
  if (!in_rotation(b, h1, h2))
    return err(ErrorCode::wrong_vertex, h2.str() + " is not in the rotation of " + b.origin(h1).str());
  if (b.is_border(h1) && b.is_border(h2))
    return err(ErrorCode::border, "both sides of the new edge would be border cycles");
  Touched t;
  MevResult r = I::raw_mev(b, I::MevKind::split, h1, h2, {}, p, {}, t);
  JournalEntry e = entry(Op::mev);
  e.h = {r.vertex.idx(), r.edge.idx(), r.x.idx(), h1.idx(), h2.idx(), kNone, 2};
  if (auto bad = I::finish(b, e, t)) return *bad;
  return r;
}

Result<Done> kev(Body& b, HalfedgeH x) {
  if (auto e = need_alive(b, x, "half-edge")) return *e;
  HalfedgeH y = twin(x);
  VertexH v = b.origin(x), w = b.origin(y);
  if (v == w) return err(ErrorCode::self_loop, "edge " + edge_of(x).str() + " is a self-loop at " + v.str());
  bool lone = b.next(x) == y && b.next(y) == x;
  if (!lone && b.next(y) == x)
    return err(ErrorCode::degree, v.str() + " dangles at the end of " + edge_of(x).str() + "; use kev(" +
                                      y.str() + ")");
  JournalEntry e = entry(Op::kev);
  // Inverse record: h[0] survivor v, h[1] killed w, h[2] x (edge and side),
  // h[3], h[4] the corners of the re-split, h[5] the loop if it collapses to v, h[6] kind.
  HalfedgeH nx = b.next(x), ny = b.next(y);
  if (lone) {
    e.h = {v.idx(), w.idx(), x.idx(), kNone, kNone, b.loop(x).idx(), 0};
  } else if (nx == y) {
    e.h = {v.idx(), w.idx(), x.idx(), ny.idx(), ny.idx(), kNone, 1};
  } else {
    e.h = {v.idx(), w.idx(), x.idx(), nx.idx(), ny.idx(), kNone, 2};
  }
  e.saved = I::save(b, &b.point(w), &b.curve(edge_of(x)), nullptr, 1);
  Touched t;
  I::raw_kev(b, x, t);
  if (auto bad = I::finish(b, e, t)) return *bad;
  return Done{};
}

Result<MefResult> mef(Body& b, Corner c1, Corner c2) {
  if (auto e = need_corner(b, c1)) return *e;
  if (auto e = need_corner(b, c2)) return *e;
  LoopH l1 = corner_loop(b, c1), l2 = corner_loop(b, c2);
  if (l1 != l2) return err(ErrorCode::wrong_loop, "corners are in different loops " + l1.str() + ", " + l2.str());
  if (c1.lone.valid() != c2.lone.valid())
    return err(ErrorCode::wrong_loop, "a lone-vertex loop has no half-edge corner");
  Touched t;
  MefResult r = I::raw_mef(b, c1, c2, {}, t);
  JournalEntry e = entry(Op::mef);
  e.h = {r.edge.idx(), r.a.idx(), r.face.idx(), r.loop.idx(), kNone, kNone, kNone};
  if (auto bad = I::finish(b, e, t)) return *bad;
  return r;
}

Result<Done> kef(Body& b, HalfedgeH h) {
  if (auto e = need_alive(b, h, "half-edge")) return *e;
  HalfedgeH tw = twin(h);
  LoopH lh = b.loop(h), lt = b.loop(tw);
  FaceH fh = b.face(lh), ft = b.face(lt);
  if (lh == lt) return err(ErrorCode::wrong_loop, "both sides of " + edge_of(h).str() + " are in loop " + lh.str() + "; use kemr");
  if (fh.valid() && fh == ft) return err(ErrorCode::wrong_face, "both sides of " + edge_of(h).str() + " are in face " + fh.str());
  if (!fh.valid() && !ft.valid()) return err(ErrorCode::border, "edge " + edge_of(h).str() + " has no face");
  if (ft.valid() && b.outer_loop(ft) != lt)
    return err(ErrorCode::outer_loop, "loop " + lt.str() + " is a ring of " + ft.str() + "; kef merges outer loops");
  bool h_alone = b.next(h) == h, t_alone = b.next(tw) == tw;
  if (h_alone && !t_alone) return err(ErrorCode::not_strut, "loop " + lh.str() + " is " + h.str() + " alone; use kef(" + tw.str() + ")");
  if (!fh.valid()) {
    if (b.next_in_face(lt).valid()) return err(ErrorCode::has_rings, "face " + ft.str() + " has rings");
    if (b.shell_face_count(b.shell(ft)) <= 1) return err(ErrorCode::last_face, "face " + ft.str() + " is its shell's last face");
    for (HalfedgeH o : b.loop_halfedges(lt))
      if (o != tw && b.is_border(twin(o)))
        return err(ErrorCode::border, "edge " + edge_of(o).str() + " would have border cycles on both sides");
  }
  JournalEntry e = entry(Op::kef);
  // h[0] h (side a of the re-made edge), h[1] face killed (or none), h[2] loop killed,
  // h[3], h[4] corners of the re-made edge, h[5] h's loop, h[6] kind: 0 lone, 1 empty range,
  // 2 general.
  HalfedgeH nh = b.next(h), nt = b.next(tw);
  std::uint32_t kind = (h_alone && t_alone) ? 0 : t_alone ? 1 : 2;
  e.h = {h.idx(), ft.valid() ? ft.idx() : kNone, lt.idx(), kind == 2 ? nt.idx() : nh.idx(), nh.idx(), lh.idx(), kind};
  e.saved = I::save(b, nullptr, &b.curve(edge_of(h)), ft.valid() ? &b.surface(ft) : nullptr,
                    ft.valid() ? b.same_sense(ft) : 1);
  if (ft.valid() && fh.valid()) {
    std::vector<std::uint32_t> rings;
    for (LoopH r : b.rings_of(ft)) rings.push_back(r.idx());
    if (!rings.empty()) e.extra = I::save_list(b, std::move(rings));
  }
  Touched t;
  I::raw_kef(b, h, t);
  if (auto bad = I::finish(b, e, t)) return *bad;
  return Done{};
}

Result<KemrResult> kemr(Body& b, HalfedgeH x) {
  if (auto e = need_alive(b, x, "half-edge")) return *e;
  HalfedgeH y = twin(x);
  LoopH l = b.loop(x);
  if (b.loop(y) != l) return err(ErrorCode::wrong_loop, "the sides of " + edge_of(x).str() + " are in different loops");
  if (b.is_border(l)) return err(ErrorCode::border, "loop " + l.str() + " is a border cycle");
  if (b.next(x) == y && b.next(y) == x && b.origin(x) == b.origin(y))
    return err(ErrorCode::self_loop, "a self-loop alone in " + l.str() + " cannot make a ring");
  JournalEntry e = entry(Op::kemr);
  // h[0] x, h[1] ring made, h[2] corner c1 (next(y) or none), h[3] corner c2 (next(x) or none),
  // h[4] loop l.
  HalfedgeH nx = b.next(x), ny = b.next(y);
  e.h = {x.idx(), kNone, ny != x ? ny.idx() : kNone, nx != y ? nx.idx() : kNone, l.idx(), kNone, kNone};
  e.saved = I::save(b, nullptr, &b.curve(edge_of(x)), nullptr, 1);
  Touched t;
  KemrResult r = I::raw_kemr(b, x, {}, t);
  e.h[1] = r.ring.idx();
  if (auto bad = I::finish(b, e, t)) return *bad;
  return r;
}

Result<MekrResult> mekr(Body& b, Corner c1, Corner c2) {
  if (auto e = need_corner(b, c1)) return *e;
  if (auto e = need_corner(b, c2)) return *e;
  LoopH l1 = corner_loop(b, c1), l2 = corner_loop(b, c2);
  if (l1 == l2) return err(ErrorCode::wrong_loop, "both corners are in loop " + l1.str() + "; use mef");
  if (b.is_border(l1) || b.is_border(l2)) return err(ErrorCode::border, "mekr joins loops of a face, not border cycles");
  if (b.face(l1) != b.face(l2)) return err(ErrorCode::wrong_face, "loops " + l1.str() + " and " + l2.str() + " are in different faces");
  if (b.is_outer(l2)) return err(ErrorCode::outer_loop, "loop " + l2.str() + " is an outer loop; pass it first");
  Touched t;
  JournalEntry e = entry(Op::mekr);
  e.h = {kNone, kNone, l2.idx(), kNone, kNone, kNone, kNone};
  MekrResult r = I::raw_mekr(b, c1, c2, {}, t);
  e.h[0] = r.edge.idx();
  e.h[1] = r.a.idx();
  if (auto bad = I::finish(b, e, t)) return *bad;
  return r;
}

Result<Done> kfmrh(Body& b, FaceH keep, FaceH kf) {
  if (auto e = need_alive(b, keep, "face")) return *e;
  if (auto e = need_alive(b, kf, "face")) return *e;
  if (keep == kf) return err(ErrorCode::wrong_face, "kfmrh needs two different faces");
  if (b.shell(keep) != b.shell(kf)) return err(ErrorCode::different_shell, keep.str() + " and " + kf.str() + " are in different shells");
  if (b.next_in_face(b.outer_loop(kf)).valid()) return err(ErrorCode::has_rings, "face " + kf.str() + " has rings");
  JournalEntry e = entry(Op::kfmrh);
  e.h = {keep.idx(), kf.idx(), b.outer_loop(kf).idx(), kNone, kNone, kNone, kNone};
  e.saved = I::save(b, nullptr, nullptr, &b.surface(kf), b.same_sense(kf));
  Touched t;
  I::raw_kfmrh(b, keep, kf, t);
  if (auto bad = I::finish(b, e, t)) return *bad;
  return Done{};
}

Result<MfkrhResult> mfkrh(Body& b, LoopH ring) {
  if (auto e = need_alive(b, ring, "loop")) return *e;
  if (b.is_border(ring)) return err(ErrorCode::border, "loop " + ring.str() + " is a border cycle");
  if (b.is_outer(ring)) return err(ErrorCode::outer_loop, "loop " + ring.str() + " is an outer loop");
  if (b.shell_genus(b.shell(b.face(ring))) == 0) return err(ErrorCode::genus, "shell " + b.shell(b.face(ring)).str() + " has no through-hole");
  FaceH f = b.face(ring);
  if (!reaches_after_detach(b, ring, f))
    return err(ErrorCode::disconnects, "ring " + ring.str() + " does not go around a through-hole of " + f.str() +
                                           ": a face made from it would split the shell");
  JournalEntry e = entry(Op::mfkrh);
  Touched t;
  MfkrhResult r = I::raw_mfkrh(b, ring, {}, t);
  e.h = {f.idx(), r.face.idx(), ring.idx(), kNone, kNone, kNone, kNone};
  if (auto bad = I::finish(b, e, t)) return *bad;
  return r;
}

Result<KfmbResult> kfmb(Body& b, FaceH f) {
  if (auto e = need_alive(b, f, "face")) return *e;
  LoopH l = b.outer_loop(f);
  if (b.next_in_face(l).valid()) return err(ErrorCode::has_rings, "face " + f.str() + " has rings");
  if (b.is_lone(l)) return err(ErrorCode::is_lone, "face " + f.str() + " has no edges");
  if (b.shell_face_count(b.shell(f)) <= 1) return err(ErrorCode::last_face, "face " + f.str() + " is its shell's last face");
  for (HalfedgeH o : b.loop_halfedges(l)) {
    if (b.is_border(twin(o))) return err(ErrorCode::border, "edge " + edge_of(o).str() + " already borders a gap");
    if (b.loop(twin(o)) == l)
      return err(ErrorCode::border, "edge " + edge_of(o).str() + " has " + f.str() + " on both sides (a seam)");
  }
  JournalEntry e = entry(Op::kfmb);
  e.h = {f.idx(), l.idx(), kNone, kNone, kNone, kNone, kNone};
  e.saved = I::save(b, nullptr, nullptr, &b.surface(f), b.same_sense(f));
  Touched t;
  KfmbResult r = I::raw_kfmb(b, f, t);
  if (auto bad = I::finish(b, e, t)) return *bad;
  return r;
}

Result<MfkbResult> mfkb(Body& b, LoopH l) {
  if (auto e = need_alive(b, l, "loop")) return *e;
  if (!b.is_border(l)) return err(ErrorCode::border, "loop " + l.str() + " is not a border cycle");
  Touched t;
  MfkbResult r = I::raw_mfkb(b, l, {}, t);
  JournalEntry e = entry(Op::mfkb);
  e.h = {r.face.idx(), l.idx(), kNone, kNone, kNone, kNone, kNone};
  if (auto bad = I::finish(b, e, t)) return *bad;
  return r;
}

Result<SemvResult> semv(Body& b, HalfedgeH h, const geo::Vec3& p) {
  if (auto e = need_alive(b, h, "half-edge")) return *e;
  Touched t;
  I::Reuse r;
  r.x_side = -1;  // choose by the direction of h
  SemvResult res = I::raw_semv(b, h, p, r, t);
  JournalEntry e = entry(Op::semv);
  e.h = {h.idx(), res.vertex.idx(), res.edge.idx(), res.next.idx(), kNone, kNone, kNone};
  if (auto bad = I::finish(b, e, t)) return *bad;
  return res;
}

Result<Done> jekv(Body& b, HalfedgeH h) {
  if (auto e = need_alive(b, h, "half-edge")) return *e;
  HalfedgeH nh = b.next(h);
  VertexH m = b.target(h);
  if (nh == twin(h)) return err(ErrorCode::degree, m.str() + " dangles at the end of " + edge_of(h).str());
  if (edge_of(nh) == edge_of(h)) return err(ErrorCode::self_loop, "edge " + edge_of(h).str() + " meets itself at " + m.str());
  if (b.next(twin(nh)) != twin(h))
    return err(ErrorCode::degree, m.str() + " lies on more than the two edges " + edge_of(h).str() + ", " + edge_of(nh).str());
  JournalEntry e = entry(Op::jekv);
  e.h = {h.idx(), m.idx(), edge_of(nh).idx(), nh.idx(), kNone, kNone, kNone};
  e.saved = I::save(b, &b.point(m), &b.curve(edge_of(nh)), nullptr, 1);
  Touched t;
  I::raw_jekv(b, h, t);
  if (auto bad = I::finish(b, e, t)) return *bad;
  return Done{};
}

}  // namespace euler
}  // namespace kintsugi
