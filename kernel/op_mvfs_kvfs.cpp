// mvfs / kvfs — make (kill) vertex, face, shell: a new shell that is one face bounded by a
// lone vertex, and its removal. Contracts: kernel/euler.h, spec/operators.md.
#include "kernel/euler_impl.h"

namespace kintsugi {

using I = EulerImpl;
using pre::err;

// ---- mvfs ----------------------------------------------------------------------------

std::optional<Error> euler::can_mvfs(const Body&, const geo::Vec3&) { return std::nullopt; }

MvfsResult EulerImpl::raw_mvfs(Body& b, const geo::Vec3& p, const Reuse& r, TouchedElements& t) {
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

Result<MvfsResult> euler::mvfs(Body& b, const geo::Vec3& p) {
  if (auto e = can_mvfs(b, p)) return *e;
  TouchedElements t;
  MvfsResult r = I::raw_mvfs(b, p, {}, t);
  JournalEntry e{MvfsRecord{r.shell, r.face, r.loop, r.vertex}};
  if (auto bad = I::finish(b, e, t)) return *bad;
  return r;
}

void EulerImpl::undo(Body& b, const MvfsRecord& r, const JournalEntry&) {
  TouchedElements t;
  raw_kvfs(b, r.face, t);
}

// ---- kvfs ----------------------------------------------------------------------------

std::optional<Error> euler::can_kvfs(const Body& b, FaceH f) {
  if (auto e = pre::alive(b, f, "face")) return e;
  LoopH l = b.outer_loop(f);
  if (b.next_in_face(l).valid()) return err(ErrorCode::has_rings, "face " + f.str() + " has rings");
  if (!b.is_lone(l)) return err(ErrorCode::not_lone, "face " + f.str() + " is not bounded by a lone vertex");
  ShellH s = b.shell(f);
  if (b.shell_face_count(s) != 1) return err(ErrorCode::last_face, "shell " + s.str() + " has other faces");
  return std::nullopt;
}

void EulerImpl::raw_kvfs(Body& b, FaceH f, TouchedElements&) {
  LoopH l = fc(b, f).outer;
  VertexH v = lp(b, l).lone;
  ShellH s = fc(b, f).shell;
  kill(b, v);
  kill(b, l);
  kill(b, f);
  kill(b, s);
}

Result<Done> euler::kvfs(Body& b, FaceH f) {
  if (auto e = can_kvfs(b, f)) return *e;
  LoopH l = b.outer_loop(f);
  VertexH v = b.lone_vertex(l);
  JournalEntry e{KvfsRecord{b.shell(f), f, l, v}};
  e.saved = I::save(b, &b.point(v), nullptr, &b.surface(f), b.same_sense(f));
  TouchedElements t;
  I::raw_kvfs(b, f, t);
  if (auto bad = I::finish(b, e, t)) return *bad;
  return Done{};
}

void EulerImpl::undo(Body& b, const KvfsRecord& r, const JournalEntry& e) {
  TouchedElements t;
  Reuse reuse;
  reuse.shell = r.shell.idx();
  reuse.face = r.face.idx();
  reuse.loop = r.loop.idx();
  reuse.vertex = r.vertex.idx();
  raw_mvfs(b, saved_point(b, e), reuse, t);
  restore_surface(b, e, r.face);
}

}  // namespace kintsugi
