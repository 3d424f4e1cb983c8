// Analytic geometry as plain data: what the kernel stores per vertex, edge and face.
//
// The kernel depends on these types only; how they are evaluated, intersected and
// measured lives in the rest of geometry/ (surface.h, curve.h, ...), so the kernel
// does not depend on how geometry is computed.
//
// Parametrisations (also in spec/geometry.md). Every frame is right-handed:
// y = z × x, with x and z unit and orthogonal.
//   Plane     P(s,t)   = o + s·x + t·y                                 normal  z
//   Cylinder  P(θ,h)   = o + r(cosθ·x + sinθ·y) + h·z                  normal  radial, outward
//   Cone      P(θ,t)   = o + (r + t·sinα)(cosθ·x + sinθ·y) + t·cosα·z   normal  outward
//             (o is on the axis where the radius is r; α the half-angle, 0 < |α| < π/2;
//              the apex is at t = -r/sinα)
//   Sphere    P(θ,φ)   = o + r(cosφ(cosθ·x + sinθ·y) + sinφ·z)          normal  outward
//   Torus     P(θ,φ)   = o + (R + r·cosφ)(cosθ·x + sinθ·y) + r·sinφ·z   normal  outward
//   Line      C(t)     = o + t·d                    (d unit; t is arc length)
//   Circle    C(t)     = o + r(cos t·x + sin t·y)   (axis z)
//   Ellipse   C(t)     = o + a·cos t·x + b·sin t·y  (axis z; a along x, b along y)
//   Polyline  C(t)     piecewise linear through its points, t = arc length from the first
//             point; used for intersection curves without a closed form, with the chordal
//             accuracy recorded in `chordal_error`.
//
// Free-form geometry (spec/geometry.md, "Free-form geometry") is held exactly as its
// defining data, with OpenCASCADE's parametrisations; evaluation, projection and
// intersection go through the backend registered in geometry/freeform.h (OpenCASCADE's
// geometry classes in kintsugi_occt). Normals are ∂P/∂u × ∂P/∂v.
//   BSplineCurve        C(t)   (rational) B-spline, t in [first knot, last knot]
//   BSplineSurface      P(u,v) (rational) tensor-product B-spline
//   RevolutionSurface   P(u,v) = basis(v) turned by the angle u about the axis
//   ExtrusionSurface    P(u,v) = basis(u) + v·direction
//   OffsetSurface       P(u,v) = basis(u,v) + distance·n(u,v)
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>  // Vec3::cross, used by Frame::y()

#include <memory>
#include <variant>
#include <vector>

