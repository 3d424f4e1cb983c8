#include "geometry/curve.h"

#include "generators.h"

#include <gtest/gtest.h>
#include <algorithm>
#include <limits>
#include <rapidcheck/gtest.h>

namespace kintsugi::geo {
namespace {

using testing::gen_real;

TEST(Curve, CircleLengthAndRange) {
  const Circle c{Frame{Vec3(1, 2, 3), Vec3::UnitX(), Vec3::UnitZ()}, 2.0};
  EXPECT_NEAR(curve_length(c), 4 * kPi, 1e-14);
  // From +x to +y is a quarter turn in the circle's direction; back is three quarters.
  const ParameterRange q = parameter_range(c, Vec3(3, 2, 3), Vec3(1, 4, 3));
  EXPECT_NEAR(arc_length(c, q.t0, q.t1), kPi, 1e-14);
  const ParameterRange back = parameter_range(c, Vec3(1, 4, 3), Vec3(3, 2, 3));
  EXPECT_NEAR(arc_length(c, back.t0, back.t1), 3 * kPi, 1e-14);
  const ParameterRange full = parameter_range(c, Vec3(3, 2, 3), Vec3(3, 2, 3), 1e-9);
  EXPECT_NEAR(full.t1 - full.t0, kTwoPi, 1e-15);
}

TEST(Curve, EllipsePerimeterMatchesKnownValue) {
  // Perimeter of the ellipse a = 2, b = 1 (complete elliptic integral): 9.688448220547675...
  const Ellipse e{Frame{}, 2.0, 1.0};
  EXPECT_NEAR(curve_length(e), 9.688448220547675, 1e-12);
  // A circle as an ellipse.
  EXPECT_NEAR(curve_length(Ellipse{Frame{}, 1.5, 1.5}), 3 * kPi, 1e-12);
}

TEST(Curve, EllipseClosestPoint) {
  const Ellipse e{Frame{}, 3.0, 1.0};
  const CurvePoint p = closest_point(e, Vec3(0, 5, 0));
  EXPECT_NEAR(p.distance, 4.0, 1e-12);
  EXPECT_NEAR(p.t, kPi / 2, 1e-9);
  // On the axis: deterministic, finite.
  const CurvePoint a = closest_point(Curve(Circle{}), Vec3(0, 0, 2));
  EXPECT_TRUE(a.point.allFinite());
}

TEST(Curve, LineAndPolylineLengths) {
  const Line l{Vec3::Zero(), Vec3::UnitY()};
  EXPECT_NEAR(arc_length(l, 3.0, -2.0), 5.0, 0.0);
  EXPECT_TRUE(std::isinf(curve_length(l)));
  const Polyline p{{Vec3(0, 0, 0), Vec3(3, 0, 0), Vec3(3, 4, 0)}, 0.0};
  EXPECT_NEAR(curve_length(p), 7.0, 1e-15);
  EXPECT_TRUE(evaluate(p, 5.0).isApprox(Vec3(3, 2, 0)));
  EXPECT_TRUE(tangent(p, 5.0).isApprox(Vec3(0, 1, 0)));
  EXPECT_NEAR(arc_length(p, 1.0, 5.0), 4.0, 1e-15);
  const CurvePoint c = closest_point(p, Vec3(4, 1, 0));
  EXPECT_NEAR(c.t, 4.0, 1e-15);
  EXPECT_NEAR(c.distance, 1.0, 1e-15);
}

// A closed square's piece from the middle of one side, on past the first point, to the
// middle of the next-but-one side; an open polyline's piece forwards and backwards.
TEST(Curve, PolylinePieceRunsBetweenItsParameters) {
  Polyline sq{{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0), Vec3(0, 0, 0)}, 0.25};
  Polyline p = polyline_piece(sq, 3.5, 5.5);  // (0, 0.5) -> (0,0) -> (1,0) -> (1, 0.5)
  ASSERT_EQ(p.points.size(), 4u);
  EXPECT_TRUE(p.points[0].isApprox(Vec3(0, 0.5, 0)));
  EXPECT_TRUE(p.points[1].isApprox(Vec3(0, 0, 0)));
  EXPECT_TRUE(p.points[2].isApprox(Vec3(1, 0, 0)));
  EXPECT_TRUE(p.points[3].isApprox(Vec3(1, 0.5, 0)));
  EXPECT_EQ(p.chordal_error, 0.25);
  EXPECT_NEAR(curve_length(Curve{p}), 2.0, 1e-12);
  Polyline open{{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(3, 0, 0)}, 0};
  Polyline fwd = polyline_piece(open, 0.5, 2.5), back = polyline_piece(open, 2.5, 0.5);
  ASSERT_EQ(fwd.points.size(), 4u);
  EXPECT_TRUE(fwd.points.front().isApprox(Vec3(0.5, 0, 0)));
  EXPECT_TRUE(fwd.points.back().isApprox(Vec3(2.5, 0, 0)));
  ASSERT_EQ(back.points.size(), 4u);
  EXPECT_TRUE(back.points[1].isApprox(Vec3(2, 0, 0)));
  EXPECT_TRUE(back.points.back().isApprox(Vec3(0.5, 0, 0)));
}

TEST(Curve, SamplingRespectsChordalError) {
  const Circle c{Frame{}, 10.0};
  const std::vector<Vec3> pts = sample_curve(c, 0.0, kTwoPi, 1e-3);
  for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
    const Vec3 mid = 0.5 * (pts[i] + pts[i + 1]);
    EXPECT_LE(10.0 - mid.norm(), 1e-3);
  }
}

