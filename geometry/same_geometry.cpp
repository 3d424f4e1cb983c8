#include "geometry/same_geometry.h"

#include "geometry/frame.h"
#include "geometry/surface.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

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

// Parameter vector: [origin shift (3), rotation vector (3), shape (0-2)], lengths in
// units of `scale` so the problem is equally conditioned at every model size.
struct Param {
  const Surface& model;
  double scale;

  Surface build(const Eigen::VectorXd& p) const {
    const Vec3 shift = p.segment<3>(0) * scale;
    const Vec3 w = p.segment<3>(3);
    const Eigen::Matrix3d r = w.norm() > 0 ? Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix()
                                            : Eigen::Matrix3d::Identity();
    return std::visit(
        [&](const auto& s) -> Surface {
          using T = std::decay_t<decltype(s)>;
          if constexpr (std::is_same_v<T, std::monostate> || !requires { s.frame; }) {
            return s;  // free-form surfaces are never refitted (fit_surface_like refuses them)
          } else {
            T out = s;
            out.frame.origin = s.frame.origin + shift;
            out.frame.x = (r * s.frame.x).normalized();
            out.frame.z = (r * s.frame.z).normalized();
            if constexpr (std::is_same_v<T, Cylinder> || std::is_same_v<T, Sphere>) {
              out.radius = s.radius + p(6) * scale;
            } else if constexpr (std::is_same_v<T, Cone>) {
              out.radius = s.radius + p(6) * scale;
              out.half_angle = s.half_angle + p(7);
            } else if constexpr (std::is_same_v<T, Torus>) {
              out.major_radius = s.major_radius + p(6) * scale;
              out.minor_radius = s.minor_radius + p(7) * scale;
            }
            return out;
          }
        },
        model);
  }
  int size() const {
    if (std::holds_alternative<Cone>(model) || std::holds_alternative<Torus>(model)) return 8;
    return 7;
  }
};

SurfaceFit fit_levenberg_marquardt(const Surface& model, const std::vector<Vec3>& points) {
  SurfaceFit f;
  f.surface = model;
  Vec3 lo = points.front(), hi = points.front();
  for (const Vec3& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double scale = std::max((hi - lo).norm(), surface_scale(model));
  if (!(scale > 0)) {
    f.problem = "the points are all the same";
    return f;
  }
  const Param param{model, scale};
  const int n = param.size(), m = static_cast<int>(points.size());
  auto residuals = [&](const Eigen::VectorXd& p, Eigen::VectorXd& r) {
    const Surface s = param.build(p);
    if (!surface_problem(s).empty()) return false;  // e.g. a radius went negative
    r.resize(m);
    for (int i = 0; i < m; ++i) r(i) = signed_distance(s, points[i]) / scale;
    return true;
  };
  Eigen::VectorXd p = Eigen::VectorXd::Zero(n), r;
  residuals(p, r);
  double cost = r.squaredNorm(), lambda = 1e-3;
  const double h = 1e-7;
  for (int it = 0; it < 200; ++it) {
    Eigen::MatrixXd jac(m, n);
    Eigen::VectorXd rp, rm;
    for (int k = 0; k < n; ++k) {
      Eigen::VectorXd q = p;
      q(k) += h;
      if (!residuals(q, rp)) {
        q(k) = p(k) - h;  // one-sided the other way at a bound
        residuals(q, rp);
        jac.col(k) = (r - rp) / h;
        continue;
      }
      q(k) = p(k) - h;
      jac.col(k) = residuals(q, rm) ? Eigen::VectorXd((rp - rm) / (2 * h)) : Eigen::VectorXd((rp - r) / h);
    }
    const Eigen::MatrixXd jtj = jac.transpose() * jac;
    const Eigen::VectorXd g = jac.transpose() * r;
    // Gauge directions (rotation about a symmetry axis, sliding along it) have zero
    // curvature: the small absolute damping keeps the system solvable and the step
    // zero along them.
    const double floor = 1e-12 * std::max(1.0, jtj.diagonal().maxCoeff());
    bool improved = false;
    for (int tries = 0; tries < 20 && !improved; ++tries) {
      Eigen::MatrixXd a = jtj;
      for (int k = 0; k < n; ++k) a(k, k) += lambda * jtj(k, k) + floor;
      const Eigen::VectorXd step = -a.ldlt().solve(g);
      Eigen::VectorXd trial = p + step, rt;
      if (residuals(trial, rt) && rt.squaredNorm() < cost) {
        const double gain = cost - rt.squaredNorm();
        p = trial, r = rt, cost = rt.squaredNorm();
        lambda = std::max(lambda / 3, 1e-12);
        improved = true;
        if (gain <= 1e-15 * std::max(cost, 1e-30) || step.norm() < 1e-13) it = 1 << 20;  // converged
      } else {
        lambda *= 4;
      }
    }
    if (!improved) break;  // no descent left: at a minimum (to rounding)
  }
  f.surface = param.build(p);
  // Cylinders: slide the origin back to the foot of the model's origin on the new axis.
  if (auto* c = std::get_if<Cylinder>(&f.surface)) {
    const Vec3 o = std::get<Cylinder>(model).frame.origin;
    c->frame.origin += (o - c->frame.origin).dot(c->frame.z) * c->frame.z;
  }
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
  return fit_levenberg_marquardt(model, points);
}

}  // namespace kintsugi::geo
