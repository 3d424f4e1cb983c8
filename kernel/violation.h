// A broken invariant: which one (a stable code from spec/invariants.md), the elements
// it concerns ("h7", "l2", ...), and a sentence that says what is wrong. The kernel owns
// the record because its operators check themselves (kernel/local_check.h); the
// whole-body validators in invariants/ return the same record.
#pragma once

#include <string>
#include <vector>

namespace kintsugi {

struct Violation {
  std::string invariant;              // e.g. "twin_next_prev", "euler_poincare"
  std::vector<std::string> elements;  // printed handles
  std::string detail;
  double distance = 0.0;              // for geometric violations: how far off
};

std::string to_string(const Violation& v);

}  // namespace kintsugi
