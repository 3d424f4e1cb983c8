// Internal: what the operator files (kernel/op_<pair>.cpp) share, and what the rollback
// (kernel/undo.cpp, kernel/transaction.cpp) and body (kernel/body.cpp) use. Not part of
// the public API.
//
// Each operator file holds, top to bottom: the query can_<op> (every reason to refuse),
// the raw step (no checks, no journal; told which slots to reuse, so that undoing a kill
// revives exactly the handles it killed), the public operator (query, raw step, journal
// record, local check), and the undo of each record (the raw inverse).
#pragma once

#include "kernel/body.h"
#include "kernel/euler.h"
#include "kernel/local_check.h"

#include <optional>
#include <string>

namespace kintsugi {

constexpr std::uint32_t kNone = JournalEntry::kNone;

class EulerImpl {
 public:
  // ---- storage ------------------------------------------------------------------
  static VertexH new_vertex(Body& b, const geo::Vec3& p, std::uint32_t reuse = kNone);
  static EdgeH new_edge(Body& b, std::uint32_t reuse = kNone);
  static LoopH new_loop(Body& b, FaceH f, std::uint32_t reuse = kNone);
  static FaceH new_face(Body& b, ShellH s, std::uint32_t reuse = kNone);
  static ShellH new_shell(Body& b, std::uint32_t reuse = kNone);
  static void kill(Body& b, VertexH v);
  static void kill(Body& b, EdgeH e);
  static void kill(Body& b, LoopH l);
  static void kill(Body& b, FaceH f);
  static void kill(Body& b, ShellH s);

  static HalfedgeRec& he(Body& b, HalfedgeH h) { return b.halfedges_[h.idx()]; }
  static LoopRec& lp(Body& b, LoopH l) { return b.loops_[l.idx()]; }
  // A loop's first half-edge is set only here: while journaling, the one it had is kept
  // (Journal::firsts_, even when it stays: the undo's make step may move it), so a
  // rollback restores where every loop starts as well as its half-edges. Undo re-makes a
  // killed edge through a make step that may start the loop elsewhere (mef starts the old
  // loop at its new half-edge), and a repair refused after such a step would otherwise
  // leave its faces' loops starting elsewhere, which later repairs that walk a loop from
  // its start (a small face collapsed from its first edge) see.
  static void set_first(Body& b, LoopH l, HalfedgeH h) {
    LoopRec& r = lp(b, l);
    if (b.journaling_) b.journal_.firsts_.emplace_back(l, r.first);
    r.first = h;
  }
  // A vertex's representative out-going half-edge likewise (Journal::outs_): the order
  // Body::outgoing lists a vertex's edges in starts there, and a refused repair must not
  // change the order later repairs meet them in.
  static void set_out(Body& b, VertexH v, HalfedgeH h) {
    VertexRec& r = b.vertices_[v.idx()];
    if (b.journaling_) b.journal_.outs_.emplace_back(v, r.out);
    r.out = h;
  }
  // Before an operator: the out-going half-edge of each vertex at h's ends and the start
  // of the loop on either side, recorded as they are. The operator may leave them alone
  // and its undo still move them (kev keeps the survivor's half-edge, the mev undoing it
  // gives it the revived edge's), so the rollback must know them either way.
  static void keep_around(Body& b, HalfedgeH h) {
    if (!b.journaling_ || !h.valid()) return;
    for (HalfedgeH x : {h, twin(h)}) {
      const VertexH v = he(b, x).origin;
      set_out(b, v, vx(b, v).out);
      if (const LoopH l = he(b, x).loop; l.valid()) set_first(b, l, lp(b, l).first);
    }
  }
  static void keep_around(Body& b, LoopH lone) {
    if (!b.journaling_ || !lone.valid()) return;
    set_first(b, lone, lp(b, lone).first);
    if (const VertexH v = lp(b, lone).lone; v.valid()) set_out(b, v, vx(b, v).out);
  }
  static void keep_around(Body& b, HalfedgeH h, LoopH lone) {
    keep_around(b, h);
    keep_around(b, lone);
  }
  static FaceRec& fc(Body& b, FaceH f) { return b.faces_[f.idx()]; }
  static ShellRec& sh(Body& b, ShellH s) { return b.shells_[s.idx()]; }
  static VertexRec& vx(Body& b, VertexH v) { return b.vertices_[v.idx()]; }
  static geo::Vec3& point(Body& b, VertexH v) { return b.points_[v.idx()]; }
  static geo::Curve& curve(Body& b, EdgeH e) { return b.curves_[e.idx()]; }
  static void link(Body& b, HalfedgeH a, HalfedgeH c) {
    he(b, a).next = c;
    he(b, c).prev = a;
  }
  // Sets loop(h) = l for the half-edges from `from` following next until `stop` (exclusive).
  static void relabel(Body& b, HalfedgeH from, HalfedgeH stop, LoopH l);
  static void add_ring(Body& b, FaceH f, LoopH l);
  static void remove_ring(Body& b, FaceH f, LoopH l);

  // ---- raw steps (one operator file each) -------------------------------------------
  struct Reuse {
    std::uint32_t vertex = kNone, edge = kNone, loop = kNone, face = kNone, shell = kNone;
    int x_side = 0;  // which half-edge of a new edge plays the role of x / a
  };

