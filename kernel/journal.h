// The journal: every operator applied to a body, with its arguments and results, so a
// transaction can be rolled back exactly by applying the inverses in reverse order
// (spec/journal.md). Repairs use it to undo a change whose geometry turns out not to
// be realisable, and reports use it to say which operators a repair used.
#pragma once

#include "geometry/types.h"
#include "kernel/journal_records.h"

#include <cstdint>
#include <string>
#include <vector>

namespace kintsugi {

// One journaled operator: its record (kernel/journal_records.h, one named struct per
// operator), and where the geometry it destroyed or overwrote went in the journal's side
// tables, so the entry stays small.
struct JournalEntry {
  static constexpr std::uint32_t kNone = ~std::uint32_t{0};
  JournalRecord record;
  std::uint32_t saved = kNone;  // index into the side tables for this op's geometry
  std::uint32_t extra = kNone;  // index into `lists` (e.g. rings moved by kef)
  Op op() const {
    return std::visit([](const auto& r) { return std::decay_t<decltype(r)>::kOp; }, record);
  }
};

class Journal {
 public:
  const std::vector<JournalEntry>& entries() const { return entries_; }
  std::size_t size() const { return entries_.size(); }
  bool empty() const { return entries_.empty(); }
  // Operator names from entry `from` on, in order: what a repair did.
  std::vector<std::string> op_names(std::size_t from = 0) const;
  // The handle indices an entry's extra list holds (the rings kef moved to the kept
  // face); empty when it has none.
  const std::vector<std::uint32_t>& extra_of(const JournalEntry& e) const {
    static const std::vector<std::uint32_t> none;
    return e.extra == JournalEntry::kNone || e.extra >= lists_.size() ? none : lists_[e.extra];
  }

 private:
  friend class EulerImpl;
  friend class Body;
  friend class Transaction;
  void clear();

  std::vector<JournalEntry> entries_;
  std::vector<geo::Vec3> points_;
  std::vector<geo::Curve> curves_;
  std::vector<geo::Surface> surfaces_;
  std::vector<std::uint8_t> senses_;
  std::vector<std::vector<std::uint32_t>> lists_;
  // Each change of a loop's first half-edge while journaling: the loop and the half-edge
  // it started at before (EulerImpl::set_first); a rollback restores them in reverse.
  std::vector<std::pair<LoopH, HalfedgeH>> firsts_;
  // Each change of a vertex's out-going half-edge while journaling (EulerImpl::set_out).
  std::vector<std::pair<VertexH, HalfedgeH>> outs_;
};

}  // namespace kintsugi
