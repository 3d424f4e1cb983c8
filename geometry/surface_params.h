// An analytic surface as Ceres parameter blocks, and the residuals that put points on it.
// Two solves use them: the region solve after every repair (repair/region_solve.cpp),
// which moves surfaces and vertices together, and the refit of a surface to points
// (fit_surface_like, geometry/same_geometry.h), which gives merged faces one surface.
//
// The blocks have no redundant freedom (paper reference [7] solves the same kind of
// system; the manifolds are Ceres's own):
//   plane     unit normal n (sphere manifold) | offset d                   (n·x = d)
//   cylinder  axis as a line: origin, unit direction (line manifold) | radius
//   cone      axis as a line | radius at the origin, half-angle
//   sphere    centre | radius
//   torus     centre | unit axis (sphere manifold) | major, minor radius
// (The line manifold moves the origin only across the axis, so a cone's radius at its
// origin stays meaningful and a cylinder cannot slide along itself.)
#pragma once

#include "geometry/surface.h"
#include "geometry/types.h"

#include <ceres/ceres.h>

#include <cmath>
#include <optional>
#include <utility>
#include <vector>

namespace kintsugi::geo {

enum class SurfaceKind { plane, cylinder, cone, sphere, torus };

struct SurfaceParams {
  SurfaceKind kind = SurfaceKind::plane;
  double a[6] = {};  // normal / line (origin, direction) / centre (+ axis for a torus)
  double s[2] = {};  // d / radius / radius, half-angle / radius / major, minor

  // The parameter blocks, in the order `surface_distance` reads them.
  std::vector<std::pair<double*, int>> blocks();
  // The manifold of block `block`, or nullptr for plain Euclidean blocks. The caller owns
  // it (ceres::Problem takes ownership through SetManifold).
  ceres::Manifold* manifold(std::size_t block) const;
};

// The blocks of an analytic surface; nullopt for free-form surfaces (never solved: kintsugi
// keeps them exactly).
std::optional<SurfaceParams> params_of(const Surface& surface);

// `old` with the solved parameters: the same type and sense; the frame's x stays as near
// the old one as the new axis allows.
Surface surface_from(const Surface& old, const SurfaceParams& q);

// Signed distance from x to the surface with blocks q (the senses of geometry/surface.h:
// outward positive), in a form Ceres can differentiate.
template <typename T>
T surface_distance(SurfaceKind kind, T const* const* q, const T* x) {
  using std::cos;
  using std::sin;
  using std::sqrt;
  auto axial = [&](const T* o, const T* d, T& h, T& rho) {
    T v[3] = {x[0] - o[0], x[1] - o[1], x[2] - o[2]};
    h = v[0] * d[0] + v[1] * d[1] + v[2] * d[2];
    T w[3] = {v[0] - h * d[0], v[1] - h * d[1], v[2] - h * d[2]};
    // (+1e-300: on the axis, a cone's apex, the derivative is 0·finite, not 0·∞.)
    rho = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2] + 1e-300);
  };
  T h, rho;
  switch (kind) {
    case SurfaceKind::plane: return q[0][0] * x[0] + q[0][1] * x[1] + q[0][2] * x[2] - q[1][0];
    case SurfaceKind::cylinder: axial(q[0], q[0] + 3, h, rho); return rho - q[1][0];
    case SurfaceKind::cone: {
      // In the meridian half-plane through x the double cone is a V: the generator of x's
      // own side (radius r + t·sinα ≥ 0) and the other nappe's, seen from this side
      // (radius ≤ 0); the nearer one counts (geometry/surface.cpp, closest_cone). With the
      // first alone, samples beyond the apex pulled a fit into a wrong cone.
      axial(q[0], q[0] + 3, h, rho);
      const T near_side = (rho - q[1][0]) * cos(q[1][1]) - h * sin(q[1][1]);
      const T far_side = (rho + q[1][0]) * cos(q[1][1]) + h * sin(q[1][1]);
      using std::abs;
      return abs(far_side) < abs(near_side) ? far_side : near_side;
    }
    case SurfaceKind::sphere: {
      T d[3] = {x[0] - q[0][0], x[1] - q[0][1], x[2] - q[0][2]};
      return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] + 1e-300) - q[1][0];
    }
    case SurfaceKind::torus: {
      axial(q[0], q[1], h, rho);
      T dr = rho - q[2][0];
      return sqrt(dr * dr + h * h + 1e-300) - q[2][1];
    }
  }
  return T(0);
}

