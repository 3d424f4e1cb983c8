// Small helpers on frames and angles shared by the geometry code.
#pragma once

#include "geometry/types.h"

#include <cmath>
#include <numbers>
#include <string>

namespace kintsugi::geo {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kTwoPi = 2.0 * std::numbers::pi;

// Point of the frame's local coordinates (a, b, c) = origin + a·x + b·y + c·z.
inline Vec3 frame_point(const Frame& f, double a, double b, double c) {
  return f.origin + a * f.x + b * f.y() + c * f.z;
}
// Local coordinates of a world point.
inline Vec3 to_local(const Frame& f, const Vec3& p) {
  const Vec3 q = p - f.origin;
  return Vec3(q.dot(f.x), q.dot(f.y()), q.dot(f.z));
}
// Unit radial direction cosθ·x + sinθ·y.
inline Vec3 radial(const Frame& f, double theta) { return std::cos(theta) * f.x + std::sin(theta) * f.y(); }

// Angle wrapped into (-π, π].
inline double wrap_angle(double a) {
  a = std::remainder(a, kTwoPi);  // in [-π, π]
  return a <= -kPi ? a + kTwoPi : a;
}

// A right-handed frame with the given origin and axis; x is any unit vector
// perpendicular to the axis (the one closest to `hint` when given).
Frame frame_from_axis(const Vec3& origin, const Vec3& axis, const Vec3& hint = Vec3::Zero());

// Empty when the frame is orthonormal to within `eps`, otherwise what is wrong.
std::string frame_problem(const Frame& f, double eps = 1e-9);

}  // namespace kintsugi::geo
