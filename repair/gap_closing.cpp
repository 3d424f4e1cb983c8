#include "repair/gap_closing.h"

#include "geometry/curve.h"
#include "geometry/meet_point.h"
#include "geometry/same_geometry.h"
#include "geometry/surface.h"
#include "invariants/element_geometry.h"
#include "kernel/euler.h"
#include "repair/beautify_detail.h"
#include "repair/detect_detail.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>
#include <sstream>

namespace kintsugi::detail {

namespace {

bool on_border(const Body& b, EdgeH e) { return b.is_border(halfedge_of(e, 0)) || b.is_border(halfedge_of(e, 1)); }

std::string refused(const char* op, const Error& e) { return std::string(op) + " refused: " + e.message; }

// Joins a run's edges into one at its inner vertices (each must lie on these two edges
// only); the survivor keeps half-edge h.
std::string join_run(Body& b, HalfedgeH h, std::size_t n) {
  for (std::size_t i = 1; i < n; ++i) {
    VertexH m = b.target(h);
    if (b.degree(m) != 2) return m.str() + " inside the gap's border lies on " + std::to_string(b.degree(m)) + " edges";
    auto r = euler::jekv(b, h);
    if (!r) return refused("jekv", r.error());
  }
  return "";
}

// Closes a gap of three border edges, [a, b1, b2] in cycle order, where b1 and b2 meet at
// a vertex w that carries an edge of the face beyond them: a is split at `at` (the point
// of a nearest w) into a1, a2; an edge from the split point to w (mef) makes a new face
// [a2, b1, w→m] in the gap and leaves the gap [a1, m→w, b2]; that edge is collapsed onto w
// (kev), leaving two gaps of two edges; the face across a grows over both (kef twice),
// a1 and a2 gone: b1 and b2 lie between the two faces, meeting at w.
std::string zip_at(Body& b, HalfedgeH a, HalfedgeH b2, const geo::Vec3& at) {
  auto s = euler::semv(b, a, at);
  if (!s) return refused("semv", s.error());
  const HalfedgeH a1 = a, a2 = s->next;
  auto m = euler::mef(b, Corner::before(a2), Corner::before(b2));
  if (!m) return refused("mef", m.error());
  if (auto r = euler::kev(b, m->b); !r) return refused("kev", r.error());
  if (auto r = euler::kef(b, twin(a1)); !r) return refused("kef", r.error());
  if (auto r = euler::kef(b, twin(a2)); !r) return refused("kef", r.error());
  return "";
}

// Whether moving junction j to p extends the edges at j rather than folding them back:
// every edge at j that is not on the gap keeps its direction from its far end.
bool extends(const Body& b, VertexH j, const geo::Vec3& p) {
  const geo::Vec3 at = b.point(j);
  for (HalfedgeH o : b.outgoing(j)) {
    if (on_border(b, edge_of(o))) continue;
    const geo::Vec3 w = b.point(b.target(o));
    if (!((p - w).dot(at - w) > 0)) return false;
  }
  return true;
}

bool meets(const geo::MeetPoint& m) {
  return m.status == geo::MeetStatus::exact || m.status == geo::MeetStatus::least_squares;
}

// An "underdetermined" meeting point that is still a point: two of the surfaces touch
// (a side plane tangent to a fillet's cylinder along a ruling), so their normals agree
// there and the solve sees a curve of solutions, but the surfaces meet in one point —
// where the ruling crosses the third face. A gap at the corner where a fillet ends was
// closed with a new face instead of that vertex, and refused (scan parts, filleted_block).
// The point is taken when it lies on every surface to the precision and a step of a tenth
// of the tolerance along the direction the normals leave free, either way, leaves some
// surface by more than ten times the precision (on a true curve of solutions, such as two
// faces on one plane, the step stays on all of them).
bool isolated_meeting_point(const std::vector<geo::Surface>& ss, const geo::MeetPoint& m, const geo::Tolerances& tol) {
  if (m.status != geo::MeetStatus::underdetermined || !(m.residual <= tol.precision) || ss.size() < 3) return false;
  Eigen::MatrixXd normals(Eigen::Index(ss.size()), 3);
  for (std::size_t i = 0; i < ss.size(); ++i) normals.row(Eigen::Index(i)) = geo::closest_point(ss[i], m.point).normal.transpose();
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(normals, Eigen::ComputeFullV);
  const Eigen::Vector3d sv = svd.singularValues().head<3>();
  if (!(sv(1) > 1e-3 * sv(0))) return false;  // normals all along one direction: a surface of solutions
  const geo::Vec3 free = svd.matrixV().col(2);
  for (double side : {1.0, -1.0}) {
    const geo::Vec3 q = m.point + side * 0.1 * tol.length * free;
    double off = 0;
    for (const geo::Surface& s : ss) off = std::max(off, std::abs(geo::signed_distance(s, q)));
    if (!(off > 10 * tol.precision)) return false;
  }
  return true;
}

// Where the faces meet when they are all tangent there (their normals one direction: a
// box rounded on every edge, whose flat face's corner is where two fillet cylinders and
// the corner's sphere touch it): the surfaces alone pin the point only loosely within the
// tangent plane (meet_point is underdetermined, or finds a point within the precision of
// every surface but off where they touch), but the curves of the edges that run into the
// gap — where the faces meet pairwise, each a line or circle of contact — cross there. Alternating projections onto those curves from `start`; the point is taken when
// it is within the precision of every curve and of every surface, within
// max_vertex_move() of every junction, and two of the curves cross at an angle there (so
// it is one point, not a curve of them). Coplanar faces (a face split in four, its centre
// vertex cut out by a gap) meet the same way: the gap closes in the vertex where the four
// splitting edges cross, not with a new small face. (Scan parts, rounded_box: such a gap
// was closed in a vertex 2e-10 from the four surfaces but 3.8e-5 off their contact
// curves, and the validity gate refused it.)
std::optional<geo::Vec3> where_edges_meet(const Body& b, const std::vector<VertexH>& junctions,
                                          const std::vector<geo::Surface>& surfaces, geo::Vec3 start,
                                          const geo::Tolerances& tol) {
  std::vector<const geo::Curve*> curves;
  for (VertexH v : junctions)
    for (HalfedgeH o : b.outgoing(v))
      if (!on_border(b, edge_of(o))) curves.push_back(&b.curve(edge_of(o)));
  if (curves.size() < 2) return std::nullopt;
  geo::Vec3 p = start;
  for (int it = 0; it < 200; ++it) {
    geo::Vec3 q = geo::Vec3::Zero();
    for (const geo::Curve* c : curves) q += geo::closest_point(*c, p).point;
    q /= double(curves.size());
    const double step = (q - p).norm();
    p = q;
    if (!(step > 1e-3 * tol.precision)) break;
  }
  if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z())) return std::nullopt;
  // Curves crossing at a glancing angle cross far away: each junction becomes this point,
  // and a vertex moves at most max_vertex_move().
  for (VertexH v : junctions)
    if (!((b.point(v) - p).norm() <= tol.max_vertex_move())) return std::nullopt;
  for (const geo::Curve* c : curves)
    if (!(geo::closest_point(*c, p).distance <= tol.precision)) return std::nullopt;
  for (const geo::Surface& s : surfaces)
    if (!(std::abs(geo::signed_distance(s, p)) <= tol.precision)) return std::nullopt;
  double crossing = 0;
  for (std::size_t i = 0; i < curves.size(); ++i)
    for (std::size_t k = 0; k < i; ++k) {
      const geo::Vec3 ti = geo::tangent(*curves[i], geo::closest_point(*curves[i], p).t);
      const geo::Vec3 tk = geo::tangent(*curves[k], geo::closest_point(*curves[k], p).t);
      crossing = std::max(crossing, ti.cross(tk).norm());
    }
  if (!(crossing > 1e-3)) return std::nullopt;  // all along one direction: no single point
  return p;
}