// The surface's gradient at x (a normal, not of unit length; either sense), in a form
// Ceres can differentiate: a plane's normal, the direction across the axis for a cylinder,
// from the centre for a sphere, from the tube's centre circle for a torus; for a cone, of
// the nappe nearer x (as surface_distance).
template <typename T>
void surface_gradient(SurfaceKind kind, T const* const* q, const T* x, T* n) {
  using std::cos;
  using std::sin;
  using std::sqrt;
  auto across = [&](const T* o, const T* d, T* w, T& h) {
    T v[3] = {x[0] - o[0], x[1] - o[1], x[2] - o[2]};
    h = v[0] * d[0] + v[1] * d[1] + v[2] * d[2];
    for (int i = 0; i < 3; ++i) w[i] = v[i] - h * d[i];
    return sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2] + 1e-300);
  };
  T w[3], h;
  switch (kind) {
    case SurfaceKind::plane:
      for (int i = 0; i < 3; ++i) n[i] = q[0][i];
      return;
    case SurfaceKind::cylinder: {
      const T rho = across(q[0], q[0] + 3, w, h);
      for (int i = 0; i < 3; ++i) n[i] = w[i] / rho;
      return;
    }
    case SurfaceKind::cone: {
      // Of the nearer nappe, as surface_distance chooses it.
      const T rho = across(q[0], q[0] + 3, w, h);
      const T near_side = (rho - q[1][0]) * cos(q[1][1]) - h * sin(q[1][1]);
      const T far_side = (rho + q[1][0]) * cos(q[1][1]) + h * sin(q[1][1]);
      using std::abs;
      const T sense = abs(far_side) < abs(near_side) ? T(1) : T(-1);
      for (int i = 0; i < 3; ++i) n[i] = cos(q[1][1]) * w[i] / rho + sense * sin(q[1][1]) * q[0][3 + i];
      return;
    }
    case SurfaceKind::sphere:
      for (int i = 0; i < 3; ++i) n[i] = x[i] - q[0][i];
      return;
    case SurfaceKind::torus: {
      const T rho = across(q[0], q[1], w, h);
      for (int i = 0; i < 3; ++i) n[i] = w[i] * (T(1) - q[2][0] / rho) + h * q[1][i];
      return;
    }
  }
}

// Residuals w·L·(n_f × n_g) (3) at a variable point (the last block) where two surfaces
// are to stay tangent (unit normals parallel either way): a fillet and the faces it
// rounds off, so that a solve moving one moves the other with it. Each surface is solved
// (`f` or `g` non-null: its blocks come first, f's before g's) or fixed (`fixed_f`,
// `fixed_g`: its parameters, constants of the residual). L turns the angle into a length
// (the edge's extent). `blocks` receives the block pointers.
ceres::CostFunction* on_tangent_surfaces(SurfaceParams* f, const SurfaceParams& fixed_f, SurfaceParams* g,
                                         const SurfaceParams& fixed_g, double length, const double* w,
                                         std::vector<double*>& blocks);

// Residual w·d of a point on a solved surface: a variable point (then its 3 coordinates
// are the last parameter block) or a fixed one. `w` is read at each evaluation, so a
// caller can raise the weight between solves. Blocks: `p.blocks()` in order, then the
// point's if variable; `blocks` receives their pointers for AddResidualBlock.
ceres::CostFunction* on_solved_surface(SurfaceParams& p, bool variable_point, const Vec3& fixed_point,
                                       const double* w, std::vector<double*>& blocks);

// Residual w·(offset of a variable point from the seam half-plane of a solved periodic
// surface: through its axis, on the side of its frame's x), so that a vertex of a seam
// edge stays on the seam while the surface moves; x_old is the frame's x before the
// solve, `fixed_axis` a sphere's axis (not solved). nullptr for a plane. Blocks:
// `p.blocks()`, then the point's; `blocks` receives their pointers.
ceres::CostFunction* on_solved_seam(SurfaceParams& p, const Vec3& x_old, const Vec3& fixed_axis, const double* w,
                                    std::vector<double*>& blocks);

// Prior w·(x − p0) keeping a variable point (one block of 3) near p0: a vertex near where
// its repair put it (the region solve), a meeting point near its guess (meet_point).
struct NearPoint {
  Vec3 p0;
  double w;
  template <typename T>
  bool operator()(const T* x, T* r) const {
    for (int i = 0; i < 3; ++i) r[i] = T(w) * (x[i] - p0[i]);
    return true;
  }
};

// Residual w·d of a variable point (one block of 3) on a fixed surface of any type,
// free-form ones included: the derivative of the signed distance is the unit normal at
// the nearest point. On a free-form surface the foot is followed from the last
// evaluation's (see foot()); one residual object serves one solve.
class OnFixedSurface final : public ceres::SizedCostFunction<1, 3> {
 public:
  OnFixedSurface(const Surface& s, const double* w) : s_(s), w_(w) {}
  bool Evaluate(double const* const* params, double* residuals, double** jacobians) const override;

 private:
  SurfacePoint foot(const Vec3& p) const;
  Surface s_;
  const double* w_;
  mutable std::optional<Vec2> last_uv_;  // the last foot's parameters (free-form surfaces)
};

}  // namespace kintsugi::geo
