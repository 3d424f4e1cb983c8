// Random Euler operator sequences on the builders' solids: every operator either
// succeeds and keeps every invariant, or refuses and changes nothing, exactly when its
// query can_<op> says it would; no refusal is a postcondition (a kernel bug); rolling back
// the whole sequence restores the start. A violation aborts (the fuzzer reports it).
#include "fuzz/die.h"
#include "invariants/topology_check.h"
#include "kernel/builders.h"
#include "kernel/transaction.h"
#include "tests/support/random_ops.h"

#include <cstdio>
#include <cstdlib>

using namespace kintsugi;

using fuzz::die;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1 || size > 4096) return 0;
  Body b;
  switch (data[0] % 6) {
    case 0: b = build::box(); break;
    case 1: b = build::pyramid(build::regular_polygon(4, 1), 1); break;
    case 2: b = build::cylinder(1, 1); break;
    case 3: b = build::torus(3, 1); break;
    case 4: b = build::sphere(1); break;
    default: (void)euler::mvfs(b, geo::Vec3::Zero()); break;
  }
  Body start = b.clone();
  testing::Numbers n(data + 1, size - 1);
  {
    Transaction tx(b);
    while (!n.empty()) {
      Body before = b.clone();
      auto a = testing::apply_random_op(b, n);
      if (std::string bug = testing::kernel_bug(a); !bug.empty()) die(bug);
      if (a.query_ok != a.ok)
        die(a.what + ": can_" + a.op + " and the operator disagree: " + a.query_error + " / " + a.error);
      if (!a.ok) {
        if (!b.equals(before)) die("refused " + a.what + " changed the body");
        continue;
      }
      auto bad = check_topology(b);
      if (!bad.empty()) die(a.what + " broke " + to_string(bad.front()));
    }
    tx.rollback();
  }
  std::string why;
  if (!b.equals(start, &why)) die("rollback did not restore the start: " + why);
  if (euler::postcondition_failures() != 0) die("an operator refused with postcondition (a kernel bug)");
  return 0;
}
