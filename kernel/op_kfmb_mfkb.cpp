// kfmb / mfkb — kill (make) a face, make (kill) a border cycle: open a gap where a face
// was, and close a gap with a new face. Contracts: kernel/euler.h, spec/operators.md.
#include "kernel/euler_impl.h"

namespace kintsugi {

using I = EulerImpl;
using pre::err;

// ---- kfmb ----------------------------------------------------------------------------

std::optional<Error> euler::can_kfmb(const Body& b, FaceH f) {
  if (auto e = pre::alive(b, f, "face")) return e;
  LoopH l = b.outer_loop(f);
  if (b.next_in_face(l).valid()) return err(ErrorCode::has_rings, "face " + f.str() + " has rings");
  if (b.is_lone(l)) return err(ErrorCode::is_lone, "face " + f.str() + " has no edges");
  if (b.shell_face_count(b.shell(f)) <= 1)
    return err(ErrorCode::last_face, "face " + f.str() + " is its shell's last face");
  for (HalfedgeH o : b.loop_halfedges(l)) {
    if (b.is_border(twin(o))) return err(ErrorCode::border, "edge " + edge_of(o).str() + " already borders a gap");
    if (b.loop(twin(o)) == l)
      return err(ErrorCode::border, "edge " + edge_of(o).str() + " has " + f.str() + " on both sides (a seam)");
  }
  return std::nullopt;
}

KfmbResult EulerImpl::raw_kfmb(Body& b, FaceH f, TouchedElements& t) {
  LoopH l = fc(b, f).outer;
  kill(b, f);
  lp(b, l).face = FaceH{};
  t.loops.push_back(l);
  return {l};
}

Result<KfmbResult> euler::kfmb(Body& b, FaceH f) {
  if (auto e = can_kfmb(b, f)) return *e;
  JournalEntry e{KfmbRecord{f, b.outer_loop(f)}};
  e.saved = I::save(b, nullptr, nullptr, &b.surface(f), b.same_sense(f));
  TouchedElements t;
  KfmbResult r = I::raw_kfmb(b, f, t);
  if (auto bad = I::finish(b, e, t)) return *bad;
  return r;
}

void EulerImpl::undo(Body& b, const KfmbRecord& r, const JournalEntry& e) {
  TouchedElements t;
  Reuse reuse;
  reuse.face = r.killed.idx();
  raw_mfkb(b, r.border, reuse, t);
  restore_surface(b, e, r.killed);
}

// ---- mfkb ----------------------------------------------------------------------------

std::optional<Error> euler::can_mfkb(const Body& b, LoopH l) {
  if (auto e = pre::alive(b, l, "loop")) return e;
  if (!b.is_border(l)) return err(ErrorCode::border, "loop " + l.str() + " is not a border cycle");
  return std::nullopt;
}

MfkbResult EulerImpl::raw_mfkb(Body& b, LoopH l, const Reuse& r, TouchedElements& t) {
  ShellH s = b.shell(l);
  FaceH nf = new_face(b, s, r.face);
  fc(b, nf).outer = l;
  lp(b, l).face = nf;
  lp(b, l).next_in_face = LoopH{};
  t.loops.push_back(l);
  t.faces.push_back(nf);
  return {nf};
}

Result<MfkbResult> euler::mfkb(Body& b, LoopH l) {
  if (auto e = can_mfkb(b, l)) return *e;
  TouchedElements t;
  MfkbResult r = I::raw_mfkb(b, l, {}, t);
  JournalEntry e{MfkbRecord{r.face, l}};
  if (auto bad = I::finish(b, e, t)) return *bad;
  return r;
}

void EulerImpl::undo(Body& b, const MfkbRecord& r, const JournalEntry&) {
  TouchedElements t;
  raw_kfmb(b, r.face, t);
}

}  // namespace kintsugi
