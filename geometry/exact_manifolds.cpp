#include "geometry/exact_manifolds.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cmath>

namespace kintsugi::geo {

namespace {

using V3 = Eigen::Vector3d;

// An orthonormal basis (u, w) of the plane perpendicular to the unit vector n, built
// from the coordinate axis least aligned with n (never within 54.7° of it).
void tangent_basis(const V3& n, V3& u, V3& w) {
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(n[i]) < std::abs(n[k])) k = i;
  V3 a = V3::Zero();
  a[k] = 1.0;
  u = (a - a.dot(n) * n).normalized();
  w = n.cross(u);
}

// The length of the direction at x[0..2] and its tangent basis; false when it has none
// (zero or not finite).
bool basis_at(const double* x, double& len, V3& u, V3& w) {
  const V3 d(x[0], x[1], x[2]);
  len = d.norm();
  if (!(len > 0) || !std::isfinite(len)) return false;
  tangent_basis(d / len, u, w);
  return true;
}

bool direction_plus(const double* x, const double* delta, double* out) {
  double len;
  V3 u, w;
  if (!basis_at(x, len, u, w)) return false;
  const double step = std::hypot(delta[0], delta[1]);
  if (step == 0.0) {
    for (int i = 0; i < 3; ++i) out[i] = x[i];
    return true;
  }
  const V3 n = V3(x[0], x[1], x[2]) / len;
  // The great circle from n towards the tangent (delta[0] u + delta[1] w), an angle of
  // |delta| along it.
  const V3 t = (delta[0] * u + delta[1] * w) / step;
  const V3 y = len * (std::cos(step) * n + std::sin(step) * t);
  for (int i = 0; i < 3; ++i) out[i] = y[i];
  return true;
}

// Row-major 3x2: d Plus(x, delta) / d delta at delta = 0, written with row stride `stride`.
bool direction_plus_jacobian(const double* x, double* jac, int stride, int col) {
  double len;
  V3 u, w;
  if (!basis_at(x, len, u, w)) return false;
  for (int i = 0; i < 3; ++i) {
    jac[i * stride + col] = len * u[i];
    jac[i * stride + col + 1] = len * w[i];
  }
  return true;
}

bool direction_minus(const double* y, const double* x, double* out) {
  double lx;
  V3 u, w;
  const V3 yv(y[0], y[1], y[2]);
  const double ly = yv.norm();
  if (!basis_at(x, lx, u, w) || !(ly > 0)) return false;
  const V3 n = V3(x[0], x[1], x[2]) / lx, m = yv / ly;
  const double a = m.dot(u), b = m.dot(w), across = std::hypot(a, b);
  if (across == 0.0) {
    out[0] = out[1] = 0.0;
    return true;
  }
  const double angle = std::atan2(across, m.dot(n));
  out[0] = angle * a / across;
  out[1] = angle * b / across;
  return true;
}

// Row-major 2x3: d Minus(y, x) / d y at y = x, written with row stride `stride`.
bool direction_minus_jacobian(const double* x, double* jac, int stride, int col) {
  double len;
  V3 u, w;
  if (!basis_at(x, len, u, w)) return false;
  for (int i = 0; i < 3; ++i) {
    jac[0 * stride + col + i] = u[i] / len;
    jac[1 * stride + col + i] = w[i] / len;
  }
  return true;
}

}  // namespace

bool UnitDirectionManifold::Plus(const double* x, const double* delta, double* x_plus_delta) const {
  return direction_plus(x, delta, x_plus_delta);
}

bool UnitDirectionManifold::PlusJacobian(const double* x, double* jacobian) const {
  return direction_plus_jacobian(x, jacobian, 2, 0);
}

bool UnitDirectionManifold::Minus(const double* y, const double* x, double* y_minus_x) const {
  return direction_minus(y, x, y_minus_x);
}

bool UnitDirectionManifold::MinusJacobian(const double* x, double* jacobian) const {
  return direction_minus_jacobian(x, jacobian, 3, 0);
}

// Layout: x = (o, d); delta = (delta_o (2), delta_d (2)). The origin moves across the
// line's direction at x, in the same tangent basis as the direction.
bool AxisLineManifold::Plus(const double* x, const double* delta, double* x_plus_delta) const {
  double len;
  V3 u, w;
  if (!basis_at(x + 3, len, u, w)) return false;
  const V3 o = V3(x[0], x[1], x[2]) + delta[0] * u + delta[1] * w;
  for (int i = 0; i < 3; ++i) x_plus_delta[i] = o[i];
  return direction_plus(x + 3, delta + 2, x_plus_delta + 3);
}

bool AxisLineManifold::PlusJacobian(const double* x, double* jacobian) const {
  // Row-major 6x4: [u w 0; 0 |d|u |d|w].
  for (int i = 0; i < 24; ++i) jacobian[i] = 0.0;
  double len;
  V3 u, w;
  if (!basis_at(x + 3, len, u, w)) return false;
  for (int i = 0; i < 3; ++i) {
    jacobian[i * 4 + 0] = u[i];
    jacobian[i * 4 + 1] = w[i];
  }
  return direction_plus_jacobian(x + 3, jacobian + 3 * 4, 4, 2);
}

bool AxisLineManifold::Minus(const double* y, const double* x, double* y_minus_x) const {
  double len;
  V3 u, w;
  if (!basis_at(x + 3, len, u, w)) return false;
  const V3 step = V3(y[0], y[1], y[2]) - V3(x[0], x[1], x[2]);
  y_minus_x[0] = step.dot(u);
  y_minus_x[1] = step.dot(w);
  return direction_minus(y + 3, x + 3, y_minus_x + 2);
}

bool AxisLineManifold::MinusJacobian(const double* x, double* jacobian) const {
  // Row-major 4x6: [u^T 0; w^T 0; 0 u^T/|d|; 0 w^T/|d|].
  for (int i = 0; i < 24; ++i) jacobian[i] = 0.0;
  double len;
  V3 u, w;
  if (!basis_at(x + 3, len, u, w)) return false;
  for (int i = 0; i < 3; ++i) {
    jacobian[0 * 6 + i] = u[i];
    jacobian[1 * 6 + i] = w[i];
  }
  return direction_minus_jacobian(x + 3, jacobian + 2 * 6, 6, 3);
}

}  // namespace kintsugi::geo
