// Polygon normals do not depend on where the polygon sits: a small face far from the
// origin gets the same normal as the same face at the origin.
#include "geometry/polygon.h"

#include <gtest/gtest.h>
#include <algorithm>
#include <limits>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

namespace kintsugi::geo {
namespace {

TEST(Polygon, UnitSquare) {
  std::vector<Vec3> sq = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  EXPECT_TRUE(polygon_normal(sq).isApprox(Vec3(0, 0, 2)));
  EXPECT_DOUBLE_EQ(polygon_area(sq), 1.0);
  std::reverse(sq.begin(), sq.end());
  EXPECT_TRUE(polygon_normal(sq).isApprox(Vec3(0, 0, -2)));
}

RC_GTEST_PROP(Polygon, NormalDoesNotDependOnWhereThePolygonIs, ()) {
  const double size = *rc::gen::element(1e-3, 0.03, 1.0);
  const double far = *rc::gen::element(0.0, 3000.0, 1e4);
  auto coord = [] { return double(*rc::gen::inRange(-1000, 1000)) / 1000.0; };
  std::vector<Vec3> local;
  for (int i = 0; i < 3; ++i) local.push_back(size * Vec3(coord(), coord(), coord()));
  const Vec3 n0 = polygon_normal(local);
  RC_PRE(n0.norm() > 1e-3 * size * size);  // not degenerate
  const Vec3 offset = far * Vec3(0.7, 0.5, 0.3);
  std::vector<Vec3> moved;
  for (const Vec3& p : local) moved.push_back(p + offset);
  const Vec3 n1 = polygon_normal(moved);
  // The only error left is rounding the moved corners, of order eps * far / size (the
  // cancellation this guards against is of order eps * (far / size)^2), times how thin the
  // triangle is: a corner moved by δ turns the normal of a triangle of twice-area |n0| and
  // sides ~size by about δ·size/|n0| (a thin one, |n0| ≈ 1e-3 size², by 1000 δ/size).
  const double thin = std::max(1.0, size * size / n0.norm());
  const double bound = 32 * std::numeric_limits<double>::epsilon() * (1 + far / size) * thin;
  RC_ASSERT((n1.normalized() - n0.normalized()).norm() < bound);
}

}  // namespace
}  // namespace kintsugi::geo
