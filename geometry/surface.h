// Evaluation and projection on the five analytic surfaces (parametrisations and
// normal senses: geometry/types.h and spec/geometry.md).
//
// Parameters are (u, v) = (s, t) for a plane, (θ, h) for a cylinder, (θ, t) for a cone,
// (θ, φ) for a sphere and torus. Angles returned by `closest_point`/`parameters` are
// in (-π, π]; callers that walk along a curve unwrap them (see area.cpp).
//
// Degenerate projections are resolved deterministically, never with NaN:
//   point on a cylinder/cone/torus axis -> θ = 0 (the frame's x direction);
//   sphere centre                        -> (θ, φ) = (0, 0);
//   point on the torus core circle        -> φ = 0;
//   beyond the cone apex                  -> the nearest point of the double cone
//                                            (both nappes belong to the surface).
//
// Calling any of these on std::monostate (no geometry) is a programming error and
// throws std::invalid_argument.
#pragma once

#include "geometry/types.h"

#include <string>

namespace kintsugi::geo {

struct SurfacePoint {
  Vec3 point = Vec3::Zero();   // the nearest point on the surface
  Vec2 uv = Vec2::Zero();      // its parameters
  double distance = 0.0;       // signed: positive on the normal side
  Vec3 normal = Vec3::UnitZ(); // unit surface normal at `point`
};

Vec3 evaluate(const Surface& s, const Vec2& uv);
// Unit normal, in the documented sense. At a cone apex: the limit from the
// positive-radius nappe; at a sphere pole: ±z (well defined there).
Vec3 normal(const Surface& s, const Vec2& uv);
// First derivatives ∂P/∂u, ∂P/∂v.
void derivatives(const Surface& s, const Vec2& uv, Vec3& du, Vec3& dv);
// |∂P/∂u × ∂P/∂v|, the area element, in closed form.
double area_element(const Surface& s, const Vec2& uv);

SurfacePoint closest_point(const Surface& s, const Vec3& p);
double signed_distance(const Surface& s, const Vec3& p);
Vec2 parameters(const Surface& s, const Vec3& p);

// Whether u (resp. v) is an angle with period 2π.
bool periodic_u(const Surface& s);
bool periodic_v(const Surface& s);

// The cone apex (on the axis, where the radius is zero).
Vec3 apex(const Cone& c);
// The cone's v-parameter of the apex, t = -r / sin α.
double apex_parameter(const Cone& c);

// Empty when the surface's data are usable, otherwise a sentence naming what is wrong
// (e.g. "cylinder radius must be positive, got -1").
std::string surface_problem(const Surface& s);

// A characteristic size of the surface (its radius; 0 for a plane), used to make
// internal thresholds scale with the model.
double surface_scale(const Surface& s);

}  // namespace kintsugi::geo
