#include "geometry/surface_params.h"

#include "geometry/exact_manifolds.h"
#include "geometry/surface.h"

#include <cmath>
#include <exception>
#include <type_traits>
#include <variant>

namespace kintsugi::geo {

std::vector<std::pair<double*, int>> SurfaceParams::blocks() {
  switch (kind) {
    case SurfaceKind::plane: return {{a, 3}, {s, 1}};
    case SurfaceKind::cylinder: return {{a, 6}, {s, 1}};
    case SurfaceKind::cone: return {{a, 6}, {s, 2}};
    case SurfaceKind::sphere: return {{a, 3}, {s, 1}};
    case SurfaceKind::torus: return {{a, 3}, {a + 3, 3}, {s, 2}};
  }
  return {};
}

ceres::Manifold* SurfaceParams::manifold(std::size_t block) const {
  // Not Ceres's SphereManifold and LineManifold: near the z axis they snap a direction
  // onto it on every step (exact_manifolds.h).
  if (kind == SurfaceKind::plane && block == 0) return new UnitDirectionManifold();
  if ((kind == SurfaceKind::cylinder || kind == SurfaceKind::cone) && block == 0) return new AxisLineManifold();
  if (kind == SurfaceKind::torus && block == 1) return new UnitDirectionManifold();
  return nullptr;
}

std::optional<SurfaceParams> params_of(const Surface& surface) {
  SurfaceParams q;
  auto put = [](double* to, const Vec3& v) {
    for (int i = 0; i < 3; ++i) to[i] = v[i];
  };
  if (auto* p = std::get_if<Plane>(&surface)) {
    q.kind = SurfaceKind::plane;
    put(q.a, p->frame.z.normalized());
    q.s[0] = p->frame.z.normalized().dot(p->frame.origin);
  } else if (auto* c = std::get_if<Cylinder>(&surface)) {
    q.kind = SurfaceKind::cylinder;
    put(q.a, c->frame.origin);
    put(q.a + 3, c->frame.z.normalized());
    q.s[0] = c->radius;
  } else if (auto* k = std::get_if<Cone>(&surface)) {
    q.kind = SurfaceKind::cone;
    put(q.a, k->frame.origin);
    put(q.a + 3, k->frame.z.normalized());
    q.s[0] = k->radius;
    q.s[1] = k->half_angle;
  } else if (auto* sp = std::get_if<Sphere>(&surface)) {
    q.kind = SurfaceKind::sphere;
    put(q.a, sp->frame.origin);
    q.s[0] = sp->radius;
  } else if (auto* t = std::get_if<Torus>(&surface)) {
    q.kind = SurfaceKind::torus;
    put(q.a, t->frame.origin);
    put(q.a + 3, t->frame.z.normalized());
    q.s[0] = t->major_radius;
    q.s[1] = t->minor_radius;
  } else {
    return std::nullopt;
  }
  return q;
}

namespace {

// The frame with a new origin and axis; x stays as near the old one as it can.
Frame moved_frame(const Frame& old, const Vec3& origin, Vec3 z) {
  z.normalize();
  Vec3 x = old.x - old.x.dot(z) * z;
  if (x.norm() < 1e-6) x = z.unitOrthogonal();
  return Frame{origin, x.normalized(), z};
}

struct OnSolvedSurface {
  SurfaceKind kind;
  int surface_blocks;
  bool variable_point;
  Vec3 fixed_point;
  const double* w;
  template <typename T>
  bool operator()(T const* const* q, T* r) const {
    T x[3];
    for (int i = 0; i < 3; ++i) x[i] = variable_point ? q[surface_blocks][i] : T(fixed_point[i]);
    r[0] = T(*w) * surface_distance(kind, q, x);
    return true;
  }
};

// The offset of a variable point (the last block) from the half-plane of a solved
// periodic surface's seam, where u = 0: through the axis, across m = unit(axis × x_old)
// (surface_from keeps the frame's x as near x_old as the new axis allows, so its seam
// lies in this half-plane). A sphere's axis is not solved: `fixed_axis`.
struct OnSolvedSeam {
  SurfaceKind kind;
  int surface_blocks;
  Vec3 x_old, fixed_axis;
  const double* w;
  template <typename T>
  bool operator()(T const* const* q, T* r) const {
    using std::sqrt;
    const T* x = q[surface_blocks];
    const T* o = q[0];
    T d[3];
    for (int i = 0; i < 3; ++i)
      d[i] = kind == SurfaceKind::torus ? q[1][i] : kind == SurfaceKind::sphere ? T(fixed_axis[i]) : q[0][3 + i];
    const T m[3] = {d[1] * x_old[2] - d[2] * x_old[1], d[2] * x_old[0] - d[0] * x_old[2], d[0] * x_old[1] - d[1] * x_old[0]};
    const T len = sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2] + 1e-300);
    r[0] = T(*w) * ((x[0] - o[0]) * m[0] + (x[1] - o[1]) * m[1] + (x[2] - o[2]) * m[2]) / len;
    return true;
  }
};