// The surfaces' normals at p nearly all along one direction (their second singular value
// below a hundredth of the first): a meeting point there is ill-conditioned in the
// tangent plane, however small its residual.
bool nearly_tangent(const std::vector<geo::Surface>& ss, const geo::Vec3& p) {
  if (ss.size() < 2) return false;
  Eigen::MatrixXd normals(Eigen::Index(ss.size()), 3);
  for (std::size_t i = 0; i < ss.size(); ++i) normals.row(Eigen::Index(i)) = geo::closest_point(ss[i], p).normal.transpose();
  const Eigen::VectorXd sv = Eigen::JacobiSVD<Eigen::MatrixXd>(normals).singularValues();
  return sv.size() >= 2 && sv(1) < 1e-2 * sv(0);
}

geo::Vec3 newell(const std::vector<geo::Vec3>& pts) {
  geo::Vec3 n = geo::Vec3::Zero();
  for (std::size_t i = 0; i < pts.size(); ++i) n += pts[i].cross(pts[(i + 1) % pts.size()]);
  return n;
}

double max_distance(const geo::Surface& s, const std::vector<geo::Vec3>& pts) {
  double d = 0;
  for (const auto& p : pts) d = std::max(d, std::abs(geo::signed_distance(s, p)));
  return d;
}

