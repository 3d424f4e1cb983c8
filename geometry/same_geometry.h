// "Same geometry within tolerance" (paper 4.5: two adjacent faces with the same geometry
// are merged) defined as a distance, so it means the same for every surface type and
// every scale (spec/geometry.md, "Same geometry"):
//
//   deviation(a, b) = max( max_{p ∈ samples_a} |d_b(p)|,  max_{q ∈ samples_b} |d_a(q)| )
//
// where samples_a are points of the region of interest on a (e.g. the tessellation
// vertices of face A from area.h) and d_s the signed distance to s. It is the
// two-sided (Hausdorff-like) deviation of the two surfaces over the faces' regions,
// symmetric by construction, zero for identical surfaces, and it compares surfaces of
// different types too (a nearly-flat cylinder patch and a plane). Two faces have the
// same geometry when deviation <= the length tolerance.
#pragma once

#include "geometry/types.h"

#include <limits>
#include <string>
#include <vector>

namespace kintsugi::geo {

// With `enough`, stops at the first sample farther than that and returns its distance (a
// lower bound, more than `enough`): all a caller comparing against `enough` needs. Each
// distance to a free-form surface is a projection, often a global search, so a pair of
// unlike B-spline faces is told apart by one sample instead of all of them.
double surface_deviation(const Surface& a, const Surface& b, const std::vector<Vec3>& samples_a,
                         const std::vector<Vec3>& samples_b,
                         double enough = std::numeric_limits<double>::infinity());

inline bool same_geometry(const Surface& a, const Surface& b, const std::vector<Vec3>& samples_a,
                          const std::vector<Vec3>& samples_b, double length_tolerance) {
  return surface_deviation(a, b, samples_a, samples_b, length_tolerance) <= length_tolerance;
}

struct SurfaceFit {
  Surface surface;              // same type as the model
  double rms = 0.0;             // root-mean-square signed distance of the points
  double max_deviation = 0.0;   // largest |signed distance|
  bool converged = false;
  std::string problem;          // why the fit failed (then `surface` is the model)
};

// Least-squares refit of a surface of the model's type to `points`, starting from the
// model (repairs use it to give the union of two merged faces one surface). Planes: SVD
// of the centred points (closed form). Other types: a Ceres least-squares problem on the
// signed distances over the surface's parameter blocks (geometry/surface_params.h). The
// result keeps the model's orientation (normal sense) and, where the type allows, its
// frame x direction.
SurfaceFit fit_surface_like(const Surface& model, const std::vector<Vec3>& points);

}  // namespace kintsugi::geo
