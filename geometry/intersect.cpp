// Dispatch and the closed forms involving a plane (and parallel cylinders). Coaxial
// pairs: intersect_coaxial.cpp; everything else: intersect_march.cpp.
#include "geometry/intersect.h"

#include "geometry/curve.h"
#include "geometry/distance.h"
#include "geometry/frame.h"
#include "geometry/freeform.h"
#include "geometry/intersect_detail.h"
#include "geometry/surface.h"

#include <Eigen/Dense>

#include <cmath>
#include <limits>

namespace kintsugi::geo {

namespace detail {

double reference_length(const Surface& a, const Surface& b, const IntersectOptions& o) {
  if (!o.region.empty() && o.region.diagonal() > 0) return o.region.diagonal();
  // No region: the surfaces' own size, and never less than what makes the angle
  // threshold 1e-6 (so two planes are not "parallel" merely because they are small).
  return std::max({surface_scale(a), surface_scale(b), o.precision * 1e6});
}

}  // namespace detail

namespace {

using detail::reference_length;

SurfaceIntersection with_curves(std::vector<Curve> c) {
  SurfaceIntersection out;
  out.kind = c.empty() ? IntersectionKind::empty : IntersectionKind::curves;
  out.curves = std::move(c);
  return out;
}

// A point near which to anchor a line's origin: the region centre, else `fallback`.
Vec3 anchor(const IntersectOptions& o, const Vec3& fallback) {
  return o.region.empty() ? fallback : o.region.centre();
}

// Line of two planes through the point nearest the anchor.
SurfaceIntersection plane_plane(const Plane& a, const Plane& b, const IntersectOptions& o, double ang) {
  const Vec3 n1 = a.frame.z, n2 = b.frame.z;
  const Vec3 d = n1.cross(n2);
  if (d.norm() <= ang) {
    SurfaceIntersection out;
    const double gap = (b.frame.origin - a.frame.origin).dot(n1);
    out.kind = std::abs(gap) <= o.precision ? IntersectionKind::coincident : IntersectionKind::empty;
    return out;
  }
  const Vec3 u = d.normalized();
  Eigen::Matrix3d m;
  m.row(0) = n1;
  m.row(1) = n2;
  m.row(2) = u;
  const Vec3 rhs(n1.dot(a.frame.origin), n2.dot(b.frame.origin), u.dot(anchor(o, a.frame.origin)));
  return with_curves({Line{m.colPivHouseholderQr().solve(rhs), u}});
}

SurfaceIntersection plane_cylinder(const Plane& p, const Cylinder& c, const IntersectOptions& o, double ang) {
  const Vec3 n = p.frame.z, a = c.frame.z;
  const double cosg = n.dot(a);
  if (std::abs(cosg) <= ang) {
    // Axis parallel to the plane: 0, 1 (tangent) or 2 lines parallel to the axis.
    const double d = (c.frame.origin - p.frame.origin).dot(n);  // axis height above plane
    const Vec3 foot = c.frame.origin - d * n;                    // axis projected on the plane
    if (std::abs(d) > c.radius + o.precision) return with_curves({});
    const Vec3 side = n.cross(a).normalized();
    const Vec3 base = foot + (anchor(o, foot) - foot).dot(a) * a;  // slide along the axis to the anchor
    if (std::abs(std::abs(d) - c.radius) <= o.precision) return with_curves({Line{base, a}});
    const double w = std::sqrt(c.radius * c.radius - d * d);
    return with_curves({Line{base + w * side, a}, Line{base - w * side, a}});
  }
  // Axis crosses the plane at the ellipse centre.
  const double t = (p.frame.origin - c.frame.origin).dot(n) / cosg;
  const Vec3 centre = c.frame.origin + t * a;
  const double major = c.radius / std::abs(cosg);
  if (major - c.radius <= o.precision) return with_curves({Circle{frame_from_axis(centre, n, c.frame.x), c.radius}});
  const Vec3 minor_dir = a.cross(n).normalized();
  Frame f;
  f.origin = centre;
  f.z = n;
  f.x = n.cross(minor_dir).normalized();  // major axis: in the plane, across the minor one
  return with_curves({Ellipse{f, major, c.radius}});
}

SurfaceIntersection plane_cone(const Plane& p, const Cone& c, const IntersectOptions& o, double ang) {
  const Vec3 n = p.frame.z, a = c.frame.z, top = apex(c);
  const double delta = (top - p.frame.origin).dot(n);  // apex height above the plane
  const double ca = std::cos(c.half_angle), sa = std::abs(std::sin(c.half_angle));
  const double cn = n.dot(a);
  const double s = std::sqrt(std::max(0.0, 1 - cn * cn));  // |a projected on the plane|
  if (std::abs(delta) <= o.precision) {
    // Plane through the apex: lines through the apex at angle α from the axis, or only
    // the apex. Directions d = cosψ e1 + sinψ e2 with d·a = ±cosα.
    SurfaceIntersection out;
    if (s < ca - ang) {
      out.kind = IntersectionKind::curves;
      out.points.push_back(top);
      return out;
    }
    const Vec3 e1 = (a - cn * n).normalized(), e2 = n.cross(e1);
    if (s <= ca + ang) return with_curves({Line{top, e1}});  // tangent plane: one generator
    const double psi = std::acos(std::clamp(ca / s, -1.0, 1.0));
    return with_curves({Line{top, std::cos(psi) * e1 + std::sin(psi) * e2},
                        Line{top, std::cos(psi) * e1 - std::sin(psi) * e2}});
  }
  // Ellipse when the plane is steeper than a generator: A = cos²α - s² > 0. Otherwise
  // (parabola, hyperbola, or an ellipse too elongated to tell apart) march.
  const double k2 = ca * ca, A = k2 - s * s;
  if (A <= ang) return detail::intersect_march(p, c, o);
  const double dp = -delta;  // plane offset seen from the apex
  const Vec3 foot = top + dp * n;
  if (s <= 1e-15) {
    const double radius = std::abs(dp) * std::abs(std::tan(c.half_angle));
    return with_curves({Circle{frame_from_axis(foot, n, c.frame.x), radius}});
  }
  const Vec3 e1 = (a - cn * n) / s;
  const double u0 = dp * cn * s / A;
  const double major = std::abs(dp) * ca * sa / A;
  const double minor = std::abs(dp) * sa / std::sqrt(A);
  const Vec3 centre = foot + u0 * e1;
  if (major - minor <= o.precision) return with_curves({Circle{frame_from_axis(centre, n, c.frame.x), major}});
  Frame f;
  f.origin = centre;
  f.z = n;
  f.x = e1;
  return with_curves({Ellipse{f, major, minor}});
}

// Plane containing the torus axis: the two tube circles in that plane.
std::optional<SurfaceIntersection> plane_torus(const Plane& p, const Torus& t, const IntersectOptions& o, double ang) {
  const Vec3 n = p.frame.z, a = t.frame.z;
  if (std::abs(n.dot(a)) > ang || std::abs((t.frame.origin - p.frame.origin).dot(n)) > o.precision)
    return std::nullopt;  // perpendicular case: coaxial; others: marched
  const Vec3 e = a.cross(n).normalized();  // radial direction in the plane
  std::vector<Curve> c;
  for (double sgn : {1.0, -1.0}) {
    Frame f;
    f.origin = t.frame.origin + sgn * t.major_radius * e;
    f.z = n;
    f.x = sgn * e;
    c.push_back(Circle{f, t.minor_radius});
  }
  return with_curves(std::move(c));
}

// Parallel (non-coaxial) cylinders: lines along the axis through the cross-section's
// circle-circle intersection points.
std::optional<SurfaceIntersection> parallel_cylinders(const Cylinder& a, const Cylinder& b, const IntersectOptions& o,
                                                      double ang) {
  if (a.frame.z.cross(b.frame.z).norm() > ang) return std::nullopt;
  const Vec3 z = a.frame.z;
  const Vec3 base = a.frame.origin + (anchor(o, a.frame.origin) - a.frame.origin).dot(z) * z;
  Vec3 d = b.frame.origin - a.frame.origin;
  d -= d.dot(z) * z;  // centre offset in the cross-section
  const double len = d.norm();
  if (len <= o.precision) return std::nullopt;  // coaxial: handled there
  if (len > a.radius + b.radius + o.precision || len < std::abs(a.radius - b.radius) - o.precision)
    return with_curves({});
  const Vec3 e = d / len, side = z.cross(e);
  const double x = (len * len + a.radius * a.radius - b.radius * b.radius) / (2 * len);
  const double y2 = a.radius * a.radius - x * x;
  if (y2 <= 0 || std::abs(len - (a.radius + b.radius)) <= o.precision ||
      std::abs(len - std::abs(a.radius - b.radius)) <= o.precision)
    return with_curves({Line{base + x * e, z}});
  const double y = std::sqrt(y2);
  return with_curves({Line{base + x * e + y * side, z}, Line{base + x * e - y * side, z}});
}

}  // namespace

SurfaceIntersection intersect_surfaces(const Surface& a, const Surface& b, const IntersectOptions& o) {
  for (const Surface* s : {&a, &b}) {
    const std::string p = surface_problem(*s);
    if (!p.empty()) {
      SurfaceIntersection out;
      out.kind = IntersectionKind::failed;
      out.problem = p;
      return out;
    }
  }
  // Free-form: OpenCASCADE's surface intersection, through the backend.
  if (is_freeform(a) || is_freeform(b)) {
    SurfaceIntersection out;
    const FreeformBackend* fb = freeform_backend();
    if (!fb) {
      out.kind = IntersectionKind::failed;
      out.problem = freeform_unavailable();
      return out;
    }
    out.curves = fb->intersect(a, b, o.precision, nullptr);
    out.kind = out.curves.empty() ? IntersectionKind::empty : IntersectionKind::curves;
    return out;
  }
  const double ang = o.precision / reference_length(a, b, o);
  if (const auto* p = std::get_if<Plane>(&a)) {
    if (const auto* q = std::get_if<Plane>(&b)) return plane_plane(*p, *q, o, ang);
  }
  if (auto c = detail::intersect_coaxial(a, b, o)) return *c;
  // Put the plane first for the plane cases.
  const bool swap = std::holds_alternative<Plane>(b) && !std::holds_alternative<Plane>(a);
  const Surface& x = swap ? b : a;
  const Surface& y = swap ? a : b;
  if (const auto* p = std::get_if<Plane>(&x)) {
    if (const auto* c = std::get_if<Cylinder>(&y)) return plane_cylinder(*p, *c, o, ang);
    if (const auto* c = std::get_if<Cone>(&y)) return plane_cone(*p, *c, o, ang);
    if (const auto* t = std::get_if<Torus>(&y))
      if (auto r = plane_torus(*p, *t, o, ang)) return *r;
  }
  if (const auto* c = std::get_if<Cylinder>(&x))
    if (const auto* d = std::get_if<Cylinder>(&y))
      if (auto r = parallel_cylinders(*c, *d, o, ang)) return *r;
  return detail::intersect_march(a, b, o);
}

std::vector<Curve> intersect_exact(const Surface& a, const Surface& b, double precision, const std::vector<Vec3>* near) {
  const FreeformBackend* fb = freeform_backend();
  if (!fb) return {};
  return fb->intersect(a, b, precision, near);
}

std::vector<Curve> intersect(const Surface& a, const Surface& b, const IntersectOptions& o) {
  SurfaceIntersection r = intersect_surfaces(a, b, o);
  return r.kind == IntersectionKind::curves ? std::move(r.curves) : std::vector<Curve>{};
}

std::optional<BranchChoice> select_branch(const std::vector<Curve>& curves, const Vec3& p_start, const Vec3& p_end) {
  std::optional<BranchChoice> best;
  for (std::size_t i = 0; i < curves.size(); ++i) {
    if (std::holds_alternative<std::monostate>(curves[i])) continue;
    const double d = std::max(closest_point(curves[i], p_start).distance, closest_point(curves[i], p_end).distance);
    if (!best || d < best->distance) best = BranchChoice{i, d};
  }
  return best;
}

}  // namespace kintsugi::geo