// Largest distance from points densely sampled on the curve to the polyline.
double polyline_error(const Curve& c, double t0, double t1, const std::vector<Vec3>& pts, int dense = 20000) {
  double worst = 0.0;
  for (int i = 0; i <= dense; ++i) {
    const Vec3 p = evaluate(c, t0 + (t1 - t0) * i / dense);
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j + 1 < pts.size(); ++j) {
      const Vec3 d = pts[j + 1] - pts[j];
      const double w = d.squaredNorm() > 0 ? std::clamp((p - pts[j]).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
      best = std::min(best, (pts[j] + w * d - p).norm());
    }
    worst = std::max(worst, best);
  }
  return worst;
}

// A flat ellipse (the section of a nearly tangent cylinder; an audit trial met this one)
// has curvature radius b²/a = 1.5e-7 at its tips and a²/b ≈ 1e9 at its sides. A uniform
// step fine enough for the tips put 2^20 points on a 2-unit arc, and triangulating the
// face behind it never ended; sampling now follows the curvature.
TEST(Curve, SamplingAFlatEllipseCostsPointsOnlyAtItsTip) {
  const Ellipse e{Frame{}, 6360.5, 0.0312323};
  for (const double eps : {0.019, 0.0097, 0.00019}) {
    const std::vector<Vec3> pts = sample_curve(e, -3.1415925594000238, -3.1151327818207828, eps);
    EXPECT_LT(pts.size(), 200u) << eps;
    EXPECT_TRUE(pts.front().isApprox(evaluate(e, -3.1415925594000238)));
    EXPECT_TRUE(pts.back().isApprox(evaluate(e, -3.1151327818207828)));
    EXPECT_LE(polyline_error(e, -3.1415925594000238, -3.1151327818207828, pts), eps) << eps;
  }
  // A span of a billion turns is bounded like any request (2^20 pieces at most).
  EXPECT_LE(sample_curve(e, 0.0, 2e9 * kTwoPi, 1e-3).size(), std::size_t((1 << 20) + 2));
  // Whole and backwards, across both tips.
  const std::vector<Vec3> whole = sample_curve(e, kTwoPi, 0.0, 1e-3);
  EXPECT_LT(whole.size(), 2000u);
  EXPECT_LE(polyline_error(e, kTwoPi, 0.0, whole, 200000), 1e-3);
}

Curve gen_curve(bool allow_line = true) {
  const Frame f = testing::gen_frame();
  switch (*rc::gen::inRange(allow_line ? 0 : 1, 4)) {
    case 0: return Line{f.origin, f.x};
    case 1: return Circle{f, gen_real(0.5, 3.0)};
    case 2: {
      const double a = gen_real(0.5, 3.0);
      return Ellipse{f, a, a * gen_real(0.2, 1.0)};
    }
    default: {
      Polyline p;
      const int n = *rc::gen::inRange(2, 8);
      for (int i = 0; i < n; ++i) p.points.push_back(testing::gen_vec(4.0));
      return p;
    }
  }
}

Curve transform(const Curve& c, const testing::Similarity& m) {
  return std::visit(
      [&](const auto& x) -> Curve {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, Line>) {
          return Line{m.point(x.origin), m.vector(x.direction)};
        } else if constexpr (std::is_same_v<T, Circle>) {
          return Circle{m.frame(x.frame), x.radius * m.scale};
        } else if constexpr (std::is_same_v<T, Ellipse>) {
          return Ellipse{m.frame(x.frame), x.major_radius * m.scale, x.minor_radius * m.scale};
        } else if constexpr (std::is_same_v<T, Polyline>) {
          Polyline p = x;
          for (Vec3& q : p.points) q = m.point(q);
          return p;
        } else {
          return x;
        }
      },
      c);
}

