// Surface-surface intersection (paper section 4.1: "the geometry of the inserted edge is
// found by intersecting the faces on either side of it") and the point where several
// surfaces meet (multiple-face gaps).
//
// Closed forms where they exist (spec/geometry.md, "Intersections"):
//   plane-plane              line
//   plane-cylinder           two lines / tangent line (axis parallel), circle, ellipse
//   plane-cone               circle, ellipse, lines through the apex (plane through apex);
//                            parabola and hyperbola branches are marched
//   plane-sphere             circle
//   plane-torus              circles when the plane is perpendicular to the axis or
//                            contains it; otherwise marched
//   coaxial pairs of cylinder / cone / sphere / torus (and a sphere whose centre is on
//   the other's axis, any two spheres): circles from the meridian profiles
//   parallel cylinders       lines
// Everything else is marched: a Polyline whose vertices lie within `precision` of both
// surfaces and whose chords stay within `chordal_error` of the true curve (checked at
// every chord midpoint), traced within `region`. Marching stops at singular points
// (tangency, self-crossing, a cone apex), so a branch through one comes back as two
// polylines meeting there; tangential contacts without a sign change and loops smaller
// than the seed grid spacing can be missed (seed grid: `seed_grid`² samples of each
// surface over the region).
#pragma once

#include "geometry/box.h"
#include "geometry/tolerance.h"
#include "geometry/types.h"

#include <optional>
#include <string>
#include <vector>

namespace kintsugi::geo {

struct IntersectOptions {
  double precision = 1e-9;      // "lies on" and degeneracy threshold (a length)
  double chordal_error = 1e-6;  // largest chord deviation of a marched polyline
  Box region;                   // region of interest: required to bound unbounded branches
  int seed_grid = 48;           // samples per parameter direction when seeding the march

  // precision from the tolerances, chordal error Tolerances::intersection_chordal().
  static IntersectOptions for_model(const Tolerances& tol, const Box& region) {
    IntersectOptions o;
    o.precision = tol.precision;
    o.chordal_error = tol.intersection_chordal();
    o.region = region;
    return o;
  }
};

enum class IntersectionKind {
  curves,      // `curves` (and possibly isolated `points`) hold the result
  empty,       // the surfaces do not meet (within precision / inside the region)
  coincident,  // the surfaces are the same (within precision): no curve
  failed,      // could not be computed; `problem` says why
};

struct SurfaceIntersection {
  IntersectionKind kind = IntersectionKind::empty;
  std::vector<Curve> curves;
  std::vector<Vec3> points;  // isolated contacts (tangent plane on a sphere, touching apex, ...)
  bool marched = false;      // true when `curves` are Polylines from the march
  std::string problem;
};

SurfaceIntersection intersect_surfaces(const Surface& a, const Surface& b, const IntersectOptions& options);
// Just the curves (empty for empty / coincident / failed).
std::vector<Curve> intersect(const Surface& a, const Surface& b, const IntersectOptions& options);

// The intersection curves as the free-form backend computes them (OpenCASCADE's
// GeomAPI_IntSS; B-spline curves within about `precision` of both surfaces), for any two
// surfaces, analytic ones too; empty without a backend or when it finds nothing. Where
// intersect() marches (no closed form), its polylines are 0.01 tol off the surfaces
// between their points, which a written file keeps; an edge can take one of these
// instead (repair/beautify_geometry.cpp, derive_edge_curve).
// With `near`: only the curves near those points (a marched branch's), found in the
// surfaces' parameter windows around them — several times faster on OpenCASCADE's Top.brep,
// whose tori and cylinders have no closed-form intersection.
std::vector<Curve> intersect_exact(const Surface& a, const Surface& b, double precision,
                                   const std::vector<Vec3>* near = nullptr);

struct BranchChoice {
  std::size_t index = 0;
  double distance = 0.0;  // max of the two end points' distances to the branch
};
// The branch passing nearest both end points (smallest max distance); nullopt if
// `curves` is empty. Used to pick the edge curve among several intersection branches.
std::optional<BranchChoice> select_branch(const std::vector<Curve>& curves, const Vec3& p_start, const Vec3& p_end);

}  // namespace kintsugi::geo
