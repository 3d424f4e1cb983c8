#include "geometry/distance.h"

#include "generators.h"

#include <gtest/gtest.h>
#include <algorithm>
#include <limits>
#include <rapidcheck/gtest.h>

namespace kintsugi::geo {
namespace {

TEST(Distance, SegmentsClosedForm) {
  // Crossing segments one unit apart in z.
  const ClosestPair c = segment_segment(Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(0, -1, 1), Vec3(0, 1, 1));
  EXPECT_NEAR(c.distance, 1.0, 1e-15);
  EXPECT_NEAR(c.s, 0.5, 1e-15);
  // Parallel, overlapping: distance between the lines.
  EXPECT_NEAR(segment_segment(Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(1, 3, 0), Vec3(5, 3, 0)).distance, 3.0, 1e-15);
  // Collinear, disjoint: gap between the ends.
  EXPECT_NEAR(segment_segment(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(3, 0, 0), Vec3(4, 0, 0)).distance, 2.0, 1e-15);
  // Degenerate segments are points.
  EXPECT_NEAR(segment_segment(Vec3(0, 0, 0), Vec3(0, 0, 0), Vec3(0, 2, 0), Vec3(0, 2, 0)).distance, 2.0, 1e-15);
}

TEST(Distance, PolylinesClosedForm) {
  const std::vector<Vec3> a{Vec3(0, 0, 0), Vec3(10, 0, 0), Vec3(10, 10, 0)};
  const std::vector<Vec3> b{Vec3(5, 3, 0), Vec3(8, 1, 0), Vec3(8, 5, 0)};
  const ClosestPair c = polyline_polyline(a, b);
  EXPECT_NEAR(c.distance, 1.0, 1e-15);  // (8, 1) to the first segment
  EXPECT_NEAR(point_polyline(Vec3(11, 5, 0), a).distance, 1.0, 1e-15);
}

std::vector<Vec3> gen_polyline() {
  std::vector<Vec3> p;
  const int n = *rc::gen::inRange(1, 7);
  for (int i = 0; i < n; ++i) p.push_back(testing::gen_vec(5.0));
  return p;
}

RC_GTEST_PROP(DistanceProperty, PolylineDistanceIsNoMoreThanAnySampledPair, ()) {
  const auto a = gen_polyline(), b = gen_polyline();
  const ClosestPair c = polyline_polyline(a, b);
  RC_ASSERT(std::abs((c.on_a - c.on_b).norm() - c.distance) < 1e-12);
  RC_ASSERT(std::abs(polyline_polyline(b, a).distance - c.distance) < 1e-12);
  auto at = [](const std::vector<Vec3>& p, double w) {
    if (p.size() == 1) return p[0];
    const double x = w * (p.size() - 1);
    const std::size_t i = std::min<std::size_t>(p.size() - 2, static_cast<std::size_t>(x));
    return Vec3(p[i] + (x - i) * (p[i + 1] - p[i]));
  };
  for (int i = 0; i <= 40; ++i)
    for (int j = 0; j <= 40; ++j) RC_ASSERT(c.distance <= (at(a, i / 40.0) - at(b, j / 40.0)).norm() + 1e-12);
}

// Every pair of segments, in order: what polyline_polyline must agree with.
ClosestPair brute_force(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  ClosestPair best;
  best.distance = std::numeric_limits<double>::infinity();
  const std::size_t na = std::max<std::size_t>(1, a.size() - 1), nb = std::max<std::size_t>(1, b.size() - 1);
  for (std::size_t i = 0; i < na; ++i)
    for (std::size_t j = 0; j < nb; ++j) {
      const ClosestPair c = segment_segment(a[i], a[std::min(i + 1, a.size() - 1)], b[j], b[std::min(j + 1, b.size() - 1)]);
      if (c.distance < best.distance) best = c, best.segment_a = i, best.segment_b = j;
    }
  return best;
}

// Long polylines (runs of many segments, as sampled boundaries are): a random walk
// against a sampled helix or a copy of itself moved a little, so that the runs' boxes
// overlap in many places and ties (a copy) occur.
RC_GTEST_PROP(DistanceProperty, LongPolylinesAgreeWithEveryPair, ()) {
  std::vector<Vec3> a{testing::gen_vec(5.0)};
  const int na = *rc::gen::inRange(1, 400);
  for (int i = 0; i < na; ++i) a.push_back(a.back() + 0.2 * testing::gen_vec(1.0));
  std::vector<Vec3> b;
  if (*rc::gen::arbitrary<bool>()) {
    const Vec3 shift = testing::gen_vec(0.5);
    for (const Vec3& p : a) b.push_back(p + shift);
  } else {
    const int nb = *rc::gen::inRange(1, 400);
    const double r = testing::gen_real(0.5, 4.0);
    for (int i = 0; i <= nb; ++i) b.emplace_back(r * std::cos(0.1 * i), r * std::sin(0.1 * i), 0.02 * i);
  }
  const ClosestPair fast = polyline_polyline(a, b), all = brute_force(a, b);
  RC_ASSERT(fast.distance == all.distance);
  RC_ASSERT(fast.segment_a == all.segment_a);
  RC_ASSERT(fast.segment_b == all.segment_b);
}

RC_GTEST_PROP(DistanceProperty, InvariantUnderRigidMotionAndScales, ()) {
  const auto a = gen_polyline(), b = gen_polyline();
  const auto m = testing::gen_similarity(true);
  auto moved = [&](std::vector<Vec3> p) {
    for (Vec3& q : p) q = m.point(q);
    return p;
  };
  const double d0 = polyline_polyline(a, b).distance;
  const double d1 = polyline_polyline(moved(a), moved(b)).distance;
  RC_ASSERT(std::abs(d1 - m.scale * d0) <= 1e-9 * m.scale * (1 + d0));
  const Vec3 p = testing::gen_vec(5.0);
  RC_ASSERT(std::abs(point_polyline(m.point(p), moved(a)).distance - m.scale * point_polyline(p, a).distance) <=
            1e-9 * m.scale * (1 + d0 + p.norm()));
}

}  // namespace
}  // namespace kintsugi::geo
