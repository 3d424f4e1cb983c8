// Building blocks of the zoo: small topology changes made only with Euler operators,
// each followed by the geometry it needs (spec/defects.md says which defect uses which).
// They throw std::logic_error when an operator refuses (a wrong precondition here is a
// zoo bug, or a site the caller should not have chosen); callers inside a Transaction
// get the body back unchanged.
#pragma once

#include "geometry/types.h"
#include "kernel/body.h"
#include "kernel/euler.h"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace kintsugi::zoo {

using geo::Vec3;

template <class T>
T must(Result<T> r, const char* what) {
  if (!r) throw std::logic_error(std::string("zoo step ") + what + " refused: " + r.error().message);
  return r.value();
}

// ---- navigation ----------------------------------------------------------------------
HalfedgeH out_in_loop(const Body& b, VertexH v, LoopH l);  // invalid if v is not on l
HalfedgeH out_in_face(const Body& b, VertexH v, FaceH f);   // in any loop of f
HalfedgeH side_in_face(const Body& b, EdgeH e, FaceH f);    // the half-edge of e in f
std::vector<FaceH> faces_around(const Body& b, VertexH v);  // face(o) for o in outgoing(v)

// ---- plane geometry ------------------------------------------------------------------
const geo::Plane* plane_of(const Body& b, FaceH f);
// Outward unit normal of a planar face (surface normal, flipped if not same_sense).
Vec3 outward_normal(const Body& b, FaceH f);
// Newell normal (not normalised) of a loop's polygon: points outward for an outer loop.
Vec3 newell(const Body& b, LoopH l);
geo::Plane plane_through(const Vec3& point, const Vec3& normal);
// Gives f the plane through `point` with outward normal `normal`.
void set_plane(Body& b, FaceH f, const Vec3& point, const Vec3& normal);
// Plane of f's outer loop (Newell normal through the vertex centroid).
void fit_plane(Body& b, FaceH f);
// Intersection of three planes given as (point, normal); nullopt if nearly dependent.
std::optional<Vec3> meet3(const Vec3& p1, const Vec3& n1, const Vec3& p2, const Vec3& n2, const Vec3& p3,
                          const Vec3& n3);
std::optional<Vec3> meet3(const Body& b, FaceH f1, FaceH f2, FaceH f3);
// Straight lines through the end points of every edge at these vertices whose curve is
// a line (or missing).
void refit_lines(Body& b, const std::vector<VertexH>& vs);
void set_line(Body& b, EdgeH e);
// A circle for edge e about `normal` through e's vertex, centred at `centre`, running
// counter-clockwise about `normal` along half-edge h.
void set_circle(Body& b, HalfedgeH h, const Vec3& centre, const Vec3& normal);
double polygon_area(const std::vector<Vec3>& pts);  // |Newell| / 2
std::vector<Vec3> loop_points(const Body& b, LoopH l);

// ---- topology with geometry --------------------------------------------------------
// A new face inside face f bounded by the polygon pts (counter-clockwise about f's
// outward normal): f gets it as a ring. The new face has f's plane.
FaceH add_ring_face(Body& b, FaceH f, const std::vector<Vec3>& pts);
// A new disc face inside planar face f bounded by one circular edge (one vertex).
FaceH add_circle_face(Body& b, FaceH f, const Vec3& centre, double radius);
// Extrudes face g (a ring face made above) by d: side faces get their planes, g moves
// to the far end (its plane moves too). Returns the side faces in loop order.
std::vector<FaceH> extrude(Body& b, FaceH g, const Vec3& d);
// Extrudes a disc face (one circular edge) by d into a cylindrical boss: returns the
// cylinder face; the disc moves to the top.
FaceH extrude_disc(Body& b, FaceH g, const Vec3& d, double radius, const Vec3& centre);
// Raises a disc face g (one circular edge of radius r0 about `centre`) into a conical
// frustum `height` tall whose flat top has radius r1 (< r0): g becomes the cone face (a
// straight seam joins the two circles), the new top disc is returned.
FaceH raise_cone(Body& b, FaceH g, const Vec3& centre, double r0, double r1, double height);
// Raises a disc face g (one circular edge of radius r about `centre`) into a spherical
// dome `height` tall (height < r: less than a hemisphere): g becomes the sphere face,
// bounded by the circle and a seam arc (a strut) from the circle's vertex to the pole.
// Returns the pole.
VertexH raise_dome(Body& b, FaceH g, const Vec3& centre, double r, double height);
// Turns face g into the base of a pyramid with its apex at `apex`: the side faces
// (planar, in loop order of g's vertices) are returned; g is consumed (it becomes one
// of the side faces).
std::vector<FaceH> raise_pyramid(Body& b, FaceH g, const Vec3& apex);

// Cuts a new face off face(m): a path of straight edges from origin(m) through pts to
// target(m), inside face(m). The new face (m's side, with face(m)'s surface) is returned.
FaceH cut_off(Body& b, HalfedgeH m, const std::vector<Vec3>& pts);

// Replaces vertex v by a face: every edge at v is cut at where(o) (o the half-edge
// leaving v along it) and the cut points are joined in each face. Returns the new face
// (no surface set) and the cut vertices in rotation order of the outgoing half-edges.
struct Truncation {
  FaceH face;
  std::vector<VertexH> corners;
};
Truncation truncate_vertex(Body& b, VertexH v, const std::function<Vec3(HalfedgeH)>& where);

// Handles as text.
template <class H>
std::string name(H h) {
  return h.str();
}

}  // namespace kintsugi::zoo
