// Defects the injector makes stay the way a scan makes them: each fitted surface within
// the tolerance of the true one. Found by the scan-parts score (tests/occt/scan_parts_test.cpp):
// a short edge at a pyramid apex whose four turned planes nearly cancelled put the apex
// several tolerances away from where the designer's planes meet.
#include "invariants/topology_check.h"
#include "kernel/builders.h"
#include "zoo/zoo.h"

#include <gtest/gtest.h>

namespace kintsugi::zoo {
namespace {

TEST(ScanLike, ShortEdgeAtAnApexKeepsTheApexWithinTheTolerance) {
  const double tol = 0.5;
  int made = 0;
  for (std::uint64_t seed = 1; seed <= 60; ++seed) {
    Body b = build::pyramid(build::regular_polygon(4, 70), 30);
    geo::Vec3 apex = geo::Vec3::Zero();
    double top = -1e300;
    for (VertexH v : b.vertices())
      if (b.point(v).z() > top) top = b.point(v).z(), apex = b.point(v);
    std::string err;
    if (!inject(b, ProblemType::short_edge, seed, std::nullopt, tol, &err)) continue;
    ++made;
    for (VertexH v : b.vertices()) {
      double d = (b.point(v) - apex).norm();
      if (d < 20) {
        EXPECT_LE(d, tol) << "seed " << seed << ": " << v.str() << " is " << d << " from the apex";
      }
    }
  }
  EXPECT_GE(made, 40) << "the injector should still find a short edge for most seeds";
}

// A pinch's block is a feature: the designer's model has it flush with the edge it nearly
// touches. inject hands that model back, built from the body before the defect.
TEST(ScanLike, PinchHandsBackTheDesignersFlushBlock) {
  Body b = build::box(100, 80, 40);
  const Counts box = b.counts();
  Body clean;
  std::string err;
  ASSERT_TRUE(inject(b, ProblemType::pinched_face, 5, std::nullopt, 0.5, &err, &clean)) << err;
  ASSERT_FALSE(clean.faces().empty()) << "no designer's model for a pinch";
  EXPECT_TRUE(check_topology(clean).empty());
  // The flush block adds its top, its two ends and its far side; the pinched block has a
  // near side of its own as well.
  EXPECT_EQ(clean.counts().faces, box.faces + 4);
  EXPECT_EQ(b.counts().faces, box.faces + 5);
  // Other types leave it alone.
  Body untouched;
  Body c = build::box(100, 80, 40);
  ASSERT_TRUE(inject(c, ProblemType::mergeable_edges, 5, std::nullopt, 0.5, &err, &untouched)) << err;
  EXPECT_TRUE(untouched.faces().empty());
}

}  // namespace
}  // namespace kintsugi::zoo