struct OnTangentSurfaces {
  SurfaceParams fixed[2];
  bool solved[2];
  int blocks[2];  // of each solved surface
  double length;
  const double* w;
  template <typename T>
  bool operator()(T const* const* q, T* r) const {
    // Each surface's blocks: the solved ones from q, the fixed ones as constants.
    T consts[2][8];
    T const* fixed_blocks[2][3];
    T const* const* at[2];
    int next = 0;
    T n[2][3];
    const T* x = q[(solved[0] ? blocks[0] : 0) + (solved[1] ? blocks[1] : 0)];
    for (int s = 0; s < 2; ++s) {
      if (solved[s]) {
        at[s] = q + next;
        next += blocks[s];
      } else {
        // The fixed parameters as constants, in the blocks' layout (SurfaceParams::blocks):
        // a (0-5) then s (6-7); a torus's a is two blocks, centre and axis.
        for (int i = 0; i < 6; ++i) consts[s][i] = T(fixed[s].a[i]);
        for (int i = 0; i < 2; ++i) consts[s][6 + i] = T(fixed[s].s[i]);
        fixed_blocks[s][0] = consts[s];
        if (fixed[s].kind == SurfaceKind::torus) {
          fixed_blocks[s][1] = consts[s] + 3, fixed_blocks[s][2] = consts[s] + 6;
        } else {
          fixed_blocks[s][1] = consts[s] + 6, fixed_blocks[s][2] = nullptr;
        }
        at[s] = fixed_blocks[s];
      }
      surface_gradient(fixed[s].kind, at[s], x, n[s]);
      using std::sqrt;
      const T len = sqrt(n[s][0] * n[s][0] + n[s][1] * n[s][1] + n[s][2] * n[s][2] + 1e-300);
      for (int i = 0; i < 3; ++i) n[s][i] /= len;
    }
    const T k = T(*w * length);
    r[0] = k * (n[0][1] * n[1][2] - n[0][2] * n[1][1]);
    r[1] = k * (n[0][2] * n[1][0] - n[0][0] * n[1][2]);
    r[2] = k * (n[0][0] * n[1][1] - n[0][1] * n[1][0]);
    return true;
  }
};

}  // namespace

ceres::CostFunction* on_tangent_surfaces(SurfaceParams* f, const SurfaceParams& fixed_f, SurfaceParams* g,
                                         const SurfaceParams& fixed_g, double length, const double* w,
                                         std::vector<double*>& blocks) {
  auto* functor = new OnTangentSurfaces{{f ? *f : fixed_f, g ? *g : fixed_g}, {f != nullptr, g != nullptr}, {0, 0}, length, w};
  auto* cost = new ceres::DynamicAutoDiffCostFunction<OnTangentSurfaces, 4>(functor);
  blocks.clear();
  SurfaceParams* solved[2] = {f, g};
  for (int s = 0; s < 2; ++s) {
    if (!solved[s]) continue;
    auto bl = solved[s]->blocks();
    functor->blocks[s] = int(bl.size());
    for (auto [ptr, size] : bl) {
      cost->AddParameterBlock(size);
      blocks.push_back(ptr);
    }
  }
  cost->AddParameterBlock(3);
  cost->SetNumResiduals(3);
  return cost;
}

ceres::CostFunction* on_solved_seam(SurfaceParams& p, const Vec3& x_old, const Vec3& fixed_axis, const double* w,
                                    std::vector<double*>& blocks) {
  if (p.kind == SurfaceKind::plane) return nullptr;
  auto bl = p.blocks();
  auto* f = new ceres::DynamicAutoDiffCostFunction<OnSolvedSeam, 4>(
      new OnSolvedSeam{p.kind, int(bl.size()), x_old, fixed_axis, w});
  blocks.clear();
  for (auto [ptr, size] : bl) {
    f->AddParameterBlock(size);
    blocks.push_back(ptr);
  }
  f->AddParameterBlock(3);
  f->SetNumResiduals(1);
  return f;
}

