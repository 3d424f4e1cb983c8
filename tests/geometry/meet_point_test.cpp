#include "tests/support/analytic_surface.h"
#include "geometry/meet_point.h"

#include "geometry/frame.h"
#include "geometry/surface.h"
#include "generators.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

namespace kintsugi::geo {
namespace {

Plane plane(const Vec3& o, const Vec3& n) { return Plane{frame_from_axis(o, n)}; }

TEST(MeetPoint, ThreePlanesExact) {
  const MeetPoint m = meet_point({plane(Vec3(1, 0, 0), Vec3::UnitX()), plane(Vec3(0, 2, 0), Vec3::UnitY()),
                                  plane(Vec3(0, 0, 3), Vec3(0, 0.1, 1))},
                                 Vec3::Zero(), 1e-3, 1e-9);
  EXPECT_EQ(m.status, MeetStatus::exact);
  EXPECT_LT(m.residual, 1e-12);
  EXPECT_NEAR(m.point.x(), 1.0, 1e-12);
  EXPECT_NEAR(m.point.y(), 2.0, 1e-12);
}

TEST(MeetPoint, ParallelPlanesAreDegenerate) {
  const MeetPoint m = meet_point({plane(Vec3(0, 0, 0), Vec3::UnitZ()), plane(Vec3(0, 0, 1), Vec3::UnitZ()),
                                  plane(Vec3::Zero(), Vec3::UnitX())},
                                 Vec3::Zero(), 1e-3, 1e-9);
  EXPECT_EQ(m.status, MeetStatus::degenerate);
  EXPECT_NE(m.problem.find("parallel"), std::string::npos);
  // Two planes meet in a line: the point nearest the guess.
  const MeetPoint u = meet_point({plane(Vec3::Zero(), Vec3::UnitZ()), plane(Vec3::Zero(), Vec3::UnitX())},
                                 Vec3(3, 4, 5), 1e-3, 1e-9);
  EXPECT_EQ(u.status, MeetStatus::underdetermined);
  EXPECT_TRUE(u.point.isApprox(Vec3(0, 4, 0)));
}

TEST(MeetPoint, CurvedSurfacesAndFourPlanes) {
  // Cylinder x² + y² = 4, plane z = 1, plane y = 0: the point (2, 0, 1) (nearest the guess).
  const MeetPoint m = meet_point({Cylinder{Frame{}, 2.0}, plane(Vec3(0, 0, 1), Vec3::UnitZ()),
                                  plane(Vec3::Zero(), Vec3::UnitY())},
                                 Vec3(1.5, 0.3, 0.8), 1e-3, 1e-9);
  EXPECT_EQ(m.status, MeetStatus::least_squares);
  EXPECT_TRUE(m.point.isApprox(Vec3(2, 0, 1), 1e-9));
  // Four planes of a corner, one off by 0.01: no point within 1e-3, but within 0.1.
  const std::vector<Surface> four{plane(Vec3::Zero(), Vec3::UnitX()), plane(Vec3::Zero(), Vec3::UnitY()),
                                  plane(Vec3::Zero(), Vec3::UnitZ()), plane(Vec3(0.01, 0, 0), Vec3(1, 1, 1))};
  const MeetPoint off = meet_point(four, Vec3(0.5, 0.5, 0.5), 1e-3, 1e-9);
  EXPECT_EQ(off.status, MeetStatus::no_point);
  EXPECT_NE(off.problem.find("within tolerance"), std::string::npos);
  EXPECT_EQ(meet_point(four, Vec3(0.5, 0.5, 0.5), 0.1, 1e-9).status, MeetStatus::least_squares);
}

TEST(MeetPoint, CurvedSurfacesMeetingInACurveGiveThePointNearTheGuess) {
  // Sphere |x| = 2 and plane z = 1 meet in a circle of radius √3; from a guess in the plane
  // y = 0 the point stays in it (nothing pulls it sideways) and is the circle's point on
  // the guess's side, not some other point of the circle.
  const MeetPoint m = meet_point({Sphere{Frame{}, 2.0}, plane(Vec3(0, 0, 1), Vec3::UnitZ())}, Vec3(3, 0, 5), 1e-3, 1e-9);
  EXPECT_EQ(m.status, MeetStatus::underdetermined);
  EXPECT_LT(m.residual, 1e-9);
  EXPECT_NEAR(m.point.y(), 0.0, 1e-9);
  EXPECT_NEAR(m.point.x(), std::sqrt(3.0), 1e-6);
  EXPECT_NEAR(m.point.z(), 1.0, 1e-9);
}

RC_GTEST_PROP(MeetPointProperty, FindsAPointOnThreeSurfacesThroughIt, ()) {
  // Three random surfaces forced through a common point p: the solver lands on all three.
  const Vec3 p = testing::gen_vec(3.0);
  std::vector<Surface> s;
  for (int i = 0; i < 3; ++i) {
    Surface x = testing::gen_any_surface();
    // Translate the surface so it passes through p.
    const SurfacePoint c = closest_point(x, p);
    std::visit([&](auto& y) {
      if constexpr (kintsugi::geo::kAnalyticSurface<std::decay_t<decltype(y)>>) y.frame.origin += p - c.point;
    }, x);
    s.push_back(x);
  }
  const MeetPoint m = meet_point(s, p + testing::gen_vec(0.01), 1e-6, 1e-12);
  RC_ASSERT(m.status != MeetStatus::no_point);
  RC_ASSERT(m.status != MeetStatus::degenerate);
  RC_ASSERT(m.residual <= 1e-6);
}

}  // namespace
}  // namespace kintsugi::geo
