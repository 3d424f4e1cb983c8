#include "geometry/same_geometry.h"

#include "geometry/frame.h"
#include "geometry/solver_log.h"
#include "geometry/surface.h"
#include "geometry/surface_params.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <optional>

namespace kintsugi::geo {

double surface_deviation(const Surface& a, const Surface& b, const std::vector<Vec3>& samples_a,
                         const std::vector<Vec3>& samples_b, double enough) {
  double worst = 0.0;
  for (const Vec3& p : samples_a)
    if ((worst = std::max(worst, std::abs(signed_distance(b, p)))) > enough) return worst;
  for (const Vec3& q : samples_b)
    if ((worst = std::max(worst, std::abs(signed_distance(a, q)))) > enough) return worst;
  return worst;
}

namespace {

void measure(SurfaceFit& f, const std::vector<Vec3>& points) {
  double sum = 0.0;
  f.max_deviation = 0.0;
  for (const Vec3& p : points) {
    const double d = signed_distance(f.surface, p);
    sum += d * d;
    f.max_deviation = std::max(f.max_deviation, std::abs(d));
  }
  f.rms = points.empty() ? 0.0 : std::sqrt(sum / points.size());
}

SurfaceFit fit_plane(const Plane& model, const std::vector<Vec3>& points) {
  SurfaceFit f;
  f.surface = model;
  if (points.size() < 3) {
    f.problem = "a plane fit needs at least 3 points, got " + std::to_string(points.size());
    return f;
  }
  Vec3 centroid = Vec3::Zero();
  for (const Vec3& p : points) centroid += p;
  centroid /= double(points.size());
  Eigen::MatrixXd m(points.size(), 3);
  for (std::size_t i = 0; i < points.size(); ++i) m.row(i) = (points[i] - centroid).transpose();
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(m, Eigen::ComputeThinV);
  const Eigen::Vector3d sv = svd.singularValues();
  if (sv(1) <= 1e-12 * sv(0)) {
    f.problem = "the points are collinear: no unique plane";
    return f;
  }
  Vec3 n = svd.matrixV().col(2);
  if (n.dot(model.frame.z) < 0) n = -n;  // keep the model's normal sense
  // Keep the model's origin (projected) and x direction so the frame does not jump.
  const Vec3 origin = model.frame.origin - (model.frame.origin - centroid).dot(n) * n;
  f.surface = Plane{frame_from_axis(origin, n, model.frame.x)};
  f.converged = true;
  measure(f, points);
  return f;
}

// Curved surfaces: least squares over the surface's own parameters (surface_params.h:
// axis lines and unit axes on Ceres manifolds, so no gauge freedom is left), one residual
// per point, its signed distance over `scale` so the problem is equally conditioned at
// every model size. Radii stay positive and a cone's half-angle keeps its sign (bounds),
// so the result is a surface of the same kind and sense.
SurfaceFit fit_with_ceres(const Surface& model, const std::vector<Vec3>& points) {
  SurfaceFit f;
  f.surface = model;
  Vec3 lo = points.front(), hi = points.front();
  for (const Vec3& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double scale = std::max((hi - lo).norm(), surface_scale(model));
  if (!(scale > 0)) {
    f.problem = "the points are all the same";
    return f;
  }
  std::optional<SurfaceParams> q = params_of(model);
  if (!q) {
    f.problem = std::string("no parameters for a ") + surface_type_name(model);
    return f;
  }
  const double w = 1.0 / scale;
  ceres::Problem::Options po;
  po.cost_function_ownership = ceres::TAKE_OWNERSHIP;
  ceres::Problem problem(po);
  const auto blocks = q->blocks();
  for (std::size_t k = 0; k < blocks.size(); ++k) {
    problem.AddParameterBlock(blocks[k].first, blocks[k].second);
    if (ceres::Manifold* m = q->manifold(k)) problem.SetManifold(blocks[k].first, m);
  }
  // The shape block (radii, half-angle) is the last; keep it inside the valid shapes.
  double* shape = blocks.back().first;
  constexpr double kAngleMargin = 1e-6;
  switch (q->kind) {
    case SurfaceKind::cylinder:
    case SurfaceKind::sphere: problem.SetParameterLowerBound(shape, 0, 1e-9 * scale); break;
    case SurfaceKind::cone:
      problem.SetParameterLowerBound(shape, 0, 0.0);
      problem.SetParameterLowerBound(shape, 1, shape[1] > 0 ? kAngleMargin : -kPi / 2 + kAngleMargin);
      problem.SetParameterUpperBound(shape, 1, shape[1] > 0 ? kPi / 2 - kAngleMargin : -kAngleMargin);
      break;
    case SurfaceKind::torus:
      problem.SetParameterLowerBound(shape, 0, 0.0);
      problem.SetParameterLowerBound(shape, 1, 1e-9 * scale);
      break;
    case SurfaceKind::plane: break;
  }
  std::vector<double*> used;
  for (const Vec3& p : points) {
    ceres::CostFunction* c = on_solved_surface(*q, false, p, &w, used);
    problem.AddResidualBlock(c, nullptr, used);
  }
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = 200;
  options.function_tolerance = 1e-15;
  options.parameter_tolerance = 1e-14;
  options.gradient_tolerance = 1e-20;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  geo::quiet_solver_log();
  ceres::Solve(options, &problem, &summary);
  if (!summary.IsSolutionUsable()) {
    f.problem = "the solver stopped without a usable fit: " + summary.message;
    return f;
  }
  const Surface fitted = surface_from(model, *q);
  if (const std::string bad = surface_problem(fitted); !bad.empty()) {
    f.problem = "the fit is no valid surface: " + bad;
    return f;
  }
  f.surface = fitted;
  f.converged = true;
  measure(f, points);
  return f;
}

}  // namespace

SurfaceFit fit_surface_like(const Surface& model, const std::vector<Vec3>& points) {
  SurfaceFit f;
  f.surface = model;
  if (const std::string p = surface_problem(model); !p.empty()) {
    f.problem = "model: " + p;
    return f;
  }
  // Reshaping a free-form surface is not something kintsugi does (it keeps them exactly).
  if (is_freeform(model)) {
    f.problem = std::string("the ") + surface_type_name(model) + " would have to be reshaped, which kintsugi does not do to free-form surfaces";
    return f;
  }
  if (const auto* p = std::get_if<Plane>(&model)) return fit_plane(*p, points);
  const std::size_t needed = std::holds_alternative<Sphere>(model) ? 4 : std::holds_alternative<Cylinder>(model) ? 5 : 7;
  if (points.size() < needed) {
    f.problem = std::string("a ") + surface_type_name(model) + " fit needs at least " + std::to_string(needed) +
                " points, got " + std::to_string(points.size());
    return f;
  }
  return fit_with_ceres(model, points);
}

}  // namespace kintsugi::geo
