// The manifolds of solved directions (geometry/exact_manifolds.h): Ceres's own manifold
// invariants at random points, and directions a hair off a coordinate axis kept as they
// are (Ceres's SphereManifold moves them onto the axis: by 1.04e-8 at a tilt of 1e-8).
#include "geometry/exact_manifolds.h"

#include "generators.h"

#include <ceres/ceres.h>
#include <ceres/manifold_test_utils.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>

namespace kintsugi::geo {
namespace {

using ceres::Vector;
// The matchers EXPECT_THAT_MANIFOLD_INVARIANTS_HOLD names unqualified.
using namespace ceres;  // NOLINT(google-build-using-namespace)
using testing::gen_real;
using testing::gen_unit;

// A unit direction: uniform on the sphere, or a coordinate axis tilted by 1e-14 to 1e-4
// rad (where Ceres's SphereManifold snaps it onto the axis).
Vector gen_direction() {
  Vec3 d;
  if (*rc::gen::inRange(0, 2) == 0) {
    d = gen_unit();
  } else {
    const int axis = *rc::gen::inRange(0, 3);
    const double sign = *rc::gen::inRange(0, 2) ? 1.0 : -1.0;
    Vec3 a = Vec3::Zero();
    a[axis] = sign;
    const double tilt = std::pow(10.0, gen_real(-14, -4));
    Vec3 across = gen_unit().cross(a);
    if (across.norm() < 1e-3) across = a.unitOrthogonal();
    d = (a + tilt * across.normalized()).normalized();
  }
  return Vector(Eigen::Vector3d(d));
}

Vector gen_tangent(int n, double extent) {
  Vector v(n);
  for (int i = 0; i < n; ++i) v[i] = gen_real(-extent, extent);
  return v;
}

RC_GTEST_PROP(ExactManifolds, UnitDirectionMeetsCeresInvariants, ()) {
  const UnitDirectionManifold manifold;
  const Vector x = gen_direction(), y = gen_direction();
  const Vector delta = gen_tangent(2, 1.0);
  EXPECT_THAT_MANIFOLD_INVARIANTS_HOLD(manifold, x, delta, y, 1e-9);
}

RC_GTEST_PROP(ExactManifolds, AxisLineMeetsCeresInvariants, ()) {
  const AxisLineManifold manifold;
  Vector x(6), y(6);
  x << gen_tangent(3, 5.0), gen_direction();
  // y: a line through a point of x's plane across d (Minus keeps only what moves the line).
  const Vector yd = gen_direction();
  Eigen::Vector3d step = gen_tangent(3, 2.0);
  const Eigen::Vector3d d = x.tail<3>();
  step -= step.dot(d) * d;
  y << x.head<3>() + step, yd;
  const Vector delta = gen_tangent(4, 1.0);
  EXPECT_THAT_MANIFOLD_INVARIANTS_HOLD(manifold, x, delta, y, 1e-9);
}

// A step of 1e-14 rad moves a direction 1e-10 rad off z by about 1e-14, not onto z.
TEST(ExactManifolds, ADirectionAHairOffAnAxisKeepsItsTilt) {
  for (double tilt : {1e-13, 1e-10, 1e-9, 1e-8}) {
    for (double sign : {1.0, -1.0}) {
      const Eigen::Vector3d x = Eigen::Vector3d(tilt, 0.3 * tilt, sign).normalized();
      const double delta[2] = {1e-14, -1e-14};
      Eigen::Vector3d out;
      ASSERT_TRUE(UnitDirectionManifold().Plus(x.data(), delta, out.data()));
      EXPECT_LT((out - x).norm(), 1e-13) << "tilt " << tilt << " sign " << sign;
      double line[6] = {1, 2, 3, x[0], x[1], x[2]}, line_out[6];
      const double line_delta[4] = {0, 0, 1e-14, 0};
      ASSERT_TRUE(AxisLineManifold().Plus(line, line_delta, line_out));
      EXPECT_LT((Eigen::Vector3d(line_out[3], line_out[4], line_out[5]) - x).norm(), 1e-13) << "tilt " << tilt;
    }
  }
}


}  // namespace
}  // namespace kintsugi::geo
