// Bodies shared by the native-format tests.
#pragma once

#include "kernel/body.h"
#include "kernel/builders.h"

namespace kintsugi::test {

// A box whose edges and faces carry every curve and surface type (and none), on a tilted
// frame with awkward doubles: what a writer must spell and a reader must take back.
inline Body every_geometry_type_body() {
  Body b = build::box();
  auto es = b.edges();
  auto fs = b.faces();
  geo::Frame tilted;
  tilted.origin = {0.1, -2.5, 1e-300};
  tilted.x = geo::Vec3(1, 1, 0).normalized();
  tilted.z = geo::Vec3(-1, 1, 1).normalized();
  tilted.z = (tilted.z - tilted.z.dot(tilted.x) * tilted.x).normalized();
  b.set_curve(es[0], geo::Circle{tilted, 0.1});
  b.set_curve(es[1], geo::Ellipse{tilted, 3, 1.0 / 3});
  b.set_curve(es[2], geo::Polyline{{{0, 0, 0}, {0.5, 1e-17, -0.0}, {1, 2, 3}}, 1e-6});
  b.set_curve(es[3], geo::Curve{});
  b.set_surface(fs[0], geo::Cylinder{tilted, 0.25}, false);
  b.set_surface(fs[1], geo::Cone{tilted, 0.0, -0.3});
  b.set_surface(fs[2], geo::Sphere{tilted, 1e5});
  b.set_surface(fs[3], geo::Torus{tilted, 7, 6.999});
  b.set_surface(fs[4], geo::Surface{});
  return b;
}

}  // namespace kintsugi::test
