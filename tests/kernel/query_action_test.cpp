// Operators as query/action pairs (kernel/euler.h): over random bodies and random
// arguments (tests/support/random_ops.h, which asks can_<op> before running <op>),
//   * can_<op> says yes exactly when <op> succeeds, for every operator;
//   * a successful operator changes V, E, F, L, S, B, R, H by its Δ in
//     kernel/operator_list.h (or its variant's);
//   * no operator refuses with postcondition, directly or inside the builders.
#include "kernel/builders.h"
#include "kernel/operator_list.h"
#include "tests/support/random_ops.h"

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <set>

namespace kintsugi {
namespace {

using testing::apply_random_op;
using testing::kernel_bug;
using testing::Numbers;

Body start_body(int which) {
  switch (which % 7) {
    case 0: return build::box();
    case 1: return build::pyramid(build::regular_polygon(5, 1), 1);
    case 2: return build::cylinder(1, 2);
    case 3: return build::torus(3, 1);
    case 4: return build::sphere(1);
    case 5: {
      Body b = build::box();
      (void)euler::kfmb(b, b.faces()[0]);  // an open shell, so border cycles take part
      return b;
    }
    default: {
      Body b;
      (void)euler::mvfs(b, geo::Vec3::Zero());
      return b;
    }
  }
}

CountDelta all_counts(const Body& b) {
  Counts c = b.counts();
  CountDelta d{int(c.vertices), int(c.edges), int(c.faces), int(c.loops), int(c.shells), int(c.border_cycles), 0, 0};
  for (FaceH f : b.faces()) d.r += int(b.rings_of(f).size());
  for (ShellH s : b.shells()) d.h += int(b.shell_genus(s));
  return d;
}

CountDelta minus(const CountDelta& a, const CountDelta& b) {
  return {a.v - b.v, a.e - b.e, a.f - b.f, a.l - b.l, a.s - b.s, a.b - b.b, a.r - b.r, a.h - b.h};
}

std::string str(const CountDelta& d) {
  return "V" + std::to_string(d.v) + " E" + std::to_string(d.e) + " F" + std::to_string(d.f) + " L" +
         std::to_string(d.l) + " S" + std::to_string(d.s) + " B" + std::to_string(d.b) + " R" +
         std::to_string(d.r) + " H" + std::to_string(d.h);
}

RC_GTEST_PROP(QueryAction, QuerySaysYesExactlyWhenTheOperatorSucceeds, ()) {
  const std::uint64_t bugs_before = euler::postcondition_failures();
  const int which = *rc::gen::inRange(0, 7);
  // Long streams: most operators need a few steps of history before they can apply.
  const auto nums = *rc::gen::container<std::vector<std::uint32_t>>(320, rc::gen::arbitrary<std::uint32_t>());
  Body b = start_body(which);
  Numbers n(nums);
  int steps = 0;
  while (!n.empty() && steps++ < 80) {
    CountDelta before = all_counts(b);
    auto a = apply_random_op(b, n);
    if (a.op.empty()) continue;
    if (std::string bug = kernel_bug(a); !bug.empty()) RC_FAIL(bug);
    if (a.query_ok != a.ok)
      RC_FAIL(a.what + ": can_" + a.op + " said " + (a.query_ok ? "yes" : "no (" + a.query_error + ")") +
              " but the operator " + (a.ok ? "succeeded" : "refused: " + a.error));
    if (!a.ok) continue;
    const OperatorInfo* info = find_operator(a.op);
    RC_ASSERT(info != nullptr);
    CountDelta d = minus(all_counts(b), before);
    if (!(d == info->delta) && !(info->has_variant && d == info->variant))
      RC_FAIL(a.what + " changed the counts by " + str(d) + " but kernel/operator_list.h says " + str(info->delta));
  }
  RC_ASSERT(euler::postcondition_failures() == bugs_before);
}

// Every exported operator is reached by the random operators, both ways (else the
// property above proves nothing about it). Deterministic: a fixed stream of numbers.
TEST(QueryAction, RandomOperatorsReachEveryOperatorBothWays) {
  std::set<std::string> ok, refused;
  std::uint32_t seed = 12345;
  for (int run = 0; run < 400; ++run) {
    std::vector<std::uint32_t> nums;
    for (int i = 0; i < 400; ++i) {
      seed = seed * 1664525u + 1013904223u;
      nums.push_back(seed >> 8);
    }
    Body b = start_body(run);
    Numbers n(nums);
    for (int step = 0; step < 80 && !n.empty(); ++step) {
      auto a = apply_random_op(b, n);
      if (a.op.empty()) continue;
      EXPECT_EQ(a.query_ok, a.ok) << a.what << ": " << a.query_error << " / " << a.error;
      (a.ok ? ok : refused).insert(a.op);
    }
  }
  for (const auto& op : kOperators) {
    EXPECT_TRUE(ok.count(std::string(op.name))) << op.name << " never succeeded";
    if (op.name != "mvfs") {  // mvfs has no precondition
      EXPECT_TRUE(refused.count(std::string(op.name))) << op.name << " never refused";
    }
  }
}

TEST(QueryAction, QueryChangesNothingAndNamesTheReason) {
  Body b = build::box();
  Body before = b.clone();
  auto why = euler::can_kvfs(b, b.faces()[0]);
  ASSERT_TRUE(why);
  EXPECT_EQ(why->code, ErrorCode::not_lone);
  auto r = euler::kvfs(b, b.faces()[0]);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, why->code);
  EXPECT_EQ(r.error().message, why->message);
  EXPECT_TRUE(b.equals(before));
  EXPECT_FALSE(euler::can_kev(b, HalfedgeH(9999)).value().message.empty());
  EXPECT_FALSE(euler::can_mef(b, Corner::before(b.halfedges()[0]), Corner::before(b.halfedges()[0])).has_value());
}

}  // namespace
}  // namespace kintsugi
