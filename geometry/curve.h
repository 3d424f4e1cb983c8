// Evaluation, projection and length on the four curve types (parametrisations:
// geometry/types.h). Line and polyline parameters are arc length; circle and ellipse
// parameters are angles, with t returned in (-π, π].
//
// Degenerate projections are resolved deterministically: a point on a circle's or
// ellipse's axis projects to t = 0. Calling these on std::monostate throws
// std::invalid_argument.
#pragma once

#include "geometry/types.h"

#include <vector>

namespace kintsugi::geo {

struct CurvePoint {
  Vec3 point = Vec3::Zero();
  double t = 0.0;
  double distance = 0.0;  // |p - point|
};

Vec3 evaluate(const Curve& c, double t);
// Unit tangent in the direction of increasing t. At a polyline vertex: the direction of
// the segment that starts there (the last segment at the end).
Vec3 tangent(const Curve& c, double t);
CurvePoint closest_point(const Curve& c, const Vec3& p);
double parameter(const Curve& c, const Vec3& p);

// Closed: circle, ellipse, and a polyline whose last point equals its first.
bool is_closed(const Curve& c);
// 2π for circle and ellipse, the length for a closed polyline, 0 otherwise.
double period(const Curve& c);

struct ParameterRange {
  double t0 = 0.0, t1 = 0.0;
};
// Parameters of p0 and p1 (projected onto the curve). On a closed curve t1 is moved into
// (t0, t0 + period], i.e. the range runs from p0 to p1 in the curve's direction; when
// |p0 - p1| <= coincide_tol the range is the full period (a closed edge with one vertex).
// On an open curve t1 may be less than t0 (an edge running against the curve).
ParameterRange parameter_range(const Curve& c, const Vec3& p0, const Vec3& p1, double coincide_tol = 0.0);

// Length of the curve between t0 and t1 (order does not matter; not reduced modulo the
// period). Closed form for line and circle, exact for a polyline, Gauss-Legendre
// quadrature for an ellipse (relative error below 1e-12 for b/a > 1e-3).
double arc_length(const Curve& c, double t0, double t1);
// Whole length; +infinity for a line.
double curve_length(const Curve& c);

// The piece of p between arc lengths t0 and t1, as a polyline of its own from p(t0) to
// p(t1) (the chordal error kept). On a closed polyline t1 may lie up to one length past
// t0: the piece runs on through the first point. t1 < t0 on an open one: the piece runs
// backwards. An edge's polyline is the edge's own piece: the writer takes a polyline
// whole, from its first point to its last.
Polyline polyline_piece(const Polyline& p, double t0, double t1);

// Points along [t0, t1] (in that order, both ends included) such that the polyline
// through them is within `chordal_error` of the curve (at most 2^20 pieces, which is
// within 5e-12 of a full circle's radius: a tighter error is not met). Circles are
// sampled uniformly; an ellipse's pieces are as long as its local curvature allows, so a
// flat ellipse costs points only round its tips.
std::vector<Vec3> sample_curve(const Curve& c, double t0, double t1, double chordal_error);

}  // namespace kintsugi::geo
