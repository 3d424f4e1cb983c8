// The geometry that agrees with a repair's new topology (issue 16; paper sections 1.1
// and 5): after the repair's operators, one least-squares problem (Ceres) over the
// repair's region moves the surfaces of the faces there and the vertices on them until
// every vertex lies on every surface of its faces within the modelling precision, each
// surface moving only as far as the new topology forces it (data terms: points sampled on
// the face before the repair). Faces outside the region stay fixed, so the cost of one
// solve depends on the size of the region, not of the model.
//
// Solved: the five analytic surfaces (unit normals and axes on Ceres manifolds; radii,
// half-angles, centres). A face without a surface from before the repair (made by the
// repair) or with very many corners is held fixed; its vertices still move onto it.
#pragma once

#include "geometry/tolerance.h"
#include "kernel/body.h"
#include "problems/problem.h"
#include "repair/touched.h"

#include <map>
#include <set>
#include <string>
#include <vector>

namespace kintsugi::detail {

// A face as it was before the repair: its surface and points sampled on it (the corners
// and edge midpoints of its loops, projected onto the surface).
struct OriginalFace {
  geo::Surface surface;
  std::vector<geo::Vec3> samples;
  std::set<FaceH> neighbours;  // the faces across its edges
};
using OriginalFaces = std::map<FaceH, OriginalFace>;

// The faces within two rings of the problem's elements (faces around their vertices,
// and the faces around those faces' vertices): where a repair of it can act.
OriginalFaces snapshot_near(const Body& b, const Problem& p, const geo::Tolerances& tol);
// Those faces (the second ring only through faces of few corners), without their data.
std::set<FaceH> faces_near(const Body& b, const Problem& p);

struct SurfaceMove {
  FaceH face;
  double distance = 0.0;  // largest distance of an original sample from the new surface
};

struct RegionSolve {
  std::string why;                  // empty on success; else the constraints that cannot be met together
  bool solved = false;              // whether a solve ran (false: the region was already consistent)
  double max_residual = 0.0;        // largest distance of a region vertex from a surface of its faces, after
  std::vector<SurfaceMove> moved;   // each solved face, how far it moved
  int variable_faces = 0, variable_vertices = 0, residuals = 0;
  double seconds = 0.0;             // wall time of the solve (docs/benchmarks.md)
};

// The region of `touched` that solve_region takes in: its live faces and the faces around
// its live vertices and along its live edges.
std::set<FaceH> region_faces(const Body& b, const Touched& touched);

// Solves the region of `touched` (the faces around its vertices and edges, and its faces)
// and, on success, writes the solved surfaces, vertices and re-derived edge curves into b
// and records them in `touched`. When the constraints cannot be met (or force a surface
// further than the tolerance) b is left as it was and `why` names them; the caller rolls
// back its transaction on any failure.
// `weigh_zipped_by_area` (a pinch's repair): planes the repair zipped together and tied to
// one weigh in by area (region_solve.cpp).
RegionSolve solve_region(Body& b, Touched& touched, const OriginalFaces& original, const geo::Tolerances& tol,
                         bool weigh_zipped_by_area = false);

}  // namespace kintsugi::detail