  static MvfsResult raw_mvfs(Body& b, const geo::Vec3& p, const Reuse& r, TouchedElements& t);
  static void raw_kvfs(Body& b, FaceH f, TouchedElements& t);
  static MevResult raw_mev(Body& b, MevKind k, HalfedgeH h1, HalfedgeH h2, LoopH lone,
                           const geo::Vec3& p, const Reuse& r, TouchedElements& t);
  static void raw_kev(Body& b, HalfedgeH x, TouchedElements& t);
  static MefResult raw_mef(Body& b, Corner c1, Corner c2, const Reuse& r, TouchedElements& t);
  static void raw_kef(Body& b, HalfedgeH h, TouchedElements& t);
  static KemrResult raw_kemr(Body& b, HalfedgeH h, const Reuse& r, TouchedElements& t);
  static MekrResult raw_mekr(Body& b, Corner c1, Corner c2, const Reuse& r, TouchedElements& t);
  static void raw_kfmrh(Body& b, FaceH keep, FaceH kill, TouchedElements& t);
  static MfkrhResult raw_mfkrh(Body& b, LoopH ring, const Reuse& r, TouchedElements& t);
  static KfmbResult raw_kfmb(Body& b, FaceH f, TouchedElements& t);
  static MfkbResult raw_mfkb(Body& b, LoopH l, const Reuse& r, TouchedElements& t);
  static SemvResult raw_semv(Body& b, HalfedgeH h, const geo::Vec3& p, const Reuse& r, TouchedElements& t);
  static void raw_jekv(Body& b, HalfedgeH h, TouchedElements& t);

  // ---- undo of each record (in the operator's file; set_* in undo.cpp) ---------------
  static void undo(Body& b, const MvfsRecord& r, const JournalEntry& e);
  static void undo(Body& b, const KvfsRecord& r, const JournalEntry& e);
  static void undo(Body& b, const MevRecord& r, const JournalEntry& e);
  static void undo(Body& b, const KevRecord& r, const JournalEntry& e);
  static void undo(Body& b, const MefRecord& r, const JournalEntry& e);
  static void undo(Body& b, const KefRecord& r, const JournalEntry& e);
  static void undo(Body& b, const KemrRecord& r, const JournalEntry& e);
  static void undo(Body& b, const MekrRecord& r, const JournalEntry& e);
  static void undo(Body& b, const KfmrhRecord& r, const JournalEntry& e);
  static void undo(Body& b, const MfkrhRecord& r, const JournalEntry& e);
  static void undo(Body& b, const KfmbRecord& r, const JournalEntry& e);
  static void undo(Body& b, const MfkbRecord& r, const JournalEntry& e);
  static void undo(Body& b, const SemvRecord& r, const JournalEntry& e);
  static void undo(Body& b, const JekvRecord& r, const JournalEntry& e);
  static void undo(Body& b, const SetPointRecord& r, const JournalEntry& e);
  static void undo(Body& b, const SetCurveRecord& r, const JournalEntry& e);
  static void undo(Body& b, const SetSurfaceRecord& r, const JournalEntry& e);
  // Applies the inverse of `e` without journaling.
  static void undo(Body& b, const JournalEntry& e);

  // ---- journal ----------------------------------------------------------------------
  // Saves geometry an operator is about to destroy; returns its index in the journal.
  static std::uint32_t save(Body& b, const geo::Vec3* p, const geo::Curve* c,
                            const geo::Surface* s, std::uint8_t sense);
  static std::uint32_t save_list(Body& b, std::vector<std::uint32_t> list);
  static const geo::Vec3& saved_point(const Body& b, const JournalEntry& e) { return b.journal_.points_[e.saved]; }
  static const geo::Curve& saved_curve(const Body& b, const JournalEntry& e) { return b.journal_.curves_[e.saved]; }
  static const std::vector<std::uint32_t>& saved_list(const Body& b, const JournalEntry& e) {
    return b.journal_.lists_[e.extra];
  }
  // Puts back the surface and sense `e` saved, on face slot `f`.
  static void restore_surface(Body& b, const JournalEntry& e, FaceH f) {
    b.surfaces_[f.idx()] = b.journal_.surfaces_[e.saved];
    b.senses_[f.idx()] = b.journal_.senses_[e.saved];
  }
  // Records `e` (if journaling) after the local check passed; otherwise undoes it and
  // returns the postcondition error (a kernel bug: counted, see euler::postcondition_failures).
  static std::optional<Error> finish(Body& b, JournalEntry e, const TouchedElements& t);

  static ShellH shell_of_loop(const Body& b, LoopH l) { return b.shell(l); }
  static bool& journaling(Body& b) { return b.journaling_; }
  static Journal& journal(Body& b) { return b.journal_; }
};

// ---- precondition helpers shared by the queries --------------------------------------
namespace pre {

inline Error err(ErrorCode c, std::string msg) { return Error{c, std::move(msg)}; }

template <class H>
std::optional<Error> alive(const Body& b, H h, const char* what) {
  if (!b.alive(h)) return err(ErrorCode::dead_handle, std::string(what) + " " + h.str() + " does not exist");
  return std::nullopt;
}

inline std::optional<Error> corner(const Body& b, Corner c) {
  if (c.lone.valid()) {
    if (auto e = alive(b, c.lone, "loop")) return e;
    if (!b.is_lone(c.lone)) return err(ErrorCode::not_lone, "loop " + c.lone.str() + " is not a lone-vertex loop");
    return std::nullopt;
  }
  return alive(b, c.he, "half-edge");
}

inline LoopH corner_loop(const Body& b, Corner c) { return c.lone.valid() ? c.lone : b.loop(c.he); }

}  // namespace pre
}  // namespace kintsugi
