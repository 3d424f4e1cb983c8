#include "invariants/geometry_check.h"

#include "geometry/curve.h"
#include "geometry/polygon.h"
#include "geometry/surface.h"
#include "geometry/tolerance.h"
#include "invariants/element_geometry.h"

#include <cmath>
#include <sstream>
#include <thread>
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

namespace {

void check_vertex(Run& run, VertexH v) {
  const Body& b = run.b;
  const geo::Vec3& p = b.point(v);
  auto outs = b.outgoing(v);
  if (outs.empty()) {
    for (LoopH l : b.loops())  // a lone vertex: on its face's surface
      if (b.is_lone(l) && b.lone_vertex(l) == v && !b.is_border(l) && has_surface(b, b.face(l)))
        run.deviation(std::abs(geo::signed_distance(b.surface(b.face(l)), p)), "vertex_on_surface", v, b.face(l),
                      " from the surface of ");
    return;
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

// An edge on both faces' surfaces, at points along it (the ends are the vertices).
void check_edge(Run& run, EdgeH e) {
  const Body& b = run.b;
  if (!has_curve(b, e)) return;
  HalfedgeH h = halfedge_of(e, 0);
  // Probes are points of the curve itself between the edge's ends (never of a chord,
  // which would be a sagitta off a curved surface).
  std::vector<geo::Vec3> probes;
  const geo::Vec3 &p0 = b.point(b.origin(h)), &p1 = b.point(b.target(h));
  if (std::holds_alternative<geo::Line>(b.curve(e))) {
    for (double s : {0.25, 0.5, 0.75}) probes.push_back(p0 + s * (p1 - p0));
  } else {
    double coincide = b.origin(h) == b.target(h) ? std::max(run.precision, 1e-300) : 0.0;
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
void check_sense(Run& run, FaceH f) {
  if (!planar_face_sense_ok(run.b, f, run.precision))
    run.r.violations.push_back({"face_sense", {f.str()}, "outer loop turns clockwise about the outward normal", 0.0});
}

// Runs check(run, x) for every x of `items` on `threads` threads, each over a contiguous
// block with a Run of its own, then folds the blocks into `run` in order: the violations
// in element order, and the largest deviation where one thread would have found it (the
// first element at it: a block's largest replaces the running one only when strictly
// larger, or when there is none yet, as Run::deviation does element by element).
template <class H, class Check>
void over_blocks(Run& run, const std::vector<H>& items, int threads, const Check& check) {
  const std::size_t t = std::size_t(std::max(1, threads));
  if (t == 1) {
    for (const H& x : items) check(run, x);
    return;
  }
  std::vector<Run> runs(t, Run{run.b, run.precision, {}});
  auto block = [&](std::size_t k) {
    for (std::size_t i = items.size() * k / t; i < items.size() * (k + 1) / t; ++i) check(runs[k], items[i]);
  };
  std::vector<std::thread> pool;
  for (std::size_t k = 1; k < t; ++k) pool.emplace_back(block, k);
  block(0);
  for (std::thread& th : pool) th.join();
  for (Run& r : runs) {
    if (!r.r.max_elements.empty() && (r.r.max_deviation > run.r.max_deviation || run.r.max_elements.empty()) &&
        r.r.max_deviation >= run.r.max_deviation) {
      run.r.max_deviation = r.r.max_deviation;
      run.r.max_elements = r.r.max_elements;
    }
    for (Violation& v : r.r.violations) run.r.violations.push_back(std::move(v));
  }
}

}  // namespace

GeometryReport check_geometry(const Body& b, double precision, int threads) {
  Run run{b, precision, {}};
  for (FaceH f : b.faces())
    if (!has_surface(b, f)) run.r.violations.push_back({"face_without_surface", {f.str()}, "no surface attached", 0.0});
  for (EdgeH e : b.edges())
    if (!has_curve(b, e)) run.r.violations.push_back({"edge_without_curve", {e.str()}, "no curve attached", 0.0});
  // Free-form evaluation keeps state between calls (a projection starts from the last
  // answer), so a body with any free-form element is checked on one thread; below a few
  // thousand elements threads cost more than they save.
  constexpr std::size_t kMinElements = 4096;
  const std::vector<VertexH> vertices = b.vertices();
  const std::vector<EdgeH> edges = b.edges();
  const std::vector<FaceH> faces = b.faces();
  if (threads > 1 && edges.size() < kMinElements) threads = 1;
  for (EdgeH e : edges)
    if (threads > 1 && geo::is_freeform(b.curve(e))) threads = 1;
  for (FaceH f : faces)
    if (threads > 1 && geo::is_freeform(b.surface(f))) threads = 1;
  over_blocks(run, vertices, threads, check_vertex);
  over_blocks(run, edges, threads, check_edge);
  over_blocks(run, faces, threads, check_sense);
  return run.r;
}

}  // namespace kintsugi