// Algebraic sphere through the points (least squares on x²+y²+z² + D·x + E·y + F·z + G = 0).
std::optional<geo::Sphere> sphere_guess(const std::vector<geo::Vec3>& pts) {
  if (pts.size() < 4) return std::nullopt;
  Eigen::MatrixXd a(long(pts.size()), 4);
  Eigen::VectorXd r(long(pts.size()));
  for (std::size_t i = 0; i < pts.size(); ++i) {
    a.row(long(i)) << pts[i].x(), pts[i].y(), pts[i].z(), 1.0;
    r(long(i)) = -pts[i].squaredNorm();
  }
  Eigen::Vector4d x = a.colPivHouseholderQr().solve(r);
  geo::Vec3 c = -0.5 * x.head<3>();
  double r2 = c.squaredNorm() - x(3);
  if (!(r2 > 0) || !std::isfinite(r2)) return std::nullopt;
  geo::Sphere s;
  s.frame.origin = c;
  s.radius = std::sqrt(r2);
  return s;
}

}  // namespace

VertexH Gap::junction(const Body& b, std::size_t i) const { return b.target(runs[i % runs.size()].edges.back()); }

std::optional<Gap> find_gap(const Body& b, const Problem& p, std::string* why) {
  LoopH l = p.first<LoopH>();
  if (!b.alive(l) || !b.is_border(l)) {
    *why = "no longer present: " + l.str() + " is no longer a border cycle";
    return std::nullopt;
  }
  std::set<FaceH> want;
  for (FaceH f : p.all<FaceH>()) want.insert(f);
  const std::vector<HalfedgeH> all = b.loop_halfedges(l);
  for (const auto& cycle : simple_cycles(b, all)) {
    std::set<FaceH> faces;
    for (HalfedgeH h : cycle) faces.insert(b.face(twin(h)));
    if (faces != want) continue;
    Gap g;
    g.border = l;
    g.cycle = cycle;
    g.whole_loop = cycle.size() == all.size();
    // Rotate so that the cycle starts where the face across changes.
    std::size_t n = cycle.size(), start = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (b.face(twin(cycle[i])) != b.face(twin(cycle[(i + n - 1) % n]))) {
        start = i;
        break;
      }
    for (std::size_t k = 0; k < n; ++k) {
      HalfedgeH h = cycle[(start + k) % n];
      FaceH f = b.face(twin(h));
      if (g.runs.empty() || g.runs.back().face != f) g.runs.push_back({f, {}});
      g.runs.back().edges.push_back(h);
    }
    return g;
  }
  *why = l.str() + " no longer bounds a gap across the faces named";
  return std::nullopt;
}

