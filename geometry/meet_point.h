// The point where several surfaces meet (paper 4.1, multiple-face gaps: "if all
// intersection edges meet at a single point (within tolerance), we replace this gap by
// a vertex").
#pragma once

#include "geometry/types.h"

#include <string>
#include <vector>

namespace kintsugi::geo {

enum class MeetStatus {
  exact,            // three planes with independent normals: solved directly
  least_squares,    // least-squares solution, residual within tolerance
  underdetermined,  // normals span < 3 directions at the solution: the surfaces meet in a
                    // curve or surface; `point` is the meeting point nearest the guess
  no_point,         // best point found is farther than `tolerance` from some surface
  degenerate,       // parallel (or otherwise dependent) surfaces with no common point
};
const char* meet_status_name(MeetStatus s);

struct MeetPoint {
  Vec3 point = Vec3::Zero();
  double residual = 0.0;  // max |signed distance| of `point` to the surfaces
  MeetStatus status = MeetStatus::no_point;
  std::string problem;    // for no_point / degenerate: which surface is how far away
};

// Solves for the point nearest `guess` lying on all `surfaces` (planes: the minimum-norm
// least-squares step, closed form; curved surfaces: Ceres, with a prior that plays the
// same part), so an underdetermined system returns the solution nearest the guess. `tolerance` is the length tolerance deciding "meets"; `precision` the
// modelling precision used for rank decisions and convergence.
MeetPoint meet_point(const std::vector<Surface>& surfaces, const Vec3& guess, double tolerance, double precision);

}  // namespace kintsugi::geo
