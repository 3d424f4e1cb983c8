// Random Euler operators on a body, driven by a stream of numbers (from rapidcheck or
// from fuzzer bytes). Arguments are chosen among live elements, biased towards
// configurations where the operator's preconditions can hold, so long sequences reach
// interesting bodies; operators that refuse are part of the test too.
#pragma once

#include "kernel/body.h"
#include "kernel/euler.h"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace kintsugi::testing {

class Numbers {
 public:
  explicit Numbers(std::vector<std::uint32_t> v) : v_(std::move(v)) {}
  Numbers(const std::uint8_t* data, std::size_t size);
  bool empty() const { return i_ >= v_.size(); }
  std::uint32_t next() { return i_ < v_.size() ? v_[i_++] : 0u; }
  std::uint32_t below(std::size_t n) { return n ? std::uint32_t(next() % n) : 0u; }
  double coord() { return double(int(next() % 2001) - 1000) / 100.0; }

 private:
  std::vector<std::uint32_t> v_;
  std::size_t i_ = 0;
};

enum class OpKind { make, kill };

struct Applied {
  std::string op;    // the operator's name as in kernel/operator_list.h, e.g. "mef"
  std::string what;  // e.g. "mef(h3, h7)"
  bool ok = false;
  // What can_<op> said before the operator ran, on the same body and arguments: the
  // operator must succeed exactly when its query says yes.
  bool query_ok = false;
  std::string query_error;
  std::string error;
  ErrorCode code = ErrorCode::dead_handle;  // when !ok; postcondition is a kernel bug
  OpKind kind = OpKind::make;
  // For a make operator that succeeded: applies its public inverse (kev after mev, ...).
  std::function<Result<Done>(Body&)> inverse;
};

// Applies one operator chosen by `n` to `b`, asking its query first.
Applied apply_random_op(Body& b, Numbers& n);

// "mev(h3) refused with postcondition: ..." when `a` is a refusal that is a kernel bug,
// else empty. Every test and fuzz target that applies operators fails on it.
std::string kernel_bug(const Applied& a);

}  // namespace kintsugi::testing