std::string remove_hole(RepairCall& c, const Gap& g) {
  Body& b = c.b;
  if (g.runs.size() != 1) return "the gap is not inside one face";
  if (!g.whole_loop) return "the gap shares a vertex with another gap";
  const FaceH f = g.runs[0].face;
  const LoopH ring = b.loop(twin(g.cycle[0]));
  if (b.is_outer(ring)) return "the gap is not a hole inside " + f.str() + " (it is on its outer loop)";
  for (HalfedgeH h : g.cycle) {
    if (b.loop(twin(h)) != ring) return "the gap's border is not one ring of " + f.str();
    if (b.degree(b.origin(h)) != 2) return b.origin(h).str() + " on the gap lies on further edges";
  }
  while (b.loop_halfedges(g.border).size() > 1) {
    auto r = euler::kev(b, b.first(g.border));
    if (!r) return refused("kev", r.error());
  }
  auto k = euler::kef(b, twin(b.first(g.border)));
  if (!k) return refused("kef", k.error());
  // What is left of the ring is a lone vertex: join it to the outer loop and collapse.
  LoopH lone;
  for (LoopH r : b.rings_of(f))
    if (b.is_lone(r)) lone = r;
  if (!lone.valid()) return "no lone vertex left in " + f.str();
  LoopH outer = b.outer_loop(f);
  if (b.is_lone(outer)) return f.str() + " has no edges on its outer loop";
  auto m = euler::mekr(b, Corner::before(b.first(outer)), Corner::in_lone(lone));
  if (!m) return refused("mekr", m.error());
  auto kv = euler::kev(b, m->a);
  if (!kv) return refused("kev", kv.error());
  c.touched.faces.insert(f);
  return "";
}

std::string collapse_gap(RepairCall& c, const Gap& g, const std::vector<std::size_t>& keep,
                         const std::vector<geo::Vec3>& points) {
  Body& b = c.b;
  if (!g.whole_loop) return "the gap shares a vertex with another gap";
  if (keep.size() != 0 && keep.size() != 2) return "a gap closes into one vertex or one edge";
  if (points.size() != (keep.empty() ? 1u : 2u)) return "no meeting point for every collapsed group";
  const std::size_t k = g.runs.size();
  std::set<FaceH> faces;
  for (const GapRun& r : g.runs) faces.insert(r.face);
  // Kept runs become one edge each. One of two kept runs may pass a vertex that carries
  // another edge: a seam of its face ending on the gap (a cylinder fitted twice, merged by
  // pass 8 with the ruling through the gap kept as its seam; scan parts, shaft). That run
  // becomes two edges, joined on either side of the vertex, and the other run is split to
  // match it (zip_at below).
  std::vector<HalfedgeH> kept;
  VertexH inner;                 // that vertex
  std::size_t inner_run = 0;     // which of `kept` passes it
  HalfedgeH after_inner;         // the run's edge from it on
  for (std::size_t i : keep) {
    const std::vector<HalfedgeH>& es = g.runs[i].edges;
    std::size_t split = 0;  // edges of the run before the vertex; 0: no such vertex
    if (keep.size() == 2 && !inner.valid())
      for (std::size_t j = 0; j + 1 < es.size() && split == 0; ++j)
        if (b.degree(b.target(es[j])) != 2) split = j + 1;
    if (split == 0) {
      if (std::string why = join_run(b, es.front(), es.size()); !why.empty()) return why;
    } else {
      inner = b.target(es[split - 1]), inner_run = kept.size(), after_inner = es[split];
      if (std::string why = join_run(b, es.front(), split); !why.empty()) return why;
      if (std::string why = join_run(b, es[split], es.size() - split); !why.empty()) return why;
    }
    kept.push_back(es.front());
  }
  // Every other run collapses: kev of its edges (the last edge of the gap stays when no
  // run is kept, and is removed by kef below).
  std::vector<HalfedgeH> doomed;
  for (std::size_t i = 0; i < k; ++i)
    if (std::find(keep.begin(), keep.end(), i) == keep.end())
      for (HalfedgeH h : g.runs[i].edges) doomed.push_back(h);
  if (keep.empty()) doomed.pop_back();
  for (HalfedgeH h : doomed) {
    auto r = euler::kev(b, h);
    if (!r) return refused("kev", r.error());
  }
  std::vector<std::pair<VertexH, geo::Vec3>> place;
  if (keep.empty()) {
    HalfedgeH last = b.first(g.border);
    if (b.loop_halfedges(g.border).size() != 1) return "the gap did not collapse to one edge";
    VertexH v = b.origin(last);
    auto r = euler::kef(b, twin(last));
    if (!r) return refused("kef", r.error());
    place.push_back({v, points[0]});
  } else if (inner.valid()) {
    if (b.loop_halfedges(g.border).size() != 3) return "the gap did not collapse to three edges";
    // Group after the first kept run ends at its end; the other group at its origin.
    place.push_back({inner_run == 0 ? b.target(after_inner) : b.target(kept[0]), points[0]});
    place.push_back({b.origin(kept[0]), points[1]});
    const HalfedgeH across = kept[1 - inner_run];
    const geo::CurvePoint m = geo::closest_point(b.curve(edge_of(across)), b.point(inner));
    place.push_back({inner, 0.5 * (m.point + b.point(inner))});
    if (std::string why = zip_at(b, across, after_inner, m.point); !why.empty()) return why;
    c.touched.edges.insert(edge_of(kept[inner_run]));
    c.touched.edges.insert(edge_of(after_inner));
  } else {
    if (b.loop_halfedges(g.border).size() != 2) return "the gap did not collapse to two edges";
    // Group after the first kept run ends at its target; the other group at its origin.
    place.push_back({b.target(kept[0]), points[0]});
    place.push_back({b.origin(kept[0]), points[1]});
    auto r = euler::kef(b, twin(kept[0]));
    if (!r) return refused("kef", r.error());
    c.touched.edges.insert(edge_of(kept[1]));
  }
  for (FaceH f : faces) c.touched.faces.insert(f);
  return place_vertices(b, place, c.tol, c.tol.length, c.touched);
}

