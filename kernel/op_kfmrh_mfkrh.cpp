// kfmrh / mfkrh — kill (make) a face, make (kill) a ring and a through-hole: a face's
// outer loop becomes a ring of another face of the shell, which gains a handle, and
// back. Contracts: kernel/euler.h, spec/operators.md.
#include "kernel/euler_impl.h"

#include <cstdint>
#include <vector>

namespace kintsugi {

using I = EulerImpl;
using pre::err;

// ---- kfmrh ---------------------------------------------------------------------------

std::optional<Error> euler::can_kfmrh(const Body& b, FaceH keep, FaceH kill) {
  if (auto e = pre::alive(b, keep, "face")) return e;
  if (auto e = pre::alive(b, kill, "face")) return e;
  if (keep == kill) return err(ErrorCode::wrong_face, "kfmrh needs two different faces");
  if (b.shell(keep) != b.shell(kill))
    return err(ErrorCode::different_shell, keep.str() + " and " + kill.str() + " are in different shells");
  if (b.next_in_face(b.outer_loop(kill)).valid())
    return err(ErrorCode::has_rings, "face " + kill.str() + " has rings");
  return std::nullopt;
}

void EulerImpl::raw_kfmrh(Body& b, FaceH keep, FaceH kf, TouchedElements& t) {
  LoopH l = fc(b, kf).outer;
  ShellH s = fc(b, kf).shell;
  add_ring(b, keep, l);
  kill(b, kf);
  sh(b, s).genus++;
  t.loops.push_back(l);
  t.faces.push_back(keep);
}

Result<Done> euler::kfmrh(Body& b, FaceH keep, FaceH kf) {
  if (auto e = can_kfmrh(b, keep, kf)) return *e;
  JournalEntry e{KfmrhRecord{keep, kf, b.outer_loop(kf)}};
  e.saved = I::save(b, nullptr, nullptr, &b.surface(kf), b.same_sense(kf));
  TouchedElements t;
  I::raw_kfmrh(b, keep, kf, t);
  if (auto bad = I::finish(b, e, t)) return *bad;
  return Done{};
}

void EulerImpl::undo(Body& b, const KfmrhRecord& r, const JournalEntry& e) {
  TouchedElements t;
  Reuse reuse;
  reuse.face = r.killed.idx();
  raw_mfkrh(b, r.ring, reuse, t);
  restore_surface(b, e, r.killed);
}

// ---- mfkrh ---------------------------------------------------------------------------

namespace {
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
}  // namespace

std::optional<Error> euler::can_mfkrh(const Body& b, LoopH ring) {
  if (auto e = pre::alive(b, ring, "loop")) return e;
  if (b.is_border(ring)) return err(ErrorCode::border, "loop " + ring.str() + " is a border cycle");
  if (b.is_outer(ring)) return err(ErrorCode::outer_loop, "loop " + ring.str() + " is an outer loop");
  FaceH f = b.face(ring);
  if (b.shell_genus(b.shell(f)) == 0)
    return err(ErrorCode::genus, "shell " + b.shell(f).str() + " has no through-hole");
  if (!reaches_after_detach(b, ring, f))
    return err(ErrorCode::disconnects, "ring " + ring.str() + " does not go around a through-hole of " + f.str() +
                                           ": a face made from it would split the shell");
  return std::nullopt;
}

MfkrhResult EulerImpl::raw_mfkrh(Body& b, LoopH ring, const Reuse& r, TouchedElements& t) {
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

Result<MfkrhResult> euler::mfkrh(Body& b, LoopH ring) {
  if (auto e = can_mfkrh(b, ring)) return *e;
  FaceH f = b.face(ring);
  TouchedElements t;
  MfkrhResult r = I::raw_mfkrh(b, ring, {}, t);
  JournalEntry e{MfkrhRecord{f, r.face, ring}};
  if (auto bad = I::finish(b, e, t)) return *bad;
  return r;
}

void EulerImpl::undo(Body& b, const MfkrhRecord& r, const JournalEntry&) {
  TouchedElements t;
  raw_kfmrh(b, r.old_face, r.face, t);
}

}  // namespace kintsugi
