#include "invariants/topology_check.h"
#include "tests/zoo/measure.h"
#include "zoo/zoo.h"

#include <gtest/gtest.h>

#include <chrono>

namespace kintsugi::zoo {
namespace {

TEST(Family, FaceCountsScaleAndBodiesAreValid) {
  for (std::size_t n : {10u, 37u, 100u, 1000u, 20000u}) {
    for (double rate : {0.0, 0.3, 1.0}) {
      SCOPED_TRACE("faces " + std::to_string(n) + " rate " + std::to_string(rate));
      ZooModel m = family(n, rate, 5);
      double faces = double(m.body.counts().faces);
      EXPECT_GE(faces, 0.9 * double(n));
      EXPECT_LE(faces, 1.1 * double(n));
      std::vector<Violation> v = check_topology(m.body);
      EXPECT_TRUE(v.empty()) << to_string(v[0]);
      if (n <= 1000) {
        std::vector<std::string> off = geometry_offences(m.body, m.tolerance * 1e-6);
        EXPECT_TRUE(off.empty()) << off[0];
      }
      for (const KnownDefect& d : m.defects) {
        for (const std::string& s : d.elements) EXPECT_TRUE(test::element_alive(m.body, s)) << s;
        EXPECT_LT(d.size, d.type == ProblemType::small_face || d.type == ProblemType::small_face_chain
                              ? m.tolerance * m.tolerance
                              : m.tolerance);
      }
      if (rate == 0.0) {
        EXPECT_TRUE(m.defects.empty());
      }
      if (rate == 1.0 && n >= 100) {
        EXPECT_GT(m.defects.size(), n / 8);
      }
    }
  }
}

TEST(Family, DeterministicPerSeed) {
  ZooModel a = family(500, 0.5, 11), b = family(500, 0.5, 11), c = family(500, 0.5, 12);
  std::string why;
  EXPECT_TRUE(a.body.equals(b.body, &why)) << why;
  EXPECT_EQ(a.meta(), b.meta());
  EXPECT_NE(a.meta(), c.meta());
}

TEST(Family, RefusesOutOfRange) {
  EXPECT_THROW(family(9, 0.1, 1), std::invalid_argument);
  EXPECT_THROW(family(100, 1.5, 1), std::invalid_argument);
}

}  // namespace
}  // namespace kintsugi::zoo
