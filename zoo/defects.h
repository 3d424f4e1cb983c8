// One function per way of making a defect (spec/defects.md), used by the injector, the
// paper objects and the family. Each builds topology with Euler operators, then places
// vertices where the (possibly perturbed) surfaces actually meet, and returns what it
// made. A site that does not suit throws Unsuitable (nothing is changed before the
// checks that throw it, except where noted: callers hold a Transaction anyway).
#pragma once

#include "zoo/local_ops.h"
#include "zoo/random.h"
#include "zoo/zoo.h"

#include <stdexcept>

namespace kintsugi::zoo {

struct Unsuitable : std::runtime_error {
  using std::runtime_error::runtime_error;
};

namespace make {

// face_gap: a k-gon (k >= 3) of circumradius r about `centre` inside planar face f,
// whose far side is a border cycle. k = 0: one circular edge instead.
KnownDefect face_gap(Body& b, FaceH f, const Vec3& centre, double r, int k);

// edge_gap: edge of h (straight, between planar faces) loses the stretch [s0, s1]
// (arc length from origin(h)); the gap reaches `depth` into each face, bounded by
// `per_side` + 1 edges on each side.
KnownDefect edge_gap(Body& b, HalfedgeH h, double s0, double s1, double depth, int per_side);

// multi_face_gap: the corner at v is cut off by a plane `depth` below it (along the mean
// outward normal of its faces) and the cut face opened into a gap.
KnownDefect corner_gap(Body& b, VertexH v, double depth);

// small_face: the corner at v replaced by a small planar face of area `area`. With
// rng: when all faces at v are triangles (a pyramid apex), each is first turned about
// its base edge by a small random angle, as independent fitting does, and the small
// face is the fitted tip plane below where they meet.
KnownDefect small_face(Body& b, VertexH v, double area, Rng* rng);

// short_edge at a vertex of degree 4 whose faces are triangles: each face is turned about
// its base edge by a random angle; the four planes then meet in two points `length`
// apart, joined by the short edge.
KnownDefect apex_short_edge(Body& b, VertexH v, double length, Rng& rng);
// short_edge at a vertex of degree >= 4 with a triangular face `tri`: only tri is turned
// (about its base edge), which moves its corner `length` along the line where its two
// neighbours meet.
KnownDefect tilt_short_edge(Body& b, VertexH v, FaceH tri, double length);

// sliver_face: edge e (straight, between planar faces A and B, both ends of degree 3)
// replaced by a thin chamfer-like face cutting `wa` into A and `wb` into B.
KnownDefect chamfer(Body& b, EdgeH e, FaceH A, double wa, double wb);
// The same with the chamfer plane given (through `point`, normal ±`normal`): a plane not
// parallel to e makes a tapered sliver.
KnownDefect chamfer_plane(Body& b, EdgeH e, FaceH A, const Vec3& point, const Vec3& normal);

// same_geometry_faces: planar face f split between the midpoints of edges e1 and e2,
// the new half turned about the split line so that the two planes deviate by
// `deviation` over f.
KnownDefect split_and_tilt(Body& b, FaceH f, EdgeH e1, EdgeH e2, double deviation);
// same_geometry_faces on a curved face: a face on a cylinder or a cone bounded by two
// circles about its axis and two rulings (or a seam) split along the ruling through the
// middle of one end, both halves keeping the one surface — the face a CAD export or a fit
// leaves in two pieces (OpenCASCADE's bottle.brep has its fillets so). The split's ends
// are at least `min_gap` from the corners.
KnownDefect split_along_ruling(Body& b, FaceH f, double min_gap);

// mergeable_edges: a vertex on the curve of edge_of(h), at fraction `at` of its length.
KnownDefect split_edge(Body& b, HalfedgeH h, double at);

// short_edge_chain: edge_of(h) (line or circle) cut so that, starting at arc length
// `start` from origin(h), consecutive pieces have the given lengths.
KnownDefect cut_edge(Body& b, HalfedgeH h, double start, const std::vector<double>& pieces);

// small_face_chain: the corner at v replaced by a chain of small triangles (a fan for
// degree >= 4; two triangles with a bent edge for degree 3), corner cut at about
// `depth` along each edge, each face below area tol^2 by choice of depth.
KnownDefect small_face_chain(Body& b, VertexH v, double depth, Rng& rng);

// pinched_face: a block of depth `w` and height `height` raised on planar face f along
// the stretch [s0, s1] of its edge h (arc length from origin(h)), `offset` inside the edge:
// f is pinched between h's edge and the block's base edge.
KnownDefect boss_pinch(Body& b, HalfedgeH h, double s0, double s1, double offset, double w, double height);

}  // namespace make

// Whether every face at v is planar and every edge straight, and the corner convex (each
// edge leaves v at least a little against the mean outward normal); the mean normal.
std::optional<Vec3> convex_corner_axis(const Body& b, VertexH v);

}  // namespace kintsugi::zoo
