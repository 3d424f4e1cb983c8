#include "invariants/assemble.h"
#include "kernel/builders.h"
#include "kernel/euler.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <vector>

namespace kintsugi {
namespace {

TEST(Assemble, DescribeThenAssembleGivesAnEqualBody) {
  for (Body b : {build::box(), build::cylinder(1, 2), build::torus(3, 1), build::sphere(2), build::cone(1, 1),
                 build::pyramid(build::regular_polygon(7, 1), 2)}) {
    ASSERT_TRUE(euler::kev(b, b.halfedges().back()) || true);  // leave a tombstone where possible
    AssembleError err;
    auto again = assemble(describe(b), &err);
    ASSERT_TRUE(again) << err.element << ": " << err.message;
    std::string why;
    EXPECT_TRUE(again->equals(b, &why)) << why;
  }
}

// A large body's arrays are made on two threads where two may be used (kernel/assemble.cpp):
// the body is the same on one thread and on two, and equal to the one described.
TEST(Assemble, ALargeBodyIsTheSameOnOneThreadAndOnTwo) {
  const Body big = build::grid_box(30000);  // about 60,000 edges: above the two-thread size
  ASSERT_GE(big.counts().edges, 20000u);
  const char* was = std::getenv("KINTSUGI_THREADS");
  const std::string saved = was ? was : "";
  std::vector<Body> read;
  for (const char* threads : {"1", "2"}) {
    setenv("KINTSUGI_THREADS", threads, 1);
    AssembleError err;
    auto b = assemble(describe(big), &err);
    ASSERT_TRUE(b) << err.element << ": " << err.message;
    read.push_back(std::move(*b));
  }
  if (was) setenv("KINTSUGI_THREADS", saved.c_str(), 1); else unsetenv("KINTSUGI_THREADS");
  std::string why;
  EXPECT_TRUE(read[0].equals(big, &why)) << why;
  EXPECT_TRUE(read[1].equals(big, &why)) << why;
}

TEST(Assemble, OpenShellWithBorderCycle) {
  Body b = build::box();
  ASSERT_TRUE(euler::kfmb(b, b.faces()[0]));
  AssembleError err;
  auto again = assemble(describe(b), &err);
  ASSERT_TRUE(again) << err.message;
  EXPECT_EQ(again->counts().border_cycles, 1u);
}

TEST(Assemble, RefusesBrokenDescriptionsNamingTheElement) {
  BodyDescription d = describe(build::box());
  AssembleError err;
  {
    auto x = d;
    x.edges[3].he[1].next = 9999;
    EXPECT_FALSE(assemble(x, &err));
    EXPECT_EQ(err.element, "edge 3 half-edge 1");
  }
  {
    auto x = d;
    x.vertices[0].id = 4000000000u;  // would allocate without bound
    EXPECT_FALSE(assemble(x, &err));
    EXPECT_NE(err.message.find("too large"), std::string::npos);
  }
  {
    auto x = d;
    x.edges[2].he[0].next = x.edges[2].he[1].next;  // two half-edges with the same next
    EXPECT_FALSE(assemble(x, &err));
  }
  {
    auto x = d;
    std::swap(x.edges[0].he[0].origin, x.edges[0].he[1].origin);  // consistent references, broken cycles
    EXPECT_FALSE(assemble(x, &err));
    EXPECT_FALSE(err.message.empty());
  }
  {
    auto x = d;
    x.shells[0].genus = 1;  // Euler–Poincaré
    EXPECT_FALSE(assemble(x, &err));
    EXPECT_NE(err.message.find("euler_poincare"), std::string::npos);
  }
  {
    auto x = d;
    x.loops[0].first.reset();
    EXPECT_FALSE(assemble(x, &err));
    EXPECT_EQ(err.element, "loop " + std::to_string(x.loops[0].id));
  }
}

}  // namespace
}  // namespace kintsugi
