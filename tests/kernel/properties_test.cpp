// rapidcheck properties over random operator sequences (tests/support/random_ops.h):
//   * every operator keeps every invariant, and a refused one changes nothing;
//   * every make operator followed by its public inverse gives an equal body, and every
//     operator followed by its journaled inverse (a one-operator rollback) too;
//   * rolling back a random transaction restores the original;
//   * no operator ever refuses with Error::postcondition: that refusal means the operator
//     broke an invariant and undid itself, a kernel bug, not a precondition.
#include "invariants/topology_check.h"
#include "kernel/builders.h"
#include "kernel/transaction.h"
#include "tests/support/random_ops.h"

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

namespace kintsugi {
namespace {

using testing::apply_random_op;
using testing::kernel_bug;
using testing::Numbers;

Body start_body(int which) {
  switch (which % 6) {
    case 0: return build::box();
    case 1: return build::pyramid(build::regular_polygon(5, 1), 1);
    case 2: return build::cylinder(1, 2);
    case 3: return build::torus(3, 1);
    case 4: return build::sphere(1);
    default: {
      Body b;
      (void)euler::mvfs(b, geo::Vec3::Zero());
      return b;
    }
  }
}

std::string violations(const Body& b) {
  std::string out;
  for (const auto& v : check_topology(b)) out += to_string(v) + "\n";
  return out;
}

RC_GTEST_PROP(EulerProperties, RandomOperatorsKeepEveryInvariant, (int which, std::vector<std::uint32_t> nums)) {
  Body b = start_body(which);
  Numbers n(nums);
  int steps = 0;
  while (!n.empty() && steps++ < 60) {
    Body before = b.clone();
    auto a = apply_random_op(b, n);
    if (std::string bug = kernel_bug(a); !bug.empty()) RC_FAIL(bug);
    if (!a.ok) {
      std::string why;
      RC_ASSERT(b.equals(before, &why));
      continue;
    }
    std::string bad = violations(b);
    if (!bad.empty()) RC_FAIL(a.what + " broke:\n" + bad);
  }
}

RC_GTEST_PROP(EulerProperties, OperatorThenInverseRestoresAnEqualBody, (int which, std::vector<std::uint32_t> nums)) {
  Body b = start_body(which);
  Numbers n(nums);
  int steps = 0;
  while (!n.empty() && steps++ < 60) {
    Body before = b.clone();
    // Public inverse, for operators that make elements.
    auto a = apply_random_op(b, n);
    if (std::string bug = kernel_bug(a); !bug.empty()) RC_FAIL(bug);
    if (!a.ok) continue;
    if (a.inverse) {
      Body made = b.clone();
      auto r = a.inverse(made);
      if (!r.ok()) RC_FAIL(a.what + ": inverse refused: " + r.error().message);
      std::string why;
      if (!made.equals(before, &why)) RC_FAIL(a.what + " then its inverse: " + why);
    }
  }
}

// Where each loop starts and which half-edge each vertex keeps: Body::equals lets a loop
// start at any of its half-edges (and a vertex name any), but a rollback restores them
// too (kernel/transaction.cpp): repairs that walk a loop from its start, or a vertex's
// edges from its own, must meet after a refused repair what they met before it.
std::string loop_starts_differ(const Body& a, const Body& b) {
  for (LoopH l : b.loops())
    if (a.first(l) != b.first(l)) return l.str() + " starts at " + a.first(l).str() + ", before at " + b.first(l).str();
  for (VertexH v : b.vertices())
    if (a.out(v) != b.out(v)) return v.str() + " leaves by " + a.out(v).str() + ", before by " + b.out(v).str();
  return "";
}

RC_GTEST_PROP(EulerProperties, RollingBackARandomTransactionRestoresTheOriginal, (int which, std::vector<std::uint32_t> nums)) {
  Body b = start_body(which);
  Numbers n(nums);
  // Some committed history first, so the transaction starts from a non-trivial body.
  for (int i = 0; i < 10 && !n.empty(); ++i)
    if (std::string bug = kernel_bug(apply_random_op(b, n)); !bug.empty()) RC_FAIL(bug);
  Body before = b.clone();
  std::vector<std::string> done;
  {
    Transaction tx(b);
    for (int i = 0; i < 40 && !n.empty(); ++i) {
      auto a = apply_random_op(b, n);
      if (std::string bug = kernel_bug(a); !bug.empty()) RC_FAIL(bug);
      if (a.ok) done.push_back(a.what);
    }
    tx.rollback();
  }
  std::string why;
  if (!b.equals(before, &why)) {
    std::string ops;
    for (auto& s : done) ops += s + " ";
    RC_FAIL("after rolling back [" + ops + "]: " + why);
  }
  if (std::string starts = loop_starts_differ(b, before); !starts.empty()) {
    std::string ops;
    for (auto& s : done) ops += s + " ";
    RC_FAIL("after rolling back [" + ops + "]: " + starts);
  }
  RC_ASSERT(violations(b).empty());
}

RC_GTEST_PROP(EulerProperties, EachOperatorRollsBackAlone, (int which, std::vector<std::uint32_t> nums)) {
  Body b = start_body(which);
  Numbers n(nums);
  int steps = 0;
  while (!n.empty() && steps++ < 60) {
    Body before = b.clone();
    std::string what, why, bug;
    {
      Transaction tx(b);
      auto a = apply_random_op(b, n);
      what = a.what;
      bug = kernel_bug(a);
      tx.rollback();
    }
    if (!bug.empty()) RC_FAIL(bug);
    if (!b.equals(before, &why)) RC_FAIL("rolling back " + what + ": " + why);
    if (std::string starts = loop_starts_differ(b, before); !starts.empty()) RC_FAIL("rolling back " + what + ": " + starts);
    // Go on from a body with that operator applied for real.
    if (std::string later = kernel_bug(apply_random_op(b, n)); !later.empty()) RC_FAIL(later);
  }
}

}  // namespace
}  // namespace kintsugi
