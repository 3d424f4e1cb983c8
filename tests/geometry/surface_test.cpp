#include "geometry/surface.h"

#include "generators.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

namespace kintsugi::geo {
namespace {

using testing::gen_any_surface;
using testing::gen_real;
using testing::gen_vec;

// A parameter pair inside the well-behaved part of each surface's domain.
Vec2 gen_uv(const Surface& s) {
  const double u = gen_real(-3.0, 3.0);
  if (std::holds_alternative<Sphere>(s)) return Vec2(u, gen_real(-1.4, 1.4));
  if (std::holds_alternative<Torus>(s)) return Vec2(u, gen_real(-3.0, 3.0));
  if (const auto* c = std::get_if<Cone>(&s)) {
    // Stay at least 0.2 away from the apex along the generator.
    const double ta = apex_parameter(*c);
    const double off = gen_real(0.2, 3.0) * (*rc::gen::element(-1.0, 1.0));
    return Vec2(u, ta + off);
  }
  return Vec2(u, gen_real(-3.0, 3.0));
}

TEST(Surface, PlaneClosedForm) {
  const Plane p{Frame{Vec3(0, 0, 1), Vec3::UnitX(), Vec3::UnitZ()}};
  const SurfacePoint c = closest_point(p, Vec3(2, 3, 5));
  EXPECT_NEAR(c.distance, 4.0, 1e-15);
  EXPECT_TRUE(c.point.isApprox(Vec3(2, 3, 1)));
  EXPECT_TRUE(c.uv.isApprox(Vec2(2, 3)));
}

TEST(Surface, CylinderAxisPointIsNotNaN) {
  const Cylinder c{Frame{}, 2.0};
  const SurfacePoint p = closest_point(c, Vec3(0, 0, 3));
  EXPECT_TRUE(p.point.allFinite());
  EXPECT_NEAR(p.distance, -2.0, 1e-15);
  EXPECT_TRUE(p.point.isApprox(Vec3(2, 0, 3)));
}

TEST(Surface, SphereCentreAndPoles) {
  const Sphere s{Frame{}, 3.0};
  const SurfacePoint c = closest_point(s, Vec3::Zero());
  EXPECT_NEAR(c.distance, -3.0, 1e-15);
  EXPECT_TRUE(c.point.allFinite());
  const SurfacePoint n = closest_point(s, Vec3(0, 0, 7));
  EXPECT_NEAR(n.uv.y(), kPi / 2, 1e-15);
  EXPECT_NEAR(n.distance, 4.0, 1e-15);
}

TEST(Surface, TorusAxisAndCoreCircle) {
  const Torus t{Frame{}, 3.0, 1.0};
  const SurfacePoint a = closest_point(t, Vec3(0, 0, 0));
  EXPECT_NEAR(a.distance, 2.0, 1e-15);  // on the axis: the inner equator is 2 away
  const SurfacePoint core = closest_point(t, Vec3(3, 0, 0));
  EXPECT_NEAR(core.distance, -1.0, 1e-15);
  EXPECT_TRUE(core.point.allFinite());
}

TEST(Surface, ConeBothNappesAndApex) {
  const Cone c{Frame{}, 1.0, kPi / 4};  // apex at z = -1
  EXPECT_TRUE(apex(c).isApprox(Vec3(0, 0, -1)));
  // A point just beyond the apex along the axis lies inside the lower nappe.
  const SurfacePoint below = closest_point(c, Vec3(0, 0, -3));
  EXPECT_NEAR(below.distance, -2.0 / std::sqrt(2.0), 1e-12);
  // On the lower nappe the normal still points away from the axis.
  const SurfacePoint out = closest_point(c, Vec3(5, 0, -3));
  EXPECT_GT(out.distance, 0);
  EXPECT_GT(out.normal.x(), 0);
  const SurfacePoint at = closest_point(c, Vec3(0, 0, -1));
  EXPECT_NEAR(at.distance, 0.0, 1e-15);
}

TEST(Surface, ProblemsNameWhatIsWrong) {
  EXPECT_EQ(surface_problem(Cylinder{Frame{}, -1.0}), "cylinder radius must be positive, got -1");
  EXPECT_NE(surface_problem(Plane{Frame{Vec3::Zero(), Vec3(1, 1, 0), Vec3::UnitZ()}}).find("not unit"),
            std::string::npos);
  EXPECT_EQ(surface_problem(Torus{Frame{}, 2.0, 1.0}), "");
}

RC_GTEST_PROP(SurfaceProperty, EvaluatedPointIsAtDistanceZero, ()) {
  const Surface s = gen_any_surface();
  const Vec2 uv = gen_uv(s);
  const Vec3 p = evaluate(s, uv);
  RC_ASSERT(std::abs(signed_distance(s, p)) < 1e-9);
  // And projecting it returns the point itself.
  RC_ASSERT((closest_point(s, p).point - p).norm() < 1e-9);
}

RC_GTEST_PROP(SurfaceProperty, ProjectingAProjectedPointChangesNothing, ()) {
  const Surface s = gen_any_surface();
  const Vec3 p = gen_vec(8.0);
  const SurfacePoint a = closest_point(s, p);
  const SurfacePoint b = closest_point(s, a.point);
  RC_ASSERT((a.point - b.point).norm() < 1e-9);
  RC_ASSERT(std::abs(b.distance) < 1e-9);
  // The parameters reproduce the point, and the normal is unit.
  RC_ASSERT((evaluate(s, a.uv) - a.point).norm() < 1e-9);
  RC_ASSERT(std::abs(a.normal.norm() - 1.0) < 1e-12);
}

RC_GTEST_PROP(SurfaceProperty, SignedDistanceIsAlongTheNormal, ()) {
  const Surface s = gen_any_surface();
  const Vec2 uv = gen_uv(s);
  const Vec3 n = normal(s, uv);
  // Small offsets along the normal: the nearest point stays the same.
  double d = gen_real(-0.1, 0.1);
  // Inwards, stay closer than the medial axis (near a cone's apex it is close).
  if (const auto* c = std::get_if<Cone>(&s))
    d = std::min(0.1, 0.5 * std::abs(c->radius + uv.y() * std::sin(c->half_angle)) * std::cos(c->half_angle)) * (d / 0.1);
  const Vec3 p = evaluate(s, uv) + d * n;
  RC_ASSERT(std::abs(signed_distance(s, p) - d) < 1e-9);
}

RC_GTEST_PROP(SurfaceProperty, NormalIsUnitAndPerpendicularToDerivatives, ()) {
  const Surface s = gen_any_surface();
  const Vec2 uv = gen_uv(s);
  Vec3 du, dv;
  derivatives(s, uv, du, dv);
  const Vec3 n = normal(s, uv);
  RC_ASSERT(std::abs(n.norm() - 1) < 1e-12);
  RC_ASSERT(std::abs(n.dot(du)) < 1e-9 * (1 + du.norm()));
  RC_ASSERT(std::abs(n.dot(dv)) < 1e-9 * (1 + dv.norm()));
  // (du × dv) has the documented sense and length.
  const Vec3 c = du.cross(dv);
  RC_ASSERT(std::abs(c.norm() - area_element(s, uv)) < 1e-9 * (1 + c.norm()));
  RC_ASSERT(c.dot(n) >= -1e-9);
}

RC_GTEST_PROP(SurfaceProperty, DistanceIsInvariantUnderSimilarity, ()) {
  const Surface s = gen_any_surface();
  const Vec3 p = gen_vec(8.0);
  const auto m = testing::gen_similarity(true);
  const double d0 = signed_distance(s, p);
  const double d1 = signed_distance(testing::transform(s, m), m.point(p));
  RC_ASSERT(std::abs(d1 - m.scale * d0) < 1e-9 * m.scale * (1 + std::abs(d0)));
}

}  // namespace
}  // namespace kintsugi::geo
