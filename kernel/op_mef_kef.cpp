// mef / kef — make (kill) an edge and a face: a chord that cuts a loop in two, the new
// half bounding a new face, and the removal of an edge between two faces (or between a
// face and a border cycle). Contracts: kernel/euler.h, spec/operators.md.
#include "kernel/euler_impl.h"

namespace kintsugi {

using I = EulerImpl;
using pre::err;

// ---- mef -----------------------------------------------------------------------------

std::optional<Error> euler::can_mef(const Body& b, Corner c1, Corner c2) {
  if (auto e = pre::corner(b, c1)) return e;
  if (auto e = pre::corner(b, c2)) return e;
  LoopH l1 = pre::corner_loop(b, c1), l2 = pre::corner_loop(b, c2);
  if (l1 != l2) return err(ErrorCode::wrong_loop, "corners are in different loops " + l1.str() + ", " + l2.str());
  if (c1.lone.valid() != c2.lone.valid())
    return err(ErrorCode::wrong_loop, "a lone-vertex loop has no half-edge corner");
  return std::nullopt;
}

MefResult EulerImpl::raw_mef(Body& b, Corner c1, Corner c2, const Reuse& r, TouchedElements& t) {
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
    set_first(b, l, a);
    lp(b, l).lone = VertexH{};
    set_out(b, v, a);
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
  set_first(b, l, a);
  set_first(b, nl, bb);
  t.loops.push_back(l);
  t.loops.push_back(nl);
  t.faces.push_back(nf);
  return {e, a, bb, nf, nl};
}

Result<MefResult> euler::mef(Body& b, Corner c1, Corner c2) {
  if (auto e = can_mef(b, c1, c2)) return *e;
  TouchedElements t;
  I::keep_around(b, c1.he, c1.lone);
  I::keep_around(b, c2.he, c2.lone);
  MefResult r = I::raw_mef(b, c1, c2, {}, t);
  JournalEntry e{MefRecord{r.edge, r.a, r.face, r.loop}};
  if (auto bad = I::finish(b, e, t)) return *bad;
  return r;
}

void EulerImpl::undo(Body& b, const MefRecord& r, const JournalEntry&) {
  TouchedElements t;
  raw_kef(b, r.a, t);
}

// ---- kef -----------------------------------------------------------------------------

std::optional<Error> euler::can_kef(const Body& b, HalfedgeH h) {
  if (auto e = pre::alive(b, h, "half-edge")) return e;
  HalfedgeH tw = twin(h);
  LoopH lh = b.loop(h), lt = b.loop(tw);
  FaceH fh = b.face(lh), ft = b.face(lt);
  if (lh == lt)
    return err(ErrorCode::wrong_loop, "both sides of " + edge_of(h).str() + " are in loop " + lh.str() + "; use kemr");
  if (fh.valid() && fh == ft)
    return err(ErrorCode::wrong_face, "both sides of " + edge_of(h).str() + " are in face " + fh.str());
  if (!fh.valid() && !ft.valid()) return err(ErrorCode::border, "edge " + edge_of(h).str() + " has no face");
  if (ft.valid() && b.outer_loop(ft) != lt)
    return err(ErrorCode::outer_loop, "loop " + lt.str() + " is a ring of " + ft.str() + "; kef merges outer loops");
  bool h_alone = b.next(h) == h, t_alone = b.next(tw) == tw;
  if (h_alone && !t_alone)
    return err(ErrorCode::not_strut, "loop " + lh.str() + " is " + h.str() + " alone; use kef(" + tw.str() + ")");
  if (!fh.valid()) {  // the face across is absorbed into the gap
    if (b.next_in_face(lt).valid()) return err(ErrorCode::has_rings, "face " + ft.str() + " has rings");
    if (b.shell_face_count(b.shell(ft)) <= 1)
      return err(ErrorCode::last_face, "face " + ft.str() + " is its shell's last face");
    // Every other edge of the absorbed face must keep a face on one side: not one that
    // already borders a gap, nor one with the absorbed loop on both sides (a strut or a
    // seam), which would lie in the gap on both sides.
    for (HalfedgeH o : b.loop_halfedges(lt))
      if (o != tw && (b.is_border(twin(o)) || b.loop(twin(o)) == lt))
        return err(ErrorCode::border, "edge " + edge_of(o).str() + " would have border cycles on both sides");
  }
  return std::nullopt;
}

void EulerImpl::raw_kef(Body& b, HalfedgeH h, TouchedElements& t) {
  HalfedgeH tw = twin(h);
  LoopH lh = he(b, h).loop, lt = he(b, tw).loop;
  FaceH fh = lp(b, lh).face, ft = lp(b, lt).face;
  VertexH v = he(b, h).origin, w = he(b, tw).origin;
  HalfedgeH ph = he(b, h).prev, nh = he(b, h).next, pt = he(b, tw).prev, nt = he(b, tw).next;
  bool h_alone = nh == h, t_alone = nt == tw;
  if (h_alone && t_alone) {  // a self-loop between two one-edge loops: v alone remains
    set_first(b, lh, HalfedgeH{});
    lp(b, lh).lone = v;
    set_out(b, v, HalfedgeH{});
  } else if (t_alone) {  // the self-loop tw bounded its face alone
    link(b, ph, nh);
    set_first(b, lh, nh);
    if (vx(b, v).out == h || vx(b, v).out == tw) set_out(b, v, nh);
  } else {
    relabel(b, nt, tw, lh);
    link(b, ph, nt);
    link(b, pt, nh);
    set_first(b, lh, nh);
    if (vx(b, v).out == h) set_out(b, v, nt);
    if (vx(b, w).out == tw) set_out(b, w, nh);
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

Result<Done> euler::kef(Body& b, HalfedgeH h) {
  if (auto e = can_kef(b, h)) return *e;
  HalfedgeH tw = twin(h);
  LoopH lh = b.loop(h), lt = b.loop(tw);
  FaceH ft = b.face(lt);
  HalfedgeH nh = b.next(h), nt = b.next(tw);
  bool h_alone = nh == h, t_alone = nt == tw;
  // The mef that undoes this one: in h's loop (now a lone vertex) for a self-loop
  // between one-edge loops; else between the corners that bound the killed loop's arc.
  KefRecord rec{KefRecord::Kind::general, h, ft, lt, nt, nh, LoopH{}};
  if (h_alone && t_alone) {
    rec.kind = KefRecord::Kind::lone;
    rec.before1 = rec.before2 = HalfedgeH{};
    rec.lone = lh;
  } else if (t_alone) {
    rec.kind = KefRecord::Kind::empty_range;
    rec.before1 = rec.before2 = nh;
  }
  JournalEntry e{rec};
  e.saved = I::save(b, nullptr, &b.curve(edge_of(h)), ft.valid() ? &b.surface(ft) : nullptr,
                    ft.valid() ? b.same_sense(ft) : 1);
  if (ft.valid() && b.face(lh).valid()) {
    std::vector<std::uint32_t> rings;
    for (LoopH r : b.rings_of(ft)) rings.push_back(r.idx());
    if (!rings.empty()) e.extra = I::save_list(b, std::move(rings));
  }
  TouchedElements t;
  I::keep_around(b, h);
  I::raw_kef(b, h, t);
  if (auto bad = I::finish(b, e, t)) return *bad;
  return Done{};
}

void EulerImpl::undo(Body& b, const KefRecord& r, const JournalEntry& e) {
  TouchedElements t;
  Reuse reuse;
  reuse.edge = edge_of(r.h).idx();
  reuse.x_side = int(r.h.idx() & 1u);
  reuse.loop = r.killed_loop.idx();
  reuse.face = r.killed_face.idx();
  Corner c1 = r.kind == KefRecord::Kind::lone ? Corner::in_lone(r.lone) : Corner::before(r.before1);
  Corner c2 = r.kind == KefRecord::Kind::lone ? Corner::in_lone(r.lone) : Corner::before(r.before2);
  FaceH fh = b.face(c1.lone.valid() ? c1.lone : he(b, c1.he).loop);
  MefResult m = raw_mef(b, c1, c2, reuse, t);
  if (!r.killed_face.valid()) {  // the killed side was a border cycle: it becomes one again
    kill(b, m.face);
    lp(b, m.loop).face = FaceH{};
  } else {
    restore_surface(b, e, r.killed_face);
    if (e.extra != kNone && fh.valid()) {
      for (std::uint32_t ring : saved_list(b, e)) {
        remove_ring(b, fh, LoopH(ring));
        add_ring(b, m.face, LoopH(ring));
      }
    }
  }
  curve(b, edge_of(r.h)) = saved_curve(b, e);
}

}  // namespace kintsugi