Surface surface_from(const Surface& old, const SurfaceParams& q) {
  const Vec3 a0(q.a[0], q.a[1], q.a[2]), a1(q.a[3], q.a[4], q.a[5]);
  return std::visit(
      [&](auto s) -> Surface {
        using S = decltype(s);
        if constexpr (std::is_same_v<S, Plane>) {
          Vec3 n = a0.normalized();
          s.frame = moved_frame(s.frame, s.frame.origin + (q.s[0] - n.dot(s.frame.origin)) * n, n);
        } else if constexpr (std::is_same_v<S, Cylinder>) {
          s.frame = moved_frame(s.frame, a0, a1);
          s.radius = q.s[0];
        } else if constexpr (std::is_same_v<S, Cone>) {
          s.frame = moved_frame(s.frame, a0, a1);
          s.radius = q.s[0];
          s.half_angle = q.s[1];
        } else if constexpr (std::is_same_v<S, Sphere>) {
          s.frame.origin = a0;
          s.radius = q.s[0];
        } else if constexpr (std::is_same_v<S, Torus>) {
          s.frame = moved_frame(s.frame, a0, a1);
          s.major_radius = q.s[0];
          s.minor_radius = q.s[1];
        }
        return s;
      },
      old);
}

ceres::CostFunction* on_solved_surface(SurfaceParams& p, bool variable_point, const Vec3& fixed_point,
                                       const double* w, std::vector<double*>& blocks) {
  auto bl = p.blocks();
  auto* f = new ceres::DynamicAutoDiffCostFunction<OnSolvedSurface, 4>(
      new OnSolvedSurface{p.kind, int(bl.size()), variable_point, fixed_point, w});
  blocks.clear();
  for (auto [ptr, size] : bl) {
    f->AddParameterBlock(size);
    blocks.push_back(ptr);
  }
  if (variable_point) f->AddParameterBlock(3);
  f->SetNumResiduals(1);
  return f;
}

// A solve's iterates move a little at a time, and a global projection onto a free-form
// surface is a search over its whole parameter grid (OpenCASCADE's Extrema, plus its
// projection onto iso-curves for a point off the surface): with up to 35 B-spline faces
// round a gap (OpenCASCADE's shell1.brep) the meeting-point solves spent minutes there.
// The foot is followed instead: Gauss-Newton on the surface from the last foot, a few
// evaluations, kept when it converges; otherwise (and for the first evaluation) the
// global projection. The nearest point found this way is a local one, which is what a
// local solver uses anyway.
SurfacePoint OnFixedSurface::foot(const Vec3& p) const {
  if (!is_freeform(s_) || !last_uv_) {
    SurfacePoint sp = closest_point(s_, p);
    if (is_freeform(s_)) last_uv_ = sp.uv;
    return sp;
  }
  try {
    Vec2 uv = *last_uv_;
    for (int it = 0; it < 12; ++it) {
      Vec3 du, dv;
      derivatives(s_, uv, du, dv);
      const Vec3 r = p - evaluate(s_, uv);
      const double a = du.dot(du), b = du.dot(dv), d = dv.dot(dv), det = a * d - b * b;
      if (!(det > 1e-300)) break;
      const Vec2 step((d * du.dot(r) - b * dv.dot(r)) / det, (a * dv.dot(r) - b * du.dot(r)) / det);
      if (!step.allFinite()) break;
      uv += step;
      // Converged: the step moves the foot by less than 1e-12 of its distance from the
      // origin (scales with the model).
      if ((step.x() * du + step.y() * dv).norm() <= 1e-12 * (1 + p.norm())) {
        SurfacePoint sp;
        sp.uv = uv;
        sp.point = evaluate(s_, uv);
        sp.normal = normal(s_, uv);
        const Vec3 off = p - sp.point;
        sp.distance = off.dot(sp.normal) >= 0 ? off.norm() : -off.norm();
        if (!std::isfinite(sp.distance)) break;
        last_uv_ = uv;
        return sp;
      }
    }
  } catch (const std::exception&) {
    // evaluated outside what the surface allows: the global projection decides
  }
  SurfacePoint sp = closest_point(s_, p);
  last_uv_ = sp.uv;
  return sp;
}

bool OnFixedSurface::Evaluate(double const* const* params, double* residuals, double** jacobians) const {
  const SurfacePoint sp = foot(Vec3(params[0][0], params[0][1], params[0][2]));
  residuals[0] = *w_ * sp.distance;
  if (jacobians && jacobians[0])
    for (int i = 0; i < 3; ++i) jacobians[0][i] = *w_ * sp.normal[i];
  return std::isfinite(residuals[0]);
}

}  // namespace kintsugi::geo
