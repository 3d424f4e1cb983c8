// Internal to beautification: what the passes share (repair/pass_*.cpp).
#pragma once

#include "geometry/tolerance.h"
#include "kernel/body.h"
#include "repair/beautify.h"
#include "repair/pass.h"
#include "repair/touched.h"

#include <optional>
#include <set>
#include <string>
#include <vector>

namespace kintsugi::detail {

using RepairCall = RepairContext;

// ---- shared helpers (beautify_geometry.cpp) -------------------------------------
// The curve for edge e from the faces beside it: the line through its vertices when
// both are planes, else the branch of their intersection through its vertices, oriented
// like the edge's present curve. nullopt with *why when none is within tolerance.
std::optional<geo::Curve> derive_edge_curve(const Body& b, EdgeH e, const geo::Tolerances& tol, std::string* why);

// After joining pieces into edge `keep` (jekv): pieces of one closed, non-straight curve
// (a circle cut in pieces) keep that curve; otherwise keep gets derive_edge_curve's.
// Empty on success, else why not.
std::string refit_joined_edge(Body& b, EdgeH keep, bool pieces_of_one_curve, const geo::Tolerances& tol);

// A seam (an edge with one face on both sides, where a sphere, cylinder, cone or torus
// closes) runs along u = 0 of its face's surface. A seam vertex that a repair moved round
// the axis (a sphere's rim vertex, placed where a refitted plane meets the sphere) would
// leave it: the surface is turned about its axis (the same surface, parametrised from
// the vertex's meridian) so that u = 0 passes through the vertex again, by at most
// 0.1 rad, when the seam's other end is on the axis (a pole). derive_edge_curve then
// gives the seam the iso-curve there.
void align_seams(Body& b, const std::vector<VertexH>& moved, const geo::Tolerances& tol, Touched& touched);

// The frame of a surface periodic about an axis (u of spec/geometry.md, its seam at
// u = 0 about frame.z): sphere, cylinder, cone, torus; null for the others.
const geo::Frame* seam_frame(const geo::Surface& s);

// Puts each vertex at the point nearest its guess where the surfaces of its faces meet
// (geo::meet_point; least squares for more than three), then re-derives the curves of
// every edge at those vertices. Fails when the surfaces do not meet within tolerance or
// the point is more than `max_move` from the guess. Faces in `ignore` are left out of the
// meeting (a neighbour with nearly the same surface, still to be merged, would make the
// point ill-conditioned).
// With `coincide` > 0 it also fails, before deriving any curve, when an edge at those
// vertices joins two distinct ones within `coincide` of each other (coinciding_ends).
std::string place_vertices(Body& b, const std::vector<std::pair<VertexH, geo::Vec3>>& guesses,
                           const geo::Tolerances& tol, double max_move, Touched& touched,
                           const std::set<FaceH>& ignore = {}, double coincide = 0.0);

// The validity gate's refusal of an edge at one of `vertices` whose two distinct vertices
// lie within `coincide` (its limit for two points being one: RepairContext::coincide) of
// each other, spelled as the gate spells it; "" when there is none. A pass that checks
// this before the expensive part of its geometry (exact intersections of its edges, the
// region solve) refuses what the gate would refuse, without computing it: Top.brep at
// --tol 0.171 has four slivers whose collapse brings the ends of an edge 0.027 long within
// 1.5e-4 of each other, where the input's own accuracy is 1e-3.
std::string coinciding_ends(const Body& b, const std::set<VertexH>& vertices, double coincide);

// Faces on either side of the edges around v (no border cycles), without repeats.
std::vector<FaceH> faces_around(const Body& b, VertexH v);

// Largest deviation of the touched elements and their neighbourhoods (vertices from the
// curves and surfaces of their edges and faces, edges from both faces' surfaces); sets
// *why for a missing curve/surface or a face left with fewer than three straight sides.
double local_deviation(const Body& b, const Touched& t, const geo::Tolerances& tol, std::string* why);

double face_area(const Body& b, FaceH f, const geo::Tolerances& tol);

// A length or deviation as the reasons and notes print it (three significant digits).
std::string fmt(double d);

// The loops that joined a face from journal entry `from` on without an element of theirs
// being changed: a new face's loops, the rings kef moved to the kept face, the ring kemr
// made, kfmrh's ring and the ring mfkrh made a face of. The validity gate and the
// detection near a repair take a face with many loops near its changed elements only
// (invariants/region_validity.h), so these count as changed: their edges (a lone loop's
// vertex) join `touched`.
void touch_rearranged_loops(const Body& b, std::size_t from, Touched& touched);

}  // namespace kintsugi::detail
