// Rollback: the inverse of each journal entry, applied without journaling. Each
// operator's undo sits in its own file (kernel/op_<pair>.cpp) next to the record it
// reads; kill operators are undone by the matching make step told to revive exactly the
// slots that were killed, so handles recorded in later (already undone) entries and held
// by callers mean the same elements again. The geometry changes are undone here.
#include "kernel/euler_impl.h"

#include <variant>

namespace kintsugi {

void EulerImpl::undo(Body& b, const JournalEntry& e) {
  std::visit([&](const auto& r) { undo(b, r, e); }, e.record);
}

void EulerImpl::undo(Body& b, const SetPointRecord& r, const JournalEntry& e) {
  point(b, r.vertex) = saved_point(b, e);
}

void EulerImpl::undo(Body& b, const SetCurveRecord& r, const JournalEntry& e) {
  curve(b, r.edge) = saved_curve(b, e);
}

void EulerImpl::undo(Body& b, const SetSurfaceRecord& r, const JournalEntry& e) { restore_surface(b, e, r.face); }

}  // namespace kintsugi
