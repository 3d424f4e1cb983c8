// Coaxial surfaces of revolution meet in circles: in a meridian plane (coordinates ρ
// along a radial direction, z along the common axis, ρ signed so the whole plane is
// covered) each surface is a union of lines and circles, and every intersection point
// with ρ > 0 of the two sections is a circle of radius ρ at height z.
//   plane ⟂ axis   the line z = z0
//   cylinder       the lines ρ = ±r
//   cone           the two generators ρ = ±(r + s(z - z0) tan α)  (s = ±1: axis sense)
//   sphere         the circle of radius r about (0, z0)
//   torus          the circles of radius r about (±R, z0)
// A sphere is symmetric about every line through its centre and a plane about every
// line along its normal, which is what makes plane-sphere, sphere-sphere etc. coaxial.
#include "geometry/frame.h"
#include "geometry/intersect_detail.h"
#include "geometry/overload.h"
#include "geometry/surface.h"

#include <cmath>

namespace kintsugi::geo::detail {

namespace {

struct Axis {
  Vec3 point, dir;
};

// What a surface allows as its axis of revolution.
struct Symmetry {
  enum Kind { fixed, any_through_point, any_along_direction, none } kind = none;
  Vec3 point = Vec3::Zero(), dir = Vec3::UnitZ();
};

Symmetry symmetry(const Surface& s) {
  return std::visit(Overload{[](const std::monostate&) { return Symmetry{}; },
                             [](const Plane& p) {
                               return Symmetry{Symmetry::any_along_direction, p.frame.origin, p.frame.z};
                             },
                             [](const Sphere& p) {
                               return Symmetry{Symmetry::any_through_point, p.frame.origin, p.frame.z};
                             },
                             [](const auto& p) {
                               if constexpr (requires { p.frame; })
                                 return Symmetry{Symmetry::fixed, p.frame.origin, p.frame.z};
                               else
                                 return Symmetry{};  // free-form: no axis used here
                             }},
                    s);
}

double line_distance(const Vec3& p, const Axis& a) { return (p - a.point).cross(a.dir).norm(); }

// The common axis, if any. `ang` is the angular tolerance, `eps` the length one.
std::optional<Axis> common_axis(const Symmetry& a, const Symmetry& b, double ang, double eps) {
  using K = Symmetry::Kind;
  if (a.kind == K::none || b.kind == K::none) return std::nullopt;
  if (a.kind == K::fixed || b.kind == K::fixed) {
    const Symmetry& f = a.kind == K::fixed ? a : b;
    const Symmetry& o = a.kind == K::fixed ? b : a;
    const Axis axis{f.point, f.dir};
    switch (o.kind) {
      case K::fixed:
        if (f.dir.cross(o.dir).norm() <= ang && line_distance(o.point, axis) <= eps) return axis;
        return std::nullopt;
      case K::any_through_point:
        if (line_distance(o.point, axis) <= eps) return axis;
        return std::nullopt;
      case K::any_along_direction:
        if (f.dir.cross(o.dir).norm() <= ang) return axis;
        return std::nullopt;
      default:
        return std::nullopt;
    }
  }
  if (a.kind == K::any_through_point && b.kind == K::any_through_point) {
    const Vec3 d = b.point - a.point;
    // Concentric spheres: any axis; use a's.
    return Axis{a.point, d.norm() > eps ? Vec3(d.normalized()) : a.dir};
  }
  if (a.kind == K::any_along_direction && b.kind == K::any_along_direction) return std::nullopt;  // plane-plane
  const Symmetry& pt = a.kind == K::any_through_point ? a : b;
  const Symmetry& dir = a.kind == K::any_through_point ? b : a;
  return Axis{pt.point, dir.dir};
}

struct Line2 {
  Vec2 p, d;  // d unit
};
struct Circle2 {
  Vec2 c;
  double r;
};
struct Section {
  std::vector<Line2> lines;
  std::vector<Circle2> circles;
};

// Meridian section of a surface about `axis` (ρ along an arbitrary radial, z along axis
// from axis.point).
Section section(const Surface& s, const Axis& axis) {
  Section out;
  auto height = [&](const Vec3& p) { return (p - axis.point).dot(axis.dir); };
  std::visit(Overload{[](const std::monostate&) {},
                      [&](const Plane& p) { out.lines.push_back({Vec2(0, height(p.frame.origin)), Vec2(1, 0)}); },
                      [&](const Cylinder& c) {
                        out.lines.push_back({Vec2(c.radius, 0), Vec2(0, 1)});
                        out.lines.push_back({Vec2(-c.radius, 0), Vec2(0, 1)});
                      },
                      [&](const Cone& c) {
                        const double sense = c.frame.z.dot(axis.dir) >= 0 ? 1.0 : -1.0;
                        const double z0 = height(c.frame.origin);
                        const double slope = sense * std::tan(c.half_angle);  // dρ/dz
                        const Vec2 d = Vec2(slope, 1).normalized();
                        out.lines.push_back({Vec2(c.radius, z0), d});
                        out.lines.push_back({Vec2(-c.radius, z0), Vec2(-d.x(), d.y())});
                      },
                      [&](const Sphere& c) { out.circles.push_back({Vec2(0, height(c.frame.origin)), c.radius}); },
                      [&](const Torus& c) {
                        const double z0 = height(c.frame.origin);
                        out.circles.push_back({Vec2(c.major_radius, z0), c.minor_radius});
                        out.circles.push_back({Vec2(-c.major_radius, z0), c.minor_radius});
                      },
                      [](const auto&) {}},  // free-form: symmetry() gave no axis, never reached
             s);
  return out;
}

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Intersection points of 2D primitives; `coincident` set when they are the same curve.
void meet(const Line2& a, const Line2& b, double ang, double eps, std::vector<Vec2>& out, bool& coincident) {
  const double den = cross2(a.d, b.d);
  if (std::abs(den) <= ang) {
    if (std::abs(cross2(a.d, b.p - a.p)) <= eps) coincident = true;
    return;
  }
  out.push_back(a.p + a.d * (cross2(b.p - a.p, b.d) / den));
}
void meet(const Line2& l, const Circle2& c, double eps, std::vector<Vec2>& out) {
  const double t0 = (c.c - l.p).dot(l.d);
  const Vec2 foot = l.p + t0 * l.d;
  const double h = (c.c - foot).norm();
  if (h > c.r + eps) return;
  if (std::abs(h - c.r) <= eps) {  // tangent: one (double) point
    out.push_back(foot);
    return;
  }
  const double w = std::sqrt(std::max(0.0, c.r * c.r - h * h));
  out.push_back(foot + w * l.d);
  out.push_back(foot - w * l.d);
}
void meet(const Circle2& a, const Circle2& b, double eps, std::vector<Vec2>& out, bool& coincident) {
  const Vec2 d = b.c - a.c;
  const double len = d.norm();
  if (len <= eps) {
    if (std::abs(a.r - b.r) <= eps) coincident = true;
    return;
  }
  if (len > a.r + b.r + eps || len < std::abs(a.r - b.r) - eps) return;
  const Vec2 e = d / len, n(-e.y(), e.x());
  const double x = (len * len + a.r * a.r - b.r * b.r) / (2 * len);
  const double y2 = a.r * a.r - x * x;
  if (std::abs(len - (a.r + b.r)) <= eps || std::abs(len - std::abs(a.r - b.r)) <= eps || y2 <= 0) {
    out.push_back(a.c + x * e);
    return;
  }
  const double y = std::sqrt(y2);
  out.push_back(a.c + x * e + y * n);
  out.push_back(a.c + x * e - y * n);
}

}  // namespace

std::optional<SurfaceIntersection> intersect_coaxial(const Surface& a, const Surface& b, const IntersectOptions& o) {
  const double eps = o.precision;
  const double ang = eps / reference_length(a, b, o);
  const std::optional<Axis> axis = common_axis(symmetry(a), symmetry(b), ang, eps);
  if (!axis) return std::nullopt;
  const Section sa = section(a, *axis), sb = section(b, *axis);
  std::vector<Vec2> pts;
  bool coincident = false;
  for (const Line2& x : sa.lines) {
    for (const Line2& y : sb.lines) meet(x, y, ang, eps, pts, coincident);
    for (const Circle2& y : sb.circles) meet(x, y, eps, pts);
  }
  for (const Circle2& x : sa.circles) {
    for (const Line2& y : sb.lines) meet(y, x, eps, pts);
    for (const Circle2& y : sb.circles) meet(x, y, eps, pts, coincident);
  }
  SurfaceIntersection out;
  if (coincident) {
    // Sections sharing a whole line or circle: the surfaces share a whole sheet.
    out.kind = IntersectionKind::coincident;
    return out;
  }
  // Reference direction for the circles' x axis: the first surface's frame x.
  const Vec3 hint = std::visit(Overload{[](const std::monostate&) { return Vec3(Vec3::UnitX()); },
                                        [](const auto& s) {
                                          if constexpr (requires { s.frame; })
                                            return Vec3(s.frame.x);
                                          else
                                            return Vec3(Vec3::UnitX());
                                        }},
                               a);
  std::vector<Vec2> kept;
  for (const Vec2& p : pts) {
    if (p.x() < -eps) continue;  // the mirror half of the section
    bool dup = false;
    for (const Vec2& q : kept) dup = dup || (p - q).norm() <= eps;
    if (dup) continue;
    kept.push_back(p);
    const Vec3 centre = axis->point + p.y() * axis->dir;
    if (p.x() <= eps) {
      out.points.push_back(centre);  // touching on the axis (apex, pole)
    } else {
      out.curves.push_back(Circle{frame_from_axis(centre, axis->dir, hint), p.x()});
    }
  }
  out.kind = out.curves.empty() && out.points.empty() ? IntersectionKind::empty : IntersectionKind::curves;
  return out;
}

}  // namespace kintsugi::geo::detail
