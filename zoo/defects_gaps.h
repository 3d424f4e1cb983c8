// Gaps made the way a scanner makes them (issue 13): a small region of space saw no data
// — a ball, a short cylinder or an irregular convex blob, 0.2-0.7 tolerance across — so
// every face stops at the region's border. The gap is the part of the model's surface
// inside the region: centred inside a face (a face gap), on an edge (an edge gap) or on a
// vertex (a multiple-face gap). Its border edges follow the curve where the face's surface
// leaves the region (polylines on the surface), split into a few edges per face; the
// interrupted edges keep their curves. Planar and curved faces, convex and concave edges.
#pragma once

#include "zoo/defects.h"

#include <functional>
#include <string>
#include <vector>

namespace kintsugi::zoo {

// A convex region of missing data: inside where phi < 0.
struct MissingRegion {
  enum Shape { ball, short_cylinder, blob } shape = ball;
  Vec3 centre = Vec3::Zero();
  double radius = 0.0;             // ball, cylinder; the blob's mean radius
  Vec3 axis = Vec3::UnitZ();       // cylinder
  double half_length = 0.0;        // cylinder
  Eigen::Matrix3d shape_matrix = Eigen::Matrix3d::Identity();  // blob: an ellipsoid ...
  std::vector<std::pair<Vec3, double>> cuts;                  // ... cut by half-spaces n·(p - centre) <= d
  double phi(const Vec3& p) const;
  // A random region of this shape about `centre`, about `across` wide (its largest extent
  // through the centre stays below `across`).
  static MissingRegion random(Shape shape, const Vec3& centre, double across, Rng& rng);
};
const char* shape_name(MissingRegion::Shape s);

namespace make {

// A face gap: the region centred on face f's surface at `centre`, well inside f.
KnownDefect scan_gap_in_face(Body& b, FaceH f, const MissingRegion& r, int edges);
// An edge gap: the region centred on edge e (whose two faces may be curved, the edge
// straight or circular, convex or concave); `per_side` edges in each face.
KnownDefect scan_gap_on_edge(Body& b, EdgeH e, const MissingRegion& r, int per_side);
// A multiple-face gap: the region centred on vertex v (three or more distinct faces).
KnownDefect scan_gap_at_vertex(Body& b, VertexH v, const MissingRegion& r, int per_face);

}  // namespace make

// Places in b for a scan-like gap of type t (face_gap: faces; edge_gap: edges;
// multi_face_gap: vertices), sizes 0.2-0.7 tol across drawn from rng. Each maker throws
// Unsuitable when the region does not fit the site.
struct GapSite {
  std::function<KnownDefect(Body&)> make;
  std::string where;
};
std::vector<GapSite> gap_sites(const Body& b, ProblemType t, double tol, Rng& rng, const std::vector<FaceH>& faces,
                               const std::vector<EdgeH>& edges, const std::vector<VertexH>& vertices);

}  // namespace kintsugi::zoo
