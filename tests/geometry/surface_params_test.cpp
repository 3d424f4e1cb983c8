// The differentiable forms of the solved surfaces (geometry/surface_params.h): the
// gradient the tangency residual is built from agrees with each surface's own normal.
#include "geometry/surface_params.h"

#include "geometry/surface.h"
#include "generators.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

namespace kintsugi::geo {
namespace {

using testing::gen_frame;
using testing::gen_real;
using testing::gen_vec;

Surface gen_analytic(int kind) {
  const Frame f = gen_frame(5.0);
  switch (kind) {
    case 0: return Plane{f};
    case 1: return Cylinder{f, gen_real(0.5, 3.0)};
    case 2: return Cone{f, gen_real(0.5, 3.0), gen_real(0.1, 1.2)};
    case 3: return Sphere{f, gen_real(0.5, 3.0)};
    default: {
      const double minor = gen_real(0.2, 1.0);
      return Torus{f, minor + gen_real(0.5, 3.0), minor};
    }
  }
}

// At a point of the surface, the gradient is parallel to the surface's unit normal.
RC_GTEST_PROP(SurfaceParams, GradientIsTheNormal, ()) {
  const Surface s = gen_analytic(*rc::gen::inRange(0, 5));
  const SurfacePoint foot = closest_point(s, gen_vec(8.0));
  // Not at a cone's apex or on a torus's or sphere's axis, where the normal turns.
  RC_PRE(foot.normal.allFinite());
  SurfaceParams q = *params_of(s);
  std::vector<const double*> blocks;
  for (auto [ptr, size] : q.blocks()) blocks.push_back(ptr);
  double n[3];
  surface_gradient(q.kind, blocks.data(), foot.point.data(), n);
  const Vec3 g(n[0], n[1], n[2]);
  RC_PRE(g.norm() > 1e-6);
  RC_ASSERT(g.normalized().cross(foot.normal).norm() < 1e-9);
}

}  // namespace
}  // namespace kintsugi::geo
