#include "geometry/surface.h"

#include "geometry/frame.h"
#include "geometry/freeform.h"
#include "geometry/overload.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace kintsugi::geo {

namespace {

[[noreturn]] void no_geometry() { throw std::invalid_argument("surface has no geometry (monostate)"); }

// Polar decomposition of a point about a frame's z axis: height along z, distance ρ
// from the axis, angle β of the radial direction (0 on the axis, by convention).
struct Polar {
  double height, rho, beta;
};
Polar polar(const Frame& f, const Vec3& p) {
  const Vec3 l = to_local(f, p);
  const double rho = std::hypot(l.x(), l.y());
  // Below this the radial direction is noise; take the frame's x (documented).
  const double tiny = 1e-300;
  return {l.z(), rho, rho > tiny ? std::atan2(l.y(), l.x()) : 0.0};
}

double cone_radius_at(const Cone& c, double t) { return c.radius + t * std::sin(c.half_angle); }

SurfacePoint closest_plane(const Plane& s, const Vec3& p) {
  const Vec3 l = to_local(s.frame, p);
  return {p - l.z() * s.frame.z, Vec2(l.x(), l.y()), l.z(), s.frame.z};
}

SurfacePoint closest_cylinder(const Cylinder& s, const Vec3& p) {
  const Polar q = polar(s.frame, p);
  const Vec3 e = radial(s.frame, q.beta);
  return {s.frame.origin + q.height * s.frame.z + s.radius * e, Vec2(q.beta, q.height), q.rho - s.radius, e};
}

SurfacePoint closest_cone(const Cone& s, const Vec3& p) {
  // In the meridian half-plane through p the double cone is a V with its vertex at
  // the apex: branch 1 is the generator at θ = β (radius r + t sinα ≥ 0), branch 2 the
  // generator at θ = β + π (radius ≤ 0, i.e. the other nappe seen from this side).
  // Points in the opposite half-plane are never nearer, so these two suffice.
  const Polar q = polar(s.frame, p);
  const double sa = std::sin(s.half_angle), ca = std::cos(s.half_angle);
  const double ta = apex_parameter(s);
  auto clamp_branch = [&](double t, bool positive_radius) {
    const bool ok = positive_radius ? cone_radius_at(s, t) >= 0 : cone_radius_at(s, t) <= 0;
    return ok ? t : ta;
  };
  // Foot of (ρ, z) on branch 1: line through (r, 0) with direction (sinα, cosα).
  const double t1 = clamp_branch((q.rho - s.radius) * sa + q.height * ca, true);
  // Branch 2: points (-(r + t sinα), t cosα), line through (-r, 0), direction (-sinα, cosα).
  const double t2 = clamp_branch(-(q.rho + s.radius) * sa + q.height * ca, false);
  auto dist2 = [&](double t, double sign) {
    const double dr = q.rho - sign * cone_radius_at(s, t), dz = q.height - t * ca;
    return dr * dr + dz * dz;
  };
  const double d1 = dist2(t1, 1.0), d2 = dist2(t2, -1.0);
  const bool first = d1 <= d2;
  const double t = first ? t1 : t2;
  const double theta = first ? q.beta : wrap_angle(q.beta + kPi);
  SurfacePoint out;
  out.uv = Vec2(theta, t);
  out.point = evaluate(s, out.uv);
  out.normal = normal(s, out.uv);
  // Outside (away from the axis) is positive on both nappes.
  const double profile = std::abs(s.radius + q.height * std::tan(s.half_angle));
  const double mag = std::sqrt(first ? d1 : d2);
  out.distance = q.rho >= profile ? mag : -mag;
  return out;
}

SurfacePoint closest_sphere(const Sphere& s, const Vec3& p) {
  const Vec3 l = to_local(s.frame, p);
  const double len = l.norm();
  SurfacePoint out;
  if (len <= 1e-300) {  // the centre: every point is nearest; take (0, 0) (documented)
    out.uv = Vec2(0, 0);
  } else {
    const double rho = std::hypot(l.x(), l.y());
    out.uv = Vec2(rho > 1e-300 ? std::atan2(l.y(), l.x()) : 0.0, std::atan2(l.z(), rho));
  }
  out.normal = normal(s, out.uv);
  out.point = s.frame.origin + s.radius * out.normal;
  out.distance = len - s.radius;
  return out;
}

SurfacePoint closest_torus(const Torus& s, const Vec3& p) {
  // Two candidate tube circles in the meridian plane through p: the one on p's side
  // (θ = β) and, for a spindle torus (r > R), the opposite one (θ = β + π) may be nearer.
  const Polar q = polar(s.frame, p);
  struct Candidate {
    double theta, phi, dist;
  };
  auto candidate = [&](double theta, double rho_in_frame) {
    const double dr = rho_in_frame - s.major_radius, dz = q.height;
    const double len = std::hypot(dr, dz);
    const double phi = len > 1e-300 ? std::atan2(dz, dr) : 0.0;  // core circle: φ = 0
    return Candidate{theta, phi, len - s.minor_radius};
  };
  const Candidate a = candidate(q.beta, q.rho);
  const Candidate b = candidate(wrap_angle(q.beta + kPi), -q.rho);
  const Candidate& c = std::abs(a.dist) <= std::abs(b.dist) ? a : b;
  SurfacePoint out;
  out.uv = Vec2(c.theta, c.phi);
  out.point = evaluate(s, out.uv);
  out.normal = normal(s, out.uv);
  out.distance = c.dist;
  return out;
}

// Free-form surfaces: through the backend (geometry/freeform.h).
Vec3 ff_point(const Surface& s, const Vec2& uv, Vec3* du = nullptr, Vec3* dv = nullptr) {
  Vec3 a, b;
  Vec3 p = require_freeform().surface_d1(s, uv, du ? du : &a, dv ? dv : &b);
  return p;
}
Vec3 ff_normal(const Surface& s, const Vec2& uv) {
  Vec3 du, dv;
  ff_point(s, uv, &du, &dv);
  Vec3 n = du.cross(dv);
  const double len = n.norm();
  if (len > 0) return n / len;
  // Degenerate point (a pole of the parametrisation): the normal a little inside.
  double u0, u1, v0, v1;
  require_freeform().surface_bounds(s, &u0, &u1, &v0, &v1);
  const double hu = 1e-7 * (std::isfinite(u1 - u0) ? u1 - u0 : 1.0), hv = 1e-7 * (std::isfinite(v1 - v0) ? v1 - v0 : 1.0);
  Vec2 q(uv.x() + (uv.x() + hu <= u1 ? hu : -hu), uv.y() + (uv.y() + hv <= v1 ? hv : -hv));
  ff_point(s, q, &du, &dv);
  n = du.cross(dv);
  return n.norm() > 0 ? Vec3(n.normalized()) : Vec3::UnitZ();
}
SurfacePoint ff_closest(const Surface& s, const Vec3& p) {
  SurfacePoint out;
  out.uv = require_freeform().surface_project(s, p);
  out.point = ff_point(s, out.uv);
  out.normal = ff_normal(s, out.uv);
  const Vec3 d = p - out.point;
  out.distance = d.dot(out.normal) >= 0 ? d.norm() : -d.norm();
  return out;
}

}  // namespace

