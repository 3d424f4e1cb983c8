// Free-form geometry (B-spline curves and surfaces, surfaces of revolution, extrusion and
// offset surfaces; geometry/types.h) is evaluated, projected and intersected by a
// backend that a library registers here: kintsugi_occt registers OpenCASCADE's geometry
// classes (geometry/occt/freeform_occt.cpp, io::register_freeform_backend()). geometry/
// itself does not link OpenCASCADE: without a backend, free-form geometry is refused when
// read, and the functions of surface.h and curve.h throw std::runtime_error on it.
#pragma once

#include "geometry/types.h"

#include <optional>
#include <string>
#include <vector>

namespace kintsugi::geo {

struct FreeformBackend {
  // Point and first derivatives at (u, v).
  Vec3 (*surface_d1)(const Surface& s, const Vec2& uv, Vec3* du, Vec3* dv);
  // The nearest point's parameters (within the surface's natural bounds).
  Vec2 (*surface_project)(const Surface& s, const Vec3& p);
  // Natural parameter bounds; infinite for an extrusion's v.
  void (*surface_bounds)(const Surface& s, double* u0, double* u1, double* v0, double* v1);
  // Empty when the data make a valid surface, else why not.
  std::string (*surface_problem)(const Surface& s);
  // Point and first derivative at t.
  Vec3 (*curve_d1)(const Curve& c, double t, Vec3* d);
  double (*curve_project)(const Curve& c, const Vec3& p);
  void (*curve_bounds)(const Curve& c, double* t0, double* t1);
  double (*curve_length)(const Curve& c, double t0, double t1);
  // Points along [t0, t1] within `chordal` of the curve, both ends included.
  std::vector<Vec3> (*curve_sample)(const Curve& c, double t0, double t1, double chordal);
  std::string (*curve_problem)(const Curve& c);
  // Intersection curves of two surfaces (any of them free-form): each as a B-spline curve
  // (or an analytic curve where OpenCASCADE gives one). With `near` (not null, not
  // empty), only where the surfaces' parameters are within reach of those points: the
  // intersection near a known stretch, at a fraction of the cost of the whole.
  std::vector<Curve> (*intersect)(const Surface& a, const Surface& b, double precision, const std::vector<Vec3>* near);
  // Forgets the last projection's foot on s (the next projection searches afresh): where
  // several parameters give one point (a pole), which one a projection returns depends on
  // where it starts, and a face's parameter domain must not depend on what was projected
  // before it (geo::parameter_domain calls this first).
  void (*surface_forget)(const Surface& s);
};

// nullptr unregisters.
void set_freeform_backend(const FreeformBackend* b);
const FreeformBackend* freeform_backend();

// The backend, or a std::runtime_error saying that free-form geometry needs one.
const FreeformBackend& require_freeform();

// Why a body with free-form geometry cannot be used in this build ("" when it can).
std::string freeform_unavailable();

}  // namespace kintsugi::geo
