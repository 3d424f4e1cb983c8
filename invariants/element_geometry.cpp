#include "invariants/element_geometry.h"

#include "geometry/curve.h"
#include "geometry/distance.h"
#include "geometry/polygon.h"

#include <cmath>
#include <variant>

namespace kintsugi {

std::vector<geo::Vec3> halfedge_polyline(const Body& b, HalfedgeH h, double chordal) {
  const geo::Vec3& p0 = b.point(b.origin(h));
  const geo::Vec3& p1 = b.point(b.target(h));
  const geo::Curve& c = b.curve(edge_of(h));
  if (std::holds_alternative<std::monostate>(c) || std::holds_alternative<geo::Line>(c)) return {p0, p1};
  // The curve runs along half-edge 2e: sample it from its start to its end, then reverse
  // for the other half-edge. A self-loop edge covers the full period.
  bool forward = (h.idx() & 1u) == 0;
  const geo::Vec3& s = forward ? p0 : p1;
  const geo::Vec3& t = forward ? p1 : p0;
  double coincide = (b.origin(h) == b.target(h)) ? std::max(chordal, 1e-300) : 0.0;
  geo::ParameterRange r = geo::parameter_range(c, s, t, coincide);
  std::vector<geo::Vec3> pts = geo::sample_curve(c, r.t0, r.t1, std::max(chordal, 1e-300));
  if (pts.size() < 2) return {p0, p1};
  // Pin the ends to the vertices: the polyline is the edge, whatever the projection did.
  pts.front() = s;
  pts.back() = t;
  if (!forward) std::reverse(pts.begin(), pts.end());
  return pts;
}

geo::Box halfedge_box(const Body& b, HalfedgeH h, double chordal) {
  geo::Box box;
  box.add(b.point(b.origin(h)));
  box.add(b.point(b.target(h)));
  const geo::Curve& c = b.curve(edge_of(h));
  if (std::holds_alternative<std::monostate>(c) || std::holds_alternative<geo::Line>(c)) return box;
  if (const auto* circle = std::get_if<geo::Circle>(&c)) {
    // The circle's extent along axis i is r·sin of the angle between its normal and the
    // axis: r·sqrt(1 - n_i²) (widened by a rounding's worth: the samples are evaluated).
    const geo::Vec3 n = circle->frame.z.normalized();
    const geo::Vec3 half = (1 + 1e-12) * circle->radius * (geo::Vec3::Ones() - n.cwiseProduct(n)).cwiseMax(0.0).cwiseSqrt();
    if (half.allFinite()) {
      box.add(circle->frame.origin - half);
      box.add(circle->frame.origin + half);
      return box;
    }
  }
  for (const geo::Vec3& p : halfedge_polyline(b, h, chordal)) box.add(p);
  return box;
}

double edge_length(const Body& b, EdgeH e) {
  HalfedgeH h = halfedge_of(e, 0);
  const geo::Curve& c = b.curve(e);
  const geo::Vec3& p0 = b.point(b.origin(h));
  const geo::Vec3& p1 = b.point(b.target(h));
  if (std::holds_alternative<std::monostate>(c) || std::holds_alternative<geo::Line>(c)) return (p1 - p0).norm();
  double coincide = (b.origin(h) == b.target(h)) ? 1e-12 * (1 + p0.norm()) : 0.0;
  geo::ParameterRange r = geo::parameter_range(c, p0, p1, coincide);
  return geo::arc_length(c, r.t0, r.t1);
}

namespace {

// One loop as a closed polyline (its first point not repeated), appended to `pts`.
// Walked in place, and a straight side adds its start without a polyline of its own:
// the planar faces' measures in a whole-model detection allocated for every edge.
void append_loop(const Body& b, LoopH l, double chordal, std::vector<geo::Vec3>& pts) {
  if (b.is_lone(l)) {
    pts.push_back(b.point(b.lone_vertex(l)));
    return;
  }
  b.for_each_halfedge(l, [&](HalfedgeH h) {
    const geo::Curve& c = b.curve(edge_of(h));
    if (std::holds_alternative<std::monostate>(c) || std::holds_alternative<geo::Line>(c)) {
      pts.push_back(b.point(b.origin(h)));  // halfedge_polyline's {origin, target}, less its end
    } else {
      std::vector<geo::Vec3> seg = halfedge_polyline(b, h, chordal);
      pts.insert(pts.end(), seg.begin(), seg.end() - 1);  // the end is the next one's start
    }
  });
}

}  // namespace

std::vector<std::vector<geo::Vec3>> face_boundary(const Body& b, FaceH f, double chordal) {
  std::vector<std::vector<geo::Vec3>> loops;
  for (LoopH l : b.loops_of(f)) append_loop(b, l, chordal, loops.emplace_back());
  return loops;
}

std::vector<geo::Vec3> surface_samples(const Body& b, FaceH f, double chordal) {
  std::vector<geo::Vec3> pts;
  const bool planar = std::holds_alternative<geo::Plane>(b.surface(f));
  for (LoopH l : b.loops_of(f)) {
    append_loop(b, l, chordal, pts);
    if (planar) break;  // the outer loop comes first
  }
  return pts;
}

geo::RegionMeasure face_measure(const Body& b, FaceH f, double chordal, bool area_and_bounds_only, int freeform_grid) {
  geo::AreaOptions o;
  o.freeform_grid = freeform_grid;
  o.reversed = !b.same_sense(f);
  o.area_and_bounds_only = area_and_bounds_only;
  return geo::measure_region(b.surface(f), face_boundary(b, f, chordal), o);
}

std::optional<AreaAndBounds> face_area_and_bounds(const Body& b, FaceH f, double chordal, int freeform_grid) {
  if (const auto* plane = std::get_if<geo::Plane>(&b.surface(f))) {
    const geo::Vec3 outward = plane->frame.z.normalized() * (b.same_sense(f) ? 1.0 : -1.0);
    AreaAndBounds r{0.0, {}};
    // The outer loop turns counter-clockwise about the outward normal, rings clockwise;
    // struts and seams are walked both ways and add nothing. One buffer for all loops.
    std::vector<geo::Vec3> loop;
    for (LoopH l = b.outer_loop(f); l.valid(); l = b.next_in_face(l)) {
      loop.clear();
      append_loop(b, l, chordal, loop);
      r.area += outward.dot(geo::polygon_normal(loop)) / 2;
      for (const geo::Vec3& p : loop) r.bounds.add(p);
    }
    if (r.area > 0 && std::isfinite(r.area)) return r;
  }
  geo::RegionMeasure m = face_measure(b, f, chordal, /*area_and_bounds_only=*/true, freeform_grid);
  if (!m.ok()) return std::nullopt;
  return AreaAndBounds{m.area, m.bounds};
}

double vertex_edge_distance(const Body& b, VertexH v, EdgeH e, double chordal) {
  return geo::point_polyline(b.point(v), halfedge_polyline(b, halfedge_of(e, 0), chordal)).distance;
}

double edge_edge_distance(const Body& b, EdgeH e1, EdgeH e2, double chordal) {
  return geo::polyline_polyline(halfedge_polyline(b, halfedge_of(e1, 0), chordal),
                                halfedge_polyline(b, halfedge_of(e2, 0), chordal))
      .distance;
}

namespace {

// Curves and faces are sampled for the model's size with a chordal error of 1e-3 of a
// first estimate of that size: no tolerance exists yet (the default tolerance derives
// from the size), and a thousandth changes the diagonal by less than any decision cares.
constexpr double kSizeChordalRatio = 1e-3;

// A box that holds the whole of a sphere or torus (not only the face's part of it).
std::optional<geo::Box> closed_surface_box(const geo::Surface& s) {
  if (const auto* k = std::get_if<geo::Sphere>(&s)) return geo::Box::around(k->frame.origin, std::abs(k->radius));
  if (const auto* k = std::get_if<geo::Torus>(&s))
    return geo::Box::around(k->frame.origin, std::abs(k->major_radius) + std::abs(k->minor_radius));
  return std::nullopt;
}

}  // namespace

geo::Box body_bounds(const Body& b) {
  geo::Box box;
  for (VertexH v : b.vertices()) box.add(b.point(v));
  // Curved edges bulge beyond their vertices (a circle has one vertex): sample them coarsely.
  // The sampling scale: the vertices' extent, or a circle's radius where that is larger
  // (a torus or a sphere may have all its vertices in one point).
  double size = box.empty() ? 0.0 : box.diagonal();
  for (EdgeH e : b.edges()) {
    const geo::Curve& c = b.curve(e);
    if (const auto* k = std::get_if<geo::Circle>(&c)) size = std::max(size, std::abs(k->radius));
    if (const auto* k = std::get_if<geo::Ellipse>(&c)) size = std::max(size, std::abs(k->major_radius));
  }
  if (!(size > 0)) size = 1.0;
  for (EdgeH e : b.edges()) {
    const geo::Curve& c = b.curve(e);
    if (std::holds_alternative<geo::Line>(c) || std::holds_alternative<std::monostate>(c)) continue;
    for (const geo::Vec3& p : halfedge_polyline(b, halfedge_of(e, 0), kSizeChordalRatio * size)) box.add(p);
  }
  // Faces bulge beyond their boundaries only on spheres and tori (a sphere bounded by one
  // seam arc, a dome): planes, cylinders and cones are linear along their rulings, so a
  // face's extent in any direction is reached on its boundary. A sphere or torus face is
  // measured only where its whole surface is not already inside the box: cheap for a
  // model whose fillets lie within it.
  for (FaceH f : b.faces()) {
    std::optional<geo::Box> whole = closed_surface_box(b.surface(f));
    if (!whole || (!box.empty() && box.contains(whole->min) && box.contains(whole->max))) continue;
    geo::RegionMeasure m = face_measure(b, f, kSizeChordalRatio * std::max(size, whole->diagonal()), true);
    const geo::Box& add = m.ok() && !m.bounds.empty() ? m.bounds : *whole;
    box.add(add.min);
    box.add(add.max);
  }
  return box;
}

double model_size(const Body& b) {
  geo::Box box = body_bounds(b);
  return box.empty() ? 0.0 : box.diagonal();
}

}  // namespace kintsugi