namespace kintsugi::geo {

using Vec3 = Eigen::Vector3d;
using Vec2 = Eigen::Vector2d;

// A right-handed orthonormal frame. `z` is the axis of revolution for the
// rotational types and the normal for a plane.
struct Frame {
  Vec3 origin = Vec3::Zero();
  Vec3 x = Vec3::UnitX();
  Vec3 z = Vec3::UnitZ();
  Vec3 y() const { return z.cross(x); }
  bool operator==(const Frame&) const = default;
};

struct Plane {
  Frame frame;
  bool operator==(const Plane&) const = default;
};
struct Cylinder {
  Frame frame;
  double radius = 1.0;
  bool operator==(const Cylinder&) const = default;
};
struct Cone {
  Frame frame;
  double radius = 1.0;      // radius at frame.origin
  double half_angle = 0.5;  // radians, signed: positive opens towards +z
  bool operator==(const Cone&) const = default;
};
struct Sphere {
  Frame frame;
  double radius = 1.0;
  bool operator==(const Sphere&) const = default;
};
struct Torus {
  Frame frame;
  double major_radius = 2.0;
  double minor_radius = 1.0;
  bool operator==(const Torus&) const = default;
};

// A B-spline curve's defining data (OpenCASCADE's Geom_BSplineCurve). `cache` holds the
// backend's object for it, built on first use; it is not part of the value.
struct BSplineCurve {
  int degree = 1;
  std::vector<Vec3> poles;
  std::vector<double> weights;  // empty: not rational
  std::vector<double> knots;    // distinct, increasing
  std::vector<int> multiplicities;
  bool periodic = false;
  mutable std::shared_ptr<const void> cache;
  bool operator==(const BSplineCurve& o) const {
    return degree == o.degree && poles == o.poles && weights == o.weights && knots == o.knots &&
           multiplicities == o.multiplicities && periodic == o.periodic;
  }
};

// A B-spline surface's defining data (Geom_BSplineSurface): poles[i * v_count + j] is
// pole (i, j), i along u.
struct BSplineSurface {
  int u_degree = 1, v_degree = 1;
  int u_count = 0, v_count = 0;
  std::vector<Vec3> poles;
  std::vector<double> weights;  // empty: not rational; else u_count × v_count like poles
  std::vector<double> u_knots, v_knots;
  std::vector<int> u_multiplicities, v_multiplicities;
  bool u_periodic = false, v_periodic = false;
  mutable std::shared_ptr<const void> cache;
  bool operator==(const BSplineSurface& o) const {
    return u_degree == o.u_degree && v_degree == o.v_degree && u_count == o.u_count && v_count == o.v_count &&
           poles == o.poles && weights == o.weights && u_knots == o.u_knots && v_knots == o.v_knots &&
           u_multiplicities == o.u_multiplicities && v_multiplicities == o.v_multiplicities &&
           u_periodic == o.u_periodic && v_periodic == o.v_periodic;
  }
};

// Surface of revolution (Geom_SurfaceOfRevolution): the basis curve turned about the
// axis through `origin` along `axis` (unit); u is the angle (period 2π).
struct RevolutionSurface {
  BSplineCurve basis;
  Vec3 origin = Vec3::Zero();
  Vec3 axis = Vec3::UnitZ();
  mutable std::shared_ptr<const void> cache;
  bool operator==(const RevolutionSurface& o) const { return basis == o.basis && origin == o.origin && axis == o.axis; }
};

// Surface of linear extrusion (Geom_SurfaceOfLinearExtrusion): the basis curve swept
// along `direction` (unit).
struct ExtrusionSurface {
  BSplineCurve basis;
  Vec3 direction = Vec3::UnitZ();
  mutable std::shared_ptr<const void> cache;
  bool operator==(const ExtrusionSurface& o) const { return basis == o.basis && direction == o.direction; }
};

// Offset surface (Geom_OffsetSurface) of a B-spline surface (any other basis is written
// as its exact B-spline form when read).
struct OffsetSurface {
  BSplineSurface basis;
  double distance = 0.0;
  mutable std::shared_ptr<const void> cache;
  bool operator==(const OffsetSurface& o) const { return basis == o.basis && distance == o.distance; }
};

// std::monostate: no surface attached yet (e.g. a face made by an operator inside a
// repair, before the repair assigns its geometry).
using Surface = std::variant<std::monostate, Plane, Cylinder, Cone, Sphere, Torus, BSplineSurface, RevolutionSurface,
                             ExtrusionSurface, OffsetSurface>;

struct Line {
  Vec3 origin = Vec3::Zero();
  Vec3 direction = Vec3::UnitX();
  bool operator==(const Line&) const = default;
};
struct Circle {
  Frame frame;
  double radius = 1.0;
  bool operator==(const Circle&) const = default;
};
struct Ellipse {
  Frame frame;
  double major_radius = 2.0;  // along frame.x
  double minor_radius = 1.0;  // along frame.y
  bool operator==(const Ellipse&) const = default;
};
struct Polyline {
  std::vector<Vec3> points;
  double chordal_error = 0.0;  // largest distance from the true curve, when known
  bool operator==(const Polyline&) const = default;
};

// std::monostate: no curve attached yet.
using Curve = std::variant<std::monostate, Line, Circle, Ellipse, Polyline, BSplineCurve>;

// Whether the geometry is free-form (needs the backend of geometry/freeform.h).
bool is_freeform(const Surface& s);
bool is_freeform(const Curve& c);
// Where the free-form backend keeps a surface's evaluation state (its `cache`, shared by
// copies of the data); nullptr for an analytic surface.
std::shared_ptr<const void>* cache_slot(const Surface& s);

// Names used in files, reports and messages.
const char* surface_type_name(const Surface& s);
const char* curve_type_name(const Curve& c);

}  // namespace kintsugi::geo
