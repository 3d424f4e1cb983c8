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
                    },
                    curve);
}

}  // namespace kintsugi::geo
