#include "invariants/geometry_check.h"

#include "geometry/curve.h"
#include "geometry/polygon.h"
#include "geometry/surface.h"
#include "geometry/tolerance.h"
#include "invariants/element_geometry.h"

#include <cmath>
#include <sstream>
#include <variant>

namespace kintsugi {

namespace {

std::string fmt(double d) {
  std::ostringstream os;
  os.precision(3);
  os << d;
  return os.str();
}

struct Run {
  const Body& b;
  double precision;
  GeometryReport r;

  // x and y name the elements: "x from the surface of y" (`from`) says what was
  // measured. The names are spelled only for a new largest deviation or a violation:
  // spelling them for every vertex and edge was most of a whole-body check's time.
  template <class X, class Y>
  void deviation(double d, const char* inv, X x, Y y, const char* from) {
    if (!std::isfinite(d)) d = HUGE_VAL;
    const bool largest = (d > r.max_deviation || r.max_elements.empty()) && d >= r.max_deviation;
    const bool violation = d > precision;
    if (!largest && !violation) return;
    std::vector<std::string> els{x.str(), y.str()};
    if (largest) {
      r.max_deviation = d;
      r.max_elements = els;
    }
    if (violation)
      r.violations.push_back(
          {inv, std::move(els), x.str() + from + y.str() + " is " + fmt(d) + " away (precision " + fmt(precision) + ")", d});
  }
};

bool has_surface(const Body& b, FaceH f) { return !std::holds_alternative<std::monostate>(b.surface(f)); }
bool has_curve(const Body& b, EdgeH e) { return !std::holds_alternative<std::monostate>(b.curve(e)); }

double polyline_chordal(const geo::Curve& c) {
  if (const auto* p = std::get_if<geo::Polyline>(&c)) return p->chordal_error;
  return 0.0;
}

}  // namespace

bool planar_face_sense_ok(const Body& b, FaceH f, double precision) {
  const auto* plane = std::get_if<geo::Plane>(&b.surface(f));
  if (!plane) return true;
  LoopH l = b.outer_loop(f);
  if (!l.valid() || b.is_lone(l)) return true;
  std::vector<geo::Vec3> pts;
  for (HalfedgeH h : b.loop_halfedges(l)) {
    auto seg = halfedge_polyline(b, h, geo::Tolerances::orientation_chordal(std::max(precision, 1e-300)));
    pts.insert(pts.end(), seg.begin(), seg.end() - 1);
  }
  geo::Vec3 n = geo::polygon_normal(pts);
  geo::Vec3 outward = plane->frame.z * (b.same_sense(f) ? 1.0 : -1.0);
  return n.dot(outward) > 0;
}

GeometryReport check_geometry(const Body& b, double precision) {
  Run run{b, precision, {}};
  for (FaceH f : b.faces())
    if (!has_surface(b, f)) run.r.violations.push_back({"face_without_surface", {f.str()}, "no surface attached", 0.0});
  for (EdgeH e : b.edges())
    if (!has_curve(b, e)) run.r.violations.push_back({"edge_without_curve", {e.str()}, "no curve attached", 0.0});

  // Vertices on their curves and surfaces.
  for (VertexH v : b.vertices()) {
    const geo::Vec3& p = b.point(v);
    auto outs = b.outgoing(v);
    if (outs.empty()) {
      for (LoopH l : b.loops())  // a lone vertex: on its face's surface
        if (b.is_lone(l) && b.lone_vertex(l) == v && !b.is_border(l) && has_surface(b, b.face(l)))
          run.deviation(std::abs(geo::signed_distance(b.surface(b.face(l)), p)), "vertex_on_surface", v, b.face(l),
                        " from the surface of ");
      continue;
    }
    for (HalfedgeH h : outs) {
      EdgeH e = edge_of(h);
      if (has_curve(b, e))
        run.deviation(geo::closest_point(b.curve(e), p).distance - polyline_chordal(b.curve(e)), "vertex_on_curve", v, e,
                      " from the curve of ");
      if (!b.is_border(h) && has_surface(b, b.face(h)))
        run.deviation(std::abs(geo::signed_distance(b.surface(b.face(h)), p)), "vertex_on_surface", v, b.face(h),
                      " from the surface of ");
    }
  }

  // Edges on both faces' surfaces, at points along them (the ends are the vertices, checked above).
  for (EdgeH e : b.edges()) {
    if (!has_curve(b, e)) continue;
    HalfedgeH h = halfedge_of(e, 0);
    // Probes are points of the curve itself between the edge's ends (never of a chord,
    // which would be a sagitta off a curved surface).
    std::vector<geo::Vec3> probes;
    const geo::Vec3 &p0 = b.point(b.origin(h)), &p1 = b.point(b.target(h));
    if (std::holds_alternative<geo::Line>(b.curve(e))) {
      for (double s : {0.25, 0.5, 0.75}) probes.push_back(p0 + s * (p1 - p0));
    } else {
      double coincide = b.origin(h) == b.target(h) ? std::max(precision, 1e-300) : 0.0;
      geo::ParameterRange r = geo::parameter_range(b.curve(e), p0, p1, coincide);
      for (double s : {0.125, 0.25, 0.5, 0.75, 0.875}) probes.push_back(geo::evaluate(b.curve(e), r.t0 + s * (r.t1 - r.t0)));
    }
    double slack = polyline_chordal(b.curve(e));
    for (HalfedgeH side : {h, twin(h)}) {
      if (b.is_border(side) || !has_surface(b, b.face(side))) continue;
      FaceH f = b.face(side);
      double worst = 0.0;
      for (const geo::Vec3& q : probes) worst = std::max(worst, std::abs(geo::signed_distance(b.surface(f), q)));
      run.deviation(worst - slack, "edge_on_surface", e, f, " from the surface of ");
    }
  }

  // Planar faces: the outer loop turns counter-clockwise about the outward normal.
  for (FaceH f : b.faces())
    if (!planar_face_sense_ok(b, f, precision))
      run.r.violations.push_back({"face_sense", {f.str()}, "outer loop turns clockwise about the outward normal", 0.0});
  return run.r;
}

}  // namespace kintsugi