std::string fill_gap(RepairCall& c, const Gap& g, std::string* surface_kind) {
  Body& b = c.b;
  if (!g.whole_loop) return "the gap shares a vertex with another gap";
  // The points the new surface must pass: the gap's border, sampled.
  std::vector<geo::Vec3> pts, corners;
  for (HalfedgeH h : g.cycle) {
    auto poly = halfedge_polyline(b, h, 0.1 * c.tol.length);
    pts.insert(pts.end(), poly.begin(), poly.end() - 1);
  }
  for (std::size_t i = 0; i < g.runs.size(); ++i) corners.push_back(b.point(g.junction(b, i)));
  const geo::Vec3 normal = newell(pts);  // the border runs counter-clockwise about the new face's outward normal
  if (!(normal.norm() > 0)) return "the gap's border encloses no area";
  geo::Vec3 centre = geo::Vec3::Zero();
  for (const auto& p : pts) centre += p;
  centre /= double(pts.size());
  // Candidates: a plane, a sphere, and the kinds of the curved neighbours.
  std::vector<geo::Surface> models;
  geo::Plane plane;
  plane.frame.origin = centre;
  plane.frame.z = normal.normalized();
  plane.frame.x = plane.frame.z.unitOrthogonal();
  models.push_back(plane);
  if (auto s = sphere_guess(pts)) models.push_back(*s);
  for (const GapRun& r : g.runs)
    if (!std::holds_alternative<geo::Plane>(b.surface(r.face))) models.push_back(b.surface(r.face));
  geo::Surface best;
  double best_dev = HUGE_VAL;
  std::string tried;
  for (std::size_t i = 0; i < models.size(); ++i) {
    geo::SurfaceFit fit = geo::fit_surface_like(models[i], pts);
    if (!fit.converged) continue;
    double dev = max_distance(fit.surface, pts);
    tried += std::string(tried.empty() ? "" : ", ") + geo::surface_type_name(fit.surface) + " " + fmt(dev);
    // A plane wins whenever it is within tolerance (coplanar points).
    if (i == 0 && dev <= c.tol.length) {
      best = fit.surface, best_dev = dev;
      break;
    }
    if (dev < best_dev) best = fit.surface, best_dev = dev;
  }
  if (!(best_dev <= c.tol.length)) return "no surface fits the gap's border within tolerance (" + tried + ")";
  const bool sense = geo::normal(best, geo::parameters(best, centre)).dot(normal) > 0;
  auto m = euler::mfkb(b, g.border);
  if (!m) return refused("mfkb", m.error());
  const FaceH n = m->face;
  b.set_surface(n, best, sense);
  for (const GapRun& r : g.runs) {
    if (std::string why = join_run(b, r.edges.front(), r.edges.size()); !why.empty()) return why;
    EdgeH e = edge_of(r.edges.front());
    std::string why;
    auto curve = derive_edge_curve(b, e, c.tol, &why);
    if (!curve) return why;
    b.set_curve(e, *curve);
    c.touched.edges.insert(e);
    c.touched.faces.insert(r.face);
  }
  c.touched.faces.insert(n);
  *surface_kind = geo::surface_type_name(best);
  return "";
}