Vec3 apex(const Cone& c) { return c.frame.origin + apex_parameter(c) * std::cos(c.half_angle) * c.frame.z; }
double apex_parameter(const Cone& c) { return -c.radius / std::sin(c.half_angle); }

Vec3 evaluate(const Surface& s, const Vec2& uv) {
  const double u = uv.x(), v = uv.y();
  return std::visit(
      detail::Overload{
          [&](const std::monostate&) -> Vec3 { no_geometry(); },
          [&](const Plane& p) -> Vec3 { return frame_point(p.frame, u, v, 0); },
          [&](const Cylinder& c) -> Vec3 {
            return c.frame.origin + c.radius * radial(c.frame, u) + v * c.frame.z;
          },
          [&](const Cone& c) -> Vec3 {
            return c.frame.origin + cone_radius_at(c, v) * radial(c.frame, u) +
                   v * std::cos(c.half_angle) * c.frame.z;
          },
          [&](const Sphere& c) -> Vec3 {
            return c.frame.origin +
                   c.radius * (std::cos(v) * radial(c.frame, u) + std::sin(v) * c.frame.z);
          },
          [&](const Torus& c) -> Vec3 {
            return c.frame.origin + (c.major_radius + c.minor_radius * std::cos(v)) * radial(c.frame, u) +
                   c.minor_radius * std::sin(v) * c.frame.z;
          },
          [&](const auto&) -> Vec3 { return ff_point(s, uv); }},
      s);
}

