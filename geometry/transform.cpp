#include "geometry/transform.h"

#include "geometry/overload.h"

namespace kintsugi::geo {

Frame transformed(const Frame& f, const Similarity& s) {
  Frame out;
  out.origin = s.point(f.origin);
  out.x = s.direction(f.x);
  out.z = s.direction(f.z);
  return out;
}

namespace {

// Free-form data: the poles move, weights and knots stay; the cached backend object
// belongs to the old data and is dropped.
BSplineCurve transformed_bspline(const BSplineCurve& c, const Similarity& s) {
  BSplineCurve out = c;
  for (Vec3& p : out.poles) p = s.point(p);
  out.cache = nullptr;
  return out;
}
BSplineSurface transformed_bspline(const BSplineSurface& b, const Similarity& s) {
  BSplineSurface out = b;
  for (Vec3& p : out.poles) p = s.point(p);
  out.cache = nullptr;
  return out;
}

}  // namespace

Surface transformed(const Surface& surface, const Similarity& s) {
  return std::visit(detail::Overload{
                        [](const std::monostate& m) -> Surface { return m; },
                        [&](const Plane& p) -> Surface { return Plane{transformed(p.frame, s)}; },
                        [&](const Cylinder& c) -> Surface { return Cylinder{transformed(c.frame, s), c.radius * s.scale}; },
                        [&](const Cone& c) -> Surface {
                          return Cone{transformed(c.frame, s), c.radius * s.scale, c.half_angle};
                        },
                        [&](const Sphere& c) -> Surface { return Sphere{transformed(c.frame, s), c.radius * s.scale}; },
                        [&](const Torus& c) -> Surface {
                          return Torus{transformed(c.frame, s), c.major_radius * s.scale, c.minor_radius * s.scale};
                        },
                        [&](const BSplineSurface& b) -> Surface { return transformed_bspline(b, s); },
                        [&](const RevolutionSurface& r) -> Surface {
                          return RevolutionSurface{transformed_bspline(r.basis, s), s.point(r.origin), s.direction(r.axis), nullptr};
                        },
                        [&](const ExtrusionSurface& e) -> Surface {
                          return ExtrusionSurface{transformed_bspline(e.basis, s), s.direction(e.direction), nullptr};
                        },
                        [&](const OffsetSurface& o) -> Surface {
                          return OffsetSurface{transformed_bspline(o.basis, s), o.distance * s.scale, nullptr};
                        },
                    },
                    surface);
}

Curve transformed(const Curve& curve, const Similarity& s) {
  return std::visit(detail::Overload{
                        [](const std::monostate& m) -> Curve { return m; },
                        [&](const Line& l) -> Curve { return Line{s.point(l.origin), s.direction(l.direction)}; },
                        [&](const Circle& c) -> Curve { return Circle{transformed(c.frame, s), c.radius * s.scale}; },
                        [&](const Ellipse& e) -> Curve {
                          return Ellipse{transformed(e.frame, s), e.major_radius * s.scale, e.minor_radius * s.scale};
                        },
                        [&](const Polyline& p) -> Curve {
                          Polyline out;
                          for (const Vec3& q : p.points) out.points.push_back(s.point(q));
                          out.chordal_error = p.chordal_error * s.scale;
                          return out;
                        },
                        [&](const BSplineCurve& b) -> Curve { return transformed_bspline(b, s); },
                    },
                    curve);
}

}  // namespace kintsugi::geo