GapClosure plan_multi_face_gap(const Body& b, const Gap& g, const geo::Tolerances& tol, bool exhaustive) {
  GapClosure out;
  const std::size_t k = g.runs.size();
  std::vector<geo::Vec3> j(k);
  std::vector<VertexH> jv(k);
  for (std::size_t i = 0; i < k; ++i) jv[i] = g.junction(b, i), j[i] = b.point(jv[i]);
  auto surfaces_of = [&](const std::vector<std::size_t>& runs) {
    std::vector<geo::Surface> s;
    std::set<FaceH> seen;
    for (std::size_t i : runs)
      if (seen.insert(g.runs[i].face).second) s.push_back(b.surface(g.runs[i].face));
    return s;
  };
  auto mean = [&](std::size_t from, std::size_t count) {  // junctions from, from+1, ... (mod k)
    geo::Vec3 m = geo::Vec3::Zero();
    for (std::size_t t = 0; t < count; ++t) m += j[(from + t) % k];
    return geo::Vec3(m / double(count));
  };
  // One vertex: all the faces meet in one point, reached by extending every edge.
  {
    std::vector<std::size_t> all(k);
    for (std::size_t i = 0; i < k; ++i) all[i] = i;
    const std::vector<geo::Surface> ss = surfaces_of(all);
    geo::MeetPoint m = geo::meet_point(ss, mean(0, k), tol.length, tol.precision);
    bool ok = meets(m) || isolated_meeting_point(ss, m, tol);
    // Surfaces (nearly) tangent there meet within the precision over a stretch of the
    // tangent plane: the point is where the edges' curves cross.
    if ((ok || m.status == geo::MeetStatus::underdetermined) && nearly_tangent(ss, m.point))
      if (auto p = where_edges_meet(b, jv, ss, m.point, tol)) {
        m.point = *p, m.residual = 0.0;
        for (const geo::Surface& s : ss) m.residual = std::max(m.residual, std::abs(geo::signed_distance(s, *p)));
        ok = true;
      }
    for (std::size_t i = 0; ok && i < k; ++i) ok = extends(b, jv[i], m.point);
    if (ok) {
      out.kind = GapClosure::one_vertex;
      out.points = {m.point};
      out.residual = m.residual;
      return out;
    }
    out.note = meets(m) ? "the faces meet in one point, but behind the gap's edges"
                        : std::string("the faces do not meet in one point (") + geo::meet_status_name(m.status) + ")";
  }
  // Two vertices: runs a and c (not next to each other) share the new edge; the runs
  // between them on either side collapse into its two ends.
  double best = HUGE_VAL;
  // For a fixed a, group A (runs a..c) grows with c and group B (runs c..a+k-1, mod k)
  // shrinks. A group whose surfaces have no common point within the tolerance (no_point,
  // degenerate) has none with more surfaces either, so A is solved for increasing c and B
  // for decreasing c, each up to its first such failure: on a wide gap whose faces meet
  // nowhere (a free-form shell's open border, 35 runs) that is O(k) solves, not O(k²).
  auto no_common_point = [](const geo::MeetPoint& m) {
    return m.status == geo::MeetStatus::no_point || m.status == geo::MeetStatus::degenerate;
  };
  std::vector<std::optional<geo::MeetPoint>> pa_at(k), pb_at(k);
  for (std::size_t a = 0; a < k; ++a) {
    const std::size_t last = std::min(k - 1, a + k - 2);  // c in [a + 2, last]
    if (a + 2 > last) continue;
    std::fill(pa_at.begin(), pa_at.end(), std::nullopt);
    std::fill(pb_at.begin(), pb_at.end(), std::nullopt);
    // Group A lies between junction a (end of run a) and junction c-1; B between c and a-1.
    for (std::size_t c = a + 2; c <= last; ++c) {
      std::vector<std::size_t> ga{a, c};
      for (std::size_t i = a + 1; i < c; ++i) ga.push_back(i);
      pa_at[c] = geo::meet_point(surfaces_of(ga), mean(a, c - a), tol.length, tol.precision);
      if (!exhaustive && no_common_point(*pa_at[c])) break;
    }
    for (std::size_t c = last; c >= a + 2; --c) {
      if (!pa_at[c] || !meets(*pa_at[c])) continue;  // no use solving B where A fails
      std::vector<std::size_t> gb{a, c};
      for (std::size_t i = c + 1; i < a + k; ++i) gb.push_back(i % k);
      pb_at[c] = geo::meet_point(surfaces_of(gb), mean(c, a + k - c), tol.length, tol.precision);
      if (!exhaustive && no_common_point(*pb_at[c])) break;
    }
    for (std::size_t c = a + 2; c <= last; ++c) {
      if (!pa_at[c] || !pb_at[c]) continue;
      const geo::MeetPoint& pa = *pa_at[c];
      const geo::MeetPoint& pb = *pb_at[c];
      if (!meets(pa) || !meets(pb) || (pa.point - pb.point).norm() <= tol.precision) continue;
      bool ok = true;
      for (std::size_t i = a; ok && i < c; ++i) ok = extends(b, jv[i], pa.point);
      for (std::size_t i = c; ok && i < a + k; ++i) ok = extends(b, jv[i % k], pb.point);
      // The new edge runs the way the kept runs ran: a from B to A, c from A to B.
      ok = ok && (pa.point - pb.point).dot(j[a] - j[(a + k - 1) % k]) > 0;
      ok = ok && (pb.point - pa.point).dot(j[c] - j[c - 1]) > 0;
      // The faces that only touch the new edge's ends stay on the side of its middle where
      // the rest of the gap's border is (the new edge is where the faces actually meet, not
      // a crossing hidden behind them: for a convex corner, inside all their planes).
      const geo::Vec3 mid = 0.5 * (pa.point + pb.point);
      double crossing = 0;
      for (std::size_t i = 0; i < k; ++i) {
        if (i == a || i == c) continue;
        const geo::Surface& s = b.surface(g.runs[i].face);
        double ref = 0;
        for (std::size_t q = 0; q < k; ++q)
          if (q != i && q != (i + k - 1) % k) ref += geo::signed_distance(s, j[q]);
        const double d = geo::signed_distance(s, mid);
        crossing = std::max(crossing, ref < 0 ? d : -d);
      }
      // Fewest crossings first, then the smallest residual.
      double res = std::max(pa.residual, pb.residual) + (crossing > tol.precision ? 1e6 * (1 + crossing) : 0.0);
      if (ok && res < best) {
        best = res;
        out.kind = GapClosure::two_vertices;
        out.keep = {a, c};
        out.points = {pa.point, pb.point};
        out.residual = std::max(pa.residual, pb.residual);
      }
    }
  }
  if (out.kind == GapClosure::two_vertices) return out;
  if (k >= 4) out.note += "; no two opposite faces carry an edge whose ends the others meet";
  out.kind = GapClosure::new_face;
  return out;
}

}  // namespace kintsugi::detail
