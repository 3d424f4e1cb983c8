// Internal: the raw operators behind kernel/euler.h, shared by euler.cpp (forward
// operators) and undo.cpp (rollback by inverses). Not part of the public API.
//
// Raw operators do no precondition checks and no journaling. Each can be told which
// slots to use for the elements it creates (`Reuse`), so that undoing a kill operator
// revives exactly the handles it killed and later journal entries stay meaningful.
#pragma once

#include "kernel/body.h"
#include "kernel/euler.h"

#include <optional>

namespace kintsugi {

constexpr std::uint32_t kNone = JournalEntry::kNone;

// What an operator touched: the local invariant check looks at exactly these.
struct Touched {
  std::vector<LoopH> loops;
  std::vector<VertexH> vertices;
  std::vector<FaceH> faces;
};

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
  static FaceRec& fc(Body& b, FaceH f) { return b.faces_[f.idx()]; }
  static ShellRec& sh(Body& b, ShellH s) { return b.shells_[s.idx()]; }
  static VertexRec& vx(Body& b, VertexH v) { return b.vertices_[v.idx()]; }
  static void link(Body& b, HalfedgeH a, HalfedgeH c) {
    he(b, a).next = c;
    he(b, c).prev = a;
  }
  // Sets loop(h) = l for the half-edges from `from` following next until `stop` (exclusive).
  static void relabel(Body& b, HalfedgeH from, HalfedgeH stop, LoopH l);
  static void add_ring(Body& b, FaceH f, LoopH l);
  static void remove_ring(Body& b, FaceH f, LoopH l);

  // ---- raw operators ---------------------------------------------------------------
  struct Reuse {
    std::uint32_t vertex = kNone, edge = kNone, loop = kNone, face = kNone, shell = kNone;
    int x_side = 0;  // which half-edge of a new edge plays the role of x / a
  };
  enum class MevKind : std::uint8_t { lone, strut, split };

  static MvfsResult raw_mvfs(Body& b, const geo::Vec3& p, const Reuse& r, Touched& t);
  static void raw_kvfs(Body& b, FaceH f, Touched& t);
  static MevResult raw_mev(Body& b, MevKind k, HalfedgeH h1, HalfedgeH h2, LoopH lone,
                           const geo::Vec3& p, const Reuse& r, Touched& t);
  static void raw_kev(Body& b, HalfedgeH x, Touched& t);
  static MefResult raw_mef(Body& b, Corner c1, Corner c2, const Reuse& r, Touched& t);
  static void raw_kef(Body& b, HalfedgeH h, Touched& t);
  static KemrResult raw_kemr(Body& b, HalfedgeH h, const Reuse& r, Touched& t);
  static MekrResult raw_mekr(Body& b, Corner c1, Corner c2, const Reuse& r, Touched& t);
  static void raw_kfmrh(Body& b, FaceH keep, FaceH kill, Touched& t);
  static MfkrhResult raw_mfkrh(Body& b, LoopH ring, const Reuse& r, Touched& t);
  static KfmbResult raw_kfmb(Body& b, FaceH f, Touched& t);
  static MfkbResult raw_mfkb(Body& b, LoopH l, const Reuse& r, Touched& t);
  static SemvResult raw_semv(Body& b, HalfedgeH h, const geo::Vec3& p, const Reuse& r, Touched& t);
  static void raw_jekv(Body& b, HalfedgeH h, Touched& t);

  // ---- journal ----------------------------------------------------------------------
  // Saves geometry an operator is about to destroy; returns its index in the journal.
  static std::uint32_t save(Body& b, const geo::Vec3* p, const geo::Curve* c,
                            const geo::Surface* s, std::uint8_t sense);
  static std::uint32_t save_list(Body& b, std::vector<std::uint32_t> list);
  // Applies the inverse of `e` without journaling.
  static void undo(Body& b, const JournalEntry& e);
  // Records `e` (if journaling) after the local check passed; otherwise undoes it and
  // returns the postcondition error.
  static std::optional<Error> finish(Body& b, JournalEntry e, const Touched& t);

  static ShellH shell_of_loop(const Body& b, LoopH l) { return b.shell(l); }
  static bool& journaling(Body& b) { return b.journaling_; }
  static Journal& journal(Body& b) { return b.journal_; }
};

// The local invariant check (invariants/topology_check.cpp): everything an operator
// touched. Empty when all holds.
struct Violation;
std::vector<Violation> check_local(const Body& b, const Touched& t);

}  // namespace kintsugi
