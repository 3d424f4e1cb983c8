// Manifolds for the unit directions of solved surfaces (a plane's normal, a torus's axis,
// a cylinder's or cone's axis line), exact near every direction.
//
// Ceres's SphereManifold and LineManifold (2.1) map the tangent space through a
// Householder reflection of the current direction x onto the last coordinate axis, and
// when x's other coordinates are below sqrt(machine epsilon) (x within 1.5e-8 rad of ±z)
// they take the reflection to be the identity: every Plus, even of a zero step, snaps x
// onto the axis. A plane at unit distance from the origin tilted by less than that moves
// by up to 1.5e-8 on each step — the modelling precision itself on a model of unit size
// — so a solve that needs a plane normal to z tilted by 1e-8 (a boss's base meeting a
// rezipped side, Beautify.InjectedDefectsOfTypes7To11AreRepaired) rejects every step and
// stops 1.005 precisions short. These take the tangent basis from the coordinate axis
// least aligned with x instead, which is well conditioned for every x.
#pragma once

#include <ceres/manifold.h>

namespace kintsugi::geo {

// Directions in R³ of any fixed length (a Plus keeps |x|): tangent size 2.
class UnitDirectionManifold final : public ceres::Manifold {
 public:
  int AmbientSize() const override { return 3; }
  int TangentSize() const override { return 2; }
  bool Plus(const double* x, const double* delta, double* x_plus_delta) const override;
  bool PlusJacobian(const double* x, double* jacobian) const override;
  bool Minus(const double* y, const double* x, double* y_minus_x) const override;
  bool MinusJacobian(const double* x, double* jacobian) const override;
};

// A line in R³ as (origin o, direction d): the direction moves as above, the origin only
// across the direction (moving it along the line is no change of the line). Tangent
// size 4: two for the origin, two for the direction.
class AxisLineManifold final : public ceres::Manifold {
 public:
  int AmbientSize() const override { return 6; }
  int TangentSize() const override { return 4; }
  bool Plus(const double* x, const double* delta, double* x_plus_delta) const override;
  bool PlusJacobian(const double* x, double* jacobian) const override;
  bool Minus(const double* y, const double* x, double* y_minus_x) const override;
  bool MinusJacobian(const double* x, double* jacobian) const override;
};

}  // namespace kintsugi::geo
