#include "kernel/transaction.h"

#include "kernel/euler_impl.h"

namespace kintsugi {

Transaction::Transaction(Body& b)
    : b_(&b),
      was_journaling_(b.journaling_),
      entries_(b.journal_.entries_.size()),
      points_(b.journal_.points_.size()),
      lists_(b.journal_.lists_.size()),
      firsts_(b.journal_.firsts_.size()),
      outs_(b.journal_.outs_.size()),
      vertices_(b.vertices_.size()),
      edges_(b.e_alive_.size()),
      loops_(b.loops_.size()),
      faces_(b.faces_.size()),
      shells_(b.shells_.size()) {
  b.open_transactions_++;
  b.journaling_ = true;  // a transaction must be able to roll back
}

Transaction::~Transaction() {
  if (open_) rollback();
}

void Transaction::close() {
  open_ = false;
  b_->open_transactions_--;
  b_->journaling_ = was_journaling_;
}

void Transaction::commit() {
  if (!open_) return;
  close();
}

void Transaction::rollback() {
  if (!open_) return;
  Body& b = *b_;
  Journal& j = b.journal_;
  // The undo steps are not recorded (they may start a loop elsewhere, or revive a killed
  // one starting at its new half-edge); then each loop is put back where it started, and
  // each vertex's out-going half-edge where it was, from what the transaction's operators
  // replaced, in reverse.
  b.journaling_ = false;
  while (j.entries_.size() > entries_) {
    JournalEntry e = j.entries_.back();
    EulerImpl::undo(b, e);
    j.entries_.pop_back();
  }
  for (std::size_t i = j.firsts_.size(); i-- > firsts_;) {
    const auto& [l, h] = j.firsts_[i];
    if (l.idx() < b.loops_.size()) b.loops_[l.idx()].first = h;
  }
  j.firsts_.resize(firsts_);
  for (std::size_t i = j.outs_.size(); i-- > outs_;) {
    const auto& [v, h] = j.outs_[i];
    if (v.idx() < b.vertices_.size()) b.vertices_[v.idx()].out = h;
  }
  j.outs_.resize(outs_);
  j.points_.resize(points_);
  j.curves_.resize(points_);
  j.surfaces_.resize(points_);
  j.senses_.resize(points_);
  j.lists_.resize(lists_);
  // Slots appended inside the transaction are all dead again: drop them so the body's
  // storage is as it was.
  b.vertices_.resize(vertices_);
  b.v_alive_.resize(vertices_);
  b.points_.resize(vertices_);
  b.e_alive_.resize(edges_);
  b.halfedges_.resize(2 * edges_);
  b.curves_.resize(edges_);
  b.loops_.resize(loops_);
  b.l_alive_.resize(loops_);
  b.faces_.resize(faces_);
  b.f_alive_.resize(faces_);
  b.surfaces_.resize(faces_);
  b.senses_.resize(faces_);
  b.shells_.resize(shells_);
  b.s_alive_.resize(shells_);
  close();
}

}  // namespace kintsugi