Vec3 normal(const Surface& s, const Vec2& uv) {
  const double u = uv.x(), v = uv.y();
  return std::visit(
      detail::Overload{
          [&](const std::monostate&) -> Vec3 { no_geometry(); },
          [&](const Plane& p) -> Vec3 { return p.frame.z; },
          [&](const Cylinder& c) -> Vec3 { return radial(c.frame, u); },
          [&](const Cone& c) -> Vec3 {
            // ∂P/∂θ × ∂P/∂t normalised: flips with the sign of the radius, so it points
            // away from the axis on both nappes.
            const double sign = cone_radius_at(c, v) < 0 ? -1.0 : 1.0;
            return sign * (std::cos(c.half_angle) * radial(c.frame, u) - std::sin(c.half_angle) * c.frame.z);
          },
          [&](const Sphere& c) -> Vec3 {
            return std::cos(v) * radial(c.frame, u) + std::sin(v) * c.frame.z;
          },
          [&](const Torus& c) -> Vec3 {
            // Outward from the tube; for a spindle torus where R + r cosφ < 0 this is
            // still the tube's outward normal.
            return std::cos(v) * radial(c.frame, u) + std::sin(v) * c.frame.z;
          },
          [&](const auto&) -> Vec3 { return ff_normal(s, uv); }},
      s);
}

void derivatives(const Surface& s, const Vec2& uv, Vec3& du, Vec3& dv) {
  const double u = uv.x(), v = uv.y();
  std::visit(detail::Overload{
                 [&](const std::monostate&) { no_geometry(); },
                 [&](const Plane& p) {
                   du = p.frame.x;
                   dv = p.frame.y();
                 },
                 [&](const Cylinder& c) {
                   du = c.radius * radial(c.frame, u + kPi / 2);
                   dv = c.frame.z;
                 },
                 [&](const Cone& c) {
                   du = cone_radius_at(c, v) * radial(c.frame, u + kPi / 2);
                   dv = std::sin(c.half_angle) * radial(c.frame, u) + std::cos(c.half_angle) * c.frame.z;
                 },
                 [&](const Sphere& c) {
                   du = c.radius * std::cos(v) * radial(c.frame, u + kPi / 2);
                   dv = c.radius * (-std::sin(v) * radial(c.frame, u) + std::cos(v) * c.frame.z);
                 },
                 [&](const Torus& c) {
                   du = (c.major_radius + c.minor_radius * std::cos(v)) * radial(c.frame, u + kPi / 2);
                   dv = c.minor_radius * (-std::sin(v) * radial(c.frame, u) + std::cos(v) * c.frame.z);
                 },
                 [&](const auto&) { ff_point(s, uv, &du, &dv); }},
             s);
}

double area_element(const Surface& s, const Vec2& uv) {
  const double v = uv.y();
  return std::visit(detail::Overload{
                        [&](const std::monostate&) -> double { no_geometry(); },
                        [&](const Plane&) { return 1.0; },
                        [&](const Cylinder& c) { return std::abs(c.radius); },
                        [&](const Cone& c) { return std::abs(cone_radius_at(c, v)); },
                        [&](const Sphere& c) { return c.radius * c.radius * std::abs(std::cos(v)); },
                        [&](const Torus& c) {
                          return c.minor_radius * std::abs(c.major_radius + c.minor_radius * std::cos(v));
                        },
                        [&](const auto&) -> double {
                          Vec3 du, dv;
                          ff_point(s, uv, &du, &dv);
                          return du.cross(dv).norm();
                        }},
                    s);
}

