// A journal transaction: everything done to a body between construction and commit()
// is undone exactly by rollback() (or by the destructor, if neither was called), by
// applying the inverses of the journaled operators in reverse order and then dropping
// the slots the transaction appended. Transactions nest.
//
//   Transaction tx(body);
//   ... Euler operators and geometry changes ...
//   if (!ok) tx.rollback(); else tx.commit();
#pragma once

#include "kernel/body.h"

namespace kintsugi {

class Transaction {
 public:
  explicit Transaction(Body& b);
  ~Transaction();
  Transaction(const Transaction&) = delete;
  Transaction& operator=(const Transaction&) = delete;

  void commit();
  void rollback();
  // Journal index of this transaction's first entry: what it did is
  // body.journal().op_names(first_entry()).
  std::size_t first_entry() const { return entries_; }

 private:
  void close();
  Body* b_;
  bool open_ = true;
  bool was_journaling_;
  std::size_t entries_, points_, lists_, firsts_, outs_;
  std::size_t vertices_, edges_, loops_, faces_, shells_;
};

}  // namespace kintsugi
