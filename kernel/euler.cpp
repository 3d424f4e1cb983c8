// What the Euler operators share: error names, storage slots, the journal's side
// tables, and finish() — the local check every operator runs after itself. Each operator
// pair lives in its own file, kernel/op_<pair>.cpp (contracts: kernel/euler.h and
// spec/operators.md).
#include "kernel/euler.h"

#include "kernel/euler_impl.h"

#include <algorithm>
#include <atomic>

namespace kintsugi {

namespace {
// Refusals with Error::postcondition since the program started: each is a kernel bug.
std::atomic<std::uint64_t> postcondition_count{0};
}  // namespace

namespace euler {
std::uint64_t postcondition_failures() { return postcondition_count.load(std::memory_order_relaxed); }
}  // namespace euler

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

void EulerImpl::kill(Body& b, VertexH v) {
  set_out(b, v, b.vertices_[v.idx()].out);  // revived by an undo, it gets its out back
  b.v_alive_[v.idx()] = 0;
}
void EulerImpl::kill(Body& b, EdgeH e) { b.e_alive_[e.idx()] = 0; }
void EulerImpl::kill(Body& b, LoopH l) {
  // Where it started goes to the journal (set_first): undone, the kill revives the loop
  // through a make step that starts it at its new half-edge.
  set_first(b, l, HalfedgeH{});
  b.l_alive_[l.idx()] = 0;
}
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

std::optional<Error> EulerImpl::finish(Body& b, JournalEntry e, const TouchedElements& t) {
  std::vector<Violation> bad = check_local(b, t);
  if (!bad.empty()) {
    undo(b, e);
    postcondition_count.fetch_add(1, std::memory_order_relaxed);
    std::string msg = std::string(op_name(e.op())) + " broke an invariant: " + to_string(bad.front());
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

}  // namespace kintsugi