RC_GTEST_PROP(CurveProperty, ProjectingAProjectedPointChangesNothing, ()) {
  const Curve c = gen_curve();
  const Vec3 p = testing::gen_vec(6.0);
  const CurvePoint a = closest_point(c, p);
  const CurvePoint b = closest_point(c, a.point);
  RC_ASSERT(b.distance < 1e-9);
  RC_ASSERT((evaluate(c, a.t) - a.point).norm() < 1e-9);
}

RC_GTEST_PROP(CurveProperty, ClosestPointIsNoFartherThanSamples, ()) {
  const Curve c = gen_curve();
  const Vec3 p = testing::gen_vec(6.0);
  const CurvePoint a = closest_point(c, p);
  const double lo = std::holds_alternative<Polyline>(c) ? 0.0 : -kPi;
  const double hi = std::holds_alternative<Polyline>(c) ? curve_length(c) : kPi;
  for (int i = 0; i <= 200; ++i) RC_ASSERT(a.distance <= (evaluate(c, lo + (hi - lo) * i / 200) - p).norm() + 1e-12);
}

RC_GTEST_PROP(CurveProperty, LengthIsInvariantUnderRigidMotionAndScales, ()) {
  const Curve c = gen_curve(false);
  const auto m = testing::gen_similarity(true);
  const Curve d = transform(c, m);
  const double t0 = gen_real(-1.0, 0.0), t1 = gen_real(0.0, 2.0);
  RC_ASSERT(std::abs(curve_length(d) - m.scale * curve_length(c)) <= 1e-12 * m.scale * curve_length(c));
  // Angles are unchanged by the motion; arc-length parameters scale with it.
  const double k = std::holds_alternative<Polyline>(c) ? m.scale : 1.0;
  RC_ASSERT(std::abs(arc_length(d, t0 * k, t1 * k) - m.scale * arc_length(c, t0, t1)) <=
            1e-12 * m.scale * (1 + arc_length(c, t0, t1)));
}

RC_GTEST_PROP(CurveProperty, ArcLengthIsAdditiveAndMatchesChords, ()) {
  const Curve c = gen_curve(false);
  const double a = gen_real(-1.0, 0.0), b = gen_real(0.0, 1.0), e = gen_real(1.0, 2.0);
  RC_ASSERT(std::abs(arc_length(c, a, b) + arc_length(c, b, e) - arc_length(c, a, e)) < 1e-10);
  // Fine chords converge to the arc length from below (smooth curves: uniform samples
  // cut a polyline's corners, which is not an error of arc_length).
  if (std::holds_alternative<Polyline>(c)) return;
  double chords = 0.0;
  for (int i = 0; i < 2000; ++i) chords += (evaluate(c, a + (e - a) * (i + 1) / 2000) - evaluate(c, a + (e - a) * i / 2000)).norm();
  RC_ASSERT(chords <= arc_length(c, a, e) + 1e-9);
  RC_ASSERT(chords >= arc_length(c, a, e) * (1 - 1e-5) - 1e-9);
}

// Any ellipse, flat ones too (b/a down to 1e-6), any arc either way round, any error:
// the polyline is within the error of the curve, and its size follows the error.
RC_GTEST_PROP(CurveProperty, SampledEllipseIsWithinTheChordalError, ()) {
  const double a = gen_real(0.5, 3.0);
  const Ellipse e{testing::gen_frame(), a, a * std::pow(10.0, -gen_real(0.0, 6.0))};
  const double t0 = gen_real(-7.0, 7.0), t1 = gen_real(-7.0, 7.0);
  const double eps = a * std::pow(10.0, -gen_real(1.0, 5.0));
  const std::vector<Vec3> pts = sample_curve(e, t0, t1, eps);
  RC_ASSERT(pts.front().isApprox(evaluate(e, t0)));
  RC_ASSERT(pts.back().isApprox(evaluate(e, t1)));
  RC_LOG() << "a " << a << " b " << e.minor_radius << " t " << t0 << " " << t1 << " eps " << eps << " n " << pts.size() << "\n";
  RC_ASSERT(polyline_error(e, t0, t1, pts, 4000) <= eps * (1 + 1e-9));
  // The flat sides need few points whatever b: the count is bounded by the circle of radius a's.
  RC_ASSERT(pts.size() <= 8 + 4 * std::ceil(std::abs(t1 - t0) * std::sqrt(a / eps)));
}

}  // namespace
}  // namespace kintsugi::geo
