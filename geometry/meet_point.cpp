#include "geometry/meet_point.h"

#include "geometry/surface.h"
#include "geometry/solver_log.h"
#include "geometry/surface_params.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace kintsugi::geo {

const char* meet_status_name(MeetStatus s) {
  switch (s) {
    case MeetStatus::exact: return "exact";
    case MeetStatus::least_squares: return "least_squares";
    case MeetStatus::underdetermined: return "underdetermined";
    case MeetStatus::no_point: return "no_point";
    case MeetStatus::degenerate: return "degenerate";
  }
  return "?";
}

namespace {

struct Linearised {
  Eigen::MatrixXd normals;  // one unit row per surface
  Eigen::VectorXd dist;     // signed distances
};

Linearised linearise(const std::vector<Surface>& s, const Vec3& x) {
  Linearised l{Eigen::MatrixXd(s.size(), 3), Eigen::VectorXd(s.size())};
  for (std::size_t i = 0; i < s.size(); ++i) {
    const SurfacePoint c = closest_point(s[i], x);
    l.normals.row(i) = c.normal.transpose();
    l.dist(i) = c.distance;
  }
  return l;
}

// Minimum-norm least-squares step: singular directions below `cut` (relative to the
// largest) are dropped, so a rank-deficient system moves the least from the guess.
Vec3 min_norm_step(const Linearised& l, double cut, int& rank) {
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(l.normals, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd& sv = svd.singularValues();
  rank = 0;
  Eigen::VectorXd inv = Eigen::VectorXd::Zero(sv.size());
  for (Eigen::Index i = 0; i < sv.size(); ++i)
    if (sv(i) > cut * sv(0)) inv(i) = 1.0 / sv(i), ++rank;
  return -(svd.matrixV() * inv.asDiagonal() * svd.matrixU().transpose() * l.dist);
}

// Curved surfaces: a Ceres least-squares problem over the point, one residual per surface
// (its signed distance; the derivative is the unit normal there, geometry/surface_params.h)
// and a prior `cut`·|x − guess|. The prior is the Tikhonov form of the minimum-norm step:
// a direction the normals span with singular value σ ≫ cut is solved fully, one with
// σ ≪ cut (the surfaces meet along it, or nearly so) keeps the guess; at a solution it
// shifts the point by about cut²·|x − guess|/σ, far below the precision.
Vec3 solve_curved(const std::vector<Surface>& surfaces, const Vec3& guess, double cut) {
  double x[3] = {guess.x(), guess.y(), guess.z()};
  const double unit = 1.0;
  ceres::Problem problem;
  for (const Surface& s : surfaces) problem.AddResidualBlock(new OnFixedSurface(s, &unit), nullptr, x);
  problem.AddResidualBlock(new ceres::AutoDiffCostFunction<NearPoint, 3, 3>(new NearPoint{guess, cut}), nullptr, x);
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = 100;
  options.function_tolerance = 1e-16;
  options.parameter_tolerance = 1e-16;
  options.gradient_tolerance = 1e-24;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  geo::quiet_solver_log();
  ceres::Solve(options, &problem, &summary);
  return summary.IsSolutionUsable() ? Vec3(x[0], x[1], x[2]) : guess;
}

}  // namespace

MeetPoint meet_point(const std::vector<Surface>& surfaces, const Vec3& guess, double tolerance, double precision) {
  MeetPoint out;
  out.point = guess;
  if (surfaces.empty()) {
    out.status = MeetStatus::degenerate;
    out.problem = "no surfaces given";
    return out;
  }
  for (std::size_t i = 0; i < surfaces.size(); ++i) {
    const std::string p = surface_problem(surfaces[i]);
    if (!p.empty()) {
      out.status = MeetStatus::degenerate;
      out.problem = "surface " + std::to_string(i) + ": " + p;
      return out;
    }
  }
  // Directions whose singular value is below precision/tolerance cannot be resolved to
  // the tolerance: moving along them by `tolerance` changes the distances by < precision.
  const double cut = std::max(1e-12, precision / std::max(tolerance, precision));
  const bool planes = std::all_of(surfaces.begin(), surfaces.end(),
                                  [](const Surface& s) { return std::holds_alternative<Plane>(s); });
  int rank = 0;
  Vec3 x = guess;
  if (planes) {
    // Linear: the minimum-norm step from the guess is the solution (closed form; a second
    // step only removes rounding).
    for (int it = 0; it < 2; ++it) x += min_norm_step(linearise(surfaces, x), cut, rank);
  } else {
    x = solve_curved(surfaces, guess, cut);
  }
  Linearised l = linearise(surfaces, x);
  min_norm_step(l, cut, rank);  // the rank at the solution
  out.point = x;
  Eigen::Index worst = 0;
  out.residual = l.dist.cwiseAbs().maxCoeff(&worst);
  if (out.residual <= tolerance) {
    if (rank < 3) out.status = MeetStatus::underdetermined;
    else out.status = planes && surfaces.size() == 3 ? MeetStatus::exact : MeetStatus::least_squares;
    return out;
  }
  std::ostringstream why;
  if (planes && rank < 3) {
    out.status = MeetStatus::degenerate;
    why << "the planes are parallel (rank " << rank << ") and have no common point: surface " << worst
        << " is " << out.residual << " away";
  } else {
    out.status = MeetStatus::no_point;
    why << "no point within tolerance " << tolerance << ": surface " << worst << " (" << surface_type_name(surfaces[worst])
        << ") is " << out.residual << " away from the best point";
  }
  out.problem = why.str();
  return out;
}

}  // namespace kintsugi::geo