SurfacePoint closest_point(const Surface& s, const Vec3& p) {
  return std::visit(detail::Overload{[&](const std::monostate&) -> SurfacePoint { no_geometry(); },
                                     [&](const Plane& x) { return closest_plane(x, p); },
                                     [&](const Cylinder& x) { return closest_cylinder(x, p); },
                                     [&](const Cone& x) { return closest_cone(x, p); },
                                     [&](const Sphere& x) { return closest_sphere(x, p); },
                                     [&](const Torus& x) { return closest_torus(x, p); },
                                     [&](const auto&) { return ff_closest(s, p); }},
                    s);
}

double signed_distance(const Surface& s, const Vec3& p) { return closest_point(s, p).distance; }
Vec2 parameters(const Surface& s, const Vec3& p) {
  // A free-form surface's parameters straight from the backend's projection, without the
  // point and normal closest_point evaluates there (a quarter of a projection's time;
  // the writer's pcurves and the measures of free-form faces ask for millions).
  if (is_freeform(s)) return require_freeform().surface_project(s, p);
  return closest_point(s, p).uv;
}

// A surface of revolution's u is its angle. B-spline periods are knot spans, not 2π:
// B-spline surfaces count as not periodic here (a face across a periodic B-spline's seam
// is measured in its unwrapped parameters by the backend's projection).
bool periodic_u(const Surface& s) {
  return std::holds_alternative<Cylinder>(s) || std::holds_alternative<Cone>(s) ||
         std::holds_alternative<Sphere>(s) || std::holds_alternative<Torus>(s) ||
         std::holds_alternative<RevolutionSurface>(s);
}
bool periodic_v(const Surface& s) { return std::holds_alternative<Torus>(s); }

double surface_scale(const Surface& s) {
  return std::visit(detail::Overload{[](const std::monostate&) { return 0.0; },
                                     [](const Plane&) { return 0.0; },
                                     [](const Cylinder& c) { return std::abs(c.radius); },
                                     [](const Cone& c) { return std::abs(c.radius); },
                                     [](const Sphere& c) { return std::abs(c.radius); },
                                     [](const Torus& c) { return c.major_radius + c.minor_radius; },
                                     // Free-form: no single radius; 0 like a plane (thresholds
                                     // then scale with the tolerance).
                                     [](const auto&) { return 0.0; }},
                    s);
}

std::string surface_problem(const Surface& s) {
  std::ostringstream out;
  auto frame = [&](const Frame& f) {
    const std::string p = frame_problem(f);
    if (!p.empty()) out << surface_type_name(s) << ": " << p;
    return p.empty();
  };
  std::visit(detail::Overload{
                 [&](const std::monostate&) { out << "surface has no geometry"; },
                 [&](const Plane& p) { frame(p.frame); },
                 [&](const Cylinder& c) {
                   if (frame(c.frame) && !(c.radius > 0))
                     out << "cylinder radius must be positive, got " << c.radius;
                 },
                 [&](const Cone& c) {
                   if (!frame(c.frame)) return;
                   if (!(c.radius >= 0))
                     out << "cone radius must not be negative, got " << c.radius;
                   else if (!(std::abs(c.half_angle) > 0 && std::abs(c.half_angle) < kPi / 2))
                     out << "cone half-angle must satisfy 0 < |α| < π/2, got " << c.half_angle;
                 },
                 [&](const Sphere& c) {
                   if (frame(c.frame) && !(c.radius > 0))
                     out << "sphere radius must be positive, got " << c.radius;
                 },
                 [&](const Torus& c) {
                   if (!frame(c.frame)) return;
                   if (!(c.minor_radius > 0))
                     out << "torus minor radius must be positive, got " << c.minor_radius;
                   else if (!(c.major_radius >= 0))
                     out << "torus major radius must not be negative, got " << c.major_radius;
                 },
                 [&](const auto&) {
                   if (const FreeformBackend* b = freeform_backend())
                     out << b->surface_problem(s);
                   else
                     out << freeform_unavailable();
                 }},
             s);
  return out.str();
}

}  // namespace kintsugi::geo
