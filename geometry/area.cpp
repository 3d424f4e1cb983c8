#include "geometry/area.h"

#include "geometry/frame.h"
#include "geometry/parameter_domain.h"
#include "geometry/revolution_measure.h"
#include "geometry/surface.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>

#include <cmath>
#include <exception>
#include <limits>
#include <list>
#include <optional>
#include <unordered_set>

namespace kintsugi::geo {

namespace {

// CGAL's polygon-with-holes setup: faces carry their nesting depth; odd depth = inside.
struct FaceInfo {
  int nesting = -1;
  bool in_domain() const { return nesting % 2 == 1; }
};
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_2<K>;
using Fbb = CGAL::Triangulation_face_base_with_info_2<FaceInfo, K>;
using Fb = CGAL::Constrained_triangulation_face_base_2<K, Fbb>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using CDT = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_predicates_tag>;

void mark(CDT& cdt, CDT::Face_handle start, int depth, std::list<CDT::Edge>& border) {
  if (start->info().nesting != -1) return;
  std::list<CDT::Face_handle> queue{start};
  while (!queue.empty()) {
    CDT::Face_handle f = queue.front();
    queue.pop_front();
    if (f->info().nesting != -1) continue;
    f->info().nesting = depth;
    for (int i = 0; i < 3; ++i) {
      CDT::Face_handle n = f->neighbor(i);
      if (n->info().nesting != -1) continue;
      if (cdt.is_constrained(CDT::Edge(f, i))) border.push_back(CDT::Edge(f, i));
      else queue.push_back(n);
    }
  }
}

void mark_domains(CDT& cdt) {
  for (CDT::Face_handle f : cdt.all_face_handles()) f->info().nesting = -1;
  std::list<CDT::Edge> border;
  mark(cdt, cdt.infinite_face(), 0, border);
  while (!border.empty()) {
    const CDT::Edge e = border.front();
    border.pop_front();
    CDT::Face_handle n = e.first->neighbor(e.second);
    if (n->info().nesting == -1) mark(cdt, n, e.first->info().nesting + 1, border);
  }
}

// Radon's 7-point degree-5 rule on a triangle, barycentric points and weights (sum 1).
struct Rule {
  std::array<std::array<double, 3>, 7> bary;
  std::array<double, 7> weight;
};
const Rule& radon7() {
  static const Rule rule = [] {
    const double s15 = std::sqrt(15.0);
    const double a1 = (6 - s15) / 21, b1 = (9 + 2 * s15) / 21, w1 = (155 - s15) / 1200;
    const double a2 = (6 + s15) / 21, b2 = (9 - 2 * s15) / 21, w2 = (155 + s15) / 1200;
    Rule r;
    r.bary = {{{1.0 / 3, 1.0 / 3, 1.0 / 3}, {a1, a1, b1}, {a1, b1, a1}, {b1, a1, a1},
               {a2, a2, b2}, {a2, b2, a2}, {b2, a2, a2}}};
    r.weight = {9.0 / 40, w1, w1, w1, w2, w2, w2};
    return r;
  }();
  return rule;
}

// Largest change of an angular parameter across the triangle.
double angular_extent(const Surface& s, const Vec2& a, const Vec2& b, const Vec2& c) {
  double e = 0.0;
  if (periodic_u(s)) e = std::max(e, std::max({a.x(), b.x(), c.x()}) - std::min({a.x(), b.x(), c.x()}));
  if (std::holds_alternative<Sphere>(s) || std::holds_alternative<Torus>(s))
    e = std::max(e, std::max({a.y(), b.y(), c.y()}) - std::min({a.y(), b.y(), c.y()}));
  return e;
}


// Parity of the point's nesting among the domain polygons: odd = inside the region.
bool in_region(const ParameterDomain& d, const Vec2& p) {
  bool in = false;
  for (const auto& poly : d.polygons)
    for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
      const Vec2 &a = poly[i], &b = poly[j];
      if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
        in = !in;
    }
  return in;
}

// Steiner points on a regular grid inside the region, so that the triangles are small
// in the angular directions (a few long triangles fanning out to a pole line would
// otherwise each need thousands of pieces). Spacing: `step` for angles; for lengths on
// cylinders and cones step × radius or a quarter of the length, whichever is larger
// (below); none for planes, whose area element is constant. At most ~40000 points: coarser beyond that.
void add_grid(CDT& cdt, const Surface& s, const ParameterDomain& d, double step, int freeform_grid) {
  if (std::holds_alternative<Plane>(s)) return;
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto& poly : d.polygons)
    for (const Vec2& p : poly) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const bool angular_v = std::holds_alternative<Sphere>(s) || std::holds_alternative<Torus>(s);
  double hu = step, hv = angular_v ? step : step * surface_scale(s);
  // On cylinders and cones the area element does not depend on u and is at most linear
  // in v, so the 7-point rule is exact on any triangle however long along v: rows are
  // only there to stop triangles fanning out, and a few do. (Spacing v like u made a long
  // thin fillet — a sliver — cost 40000 points, about a second per face.)
  if (!angular_v) hv = std::max(hv, (hi.y() - lo.y()) / 4);
  // Free-form: no radius to scale by; a grid over the region's parameter box (16 x 16
  // unless asked otherwise) keeps the triangles small where the area element varies.
  if (is_freeform(s)) {
    hu = (hi.x() - lo.x()) / std::max(1, freeform_grid);
    hv = (hi.y() - lo.y()) / std::max(1, freeform_grid);
    if (!(hu > 0) || !(hv > 0)) return;
  }
  if (!(hv > 0)) return;
  const double cells = (hi.x() - lo.x()) / hu * (hi.y() - lo.y()) / hv;
  if (cells > 40000) {
    const double grow = std::sqrt(cells / 40000);
    hu *= grow;
    hv *= grow;
  }
  std::vector<K::Point_2> pts;
  for (double u = lo.x() + 0.5 * hu; u < hi.x(); u += hu)
    for (double v = lo.y() + 0.5 * hv; v < hi.y(); v += hv)
      if (in_region(d, Vec2(u, v))) pts.emplace_back(u, v);
  cdt.insert(pts.begin(), pts.end());
}

// The bounds' share of the region's inside: the extreme points of the height along x, y
// and z that lie in the region (revolution_measure.h; the boundary's points are added by
// the caller). A point is tried at every 2π shift of its periodic coordinates that falls
// in the domain's box; a circle v = const is in the region where a domain triangle
// reaches its line, and one point of it there stands for all (the height is constant
// along it).
void add_extreme_points(const CDT& cdt, const Surface& s, const ParameterDomain& d, Box& bounds) {
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto& poly : d.polygons)
    for (const Vec2& p : poly) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  if (!(lo.x() <= hi.x())) return;
  const bool periodic_v = std::holds_alternative<Torus>(s);
  auto shifts = [](double x, double from, double to) {
    std::vector<double> out;
    for (double k = std::ceil((from - x) / kTwoPi); x + k * kTwoPi <= to; k += 1) out.push_back(x + k * kTwoPi);
    return out;
  };
  const ExtremeCandidates c = extreme_candidates(s);
  for (const Vec2& p : c.points)
    for (double u : shifts(p.x(), lo.x(), hi.x()))
      for (double v : periodic_v ? shifts(p.y(), lo.y(), hi.y()) : std::vector<double>{p.y()})
        if (in_region(d, Vec2(u, v))) bounds.add(evaluate(s, Vec2(u, v)));
  for (double circle : c.circles)
    for (double v : periodic_v ? shifts(circle, lo.y(), hi.y()) : std::vector<double>{circle}) {
      bool found = false;
      for (CDT::Face_handle f : cdt.finite_face_handles()) {
        if (!f->info().in_domain()) continue;
        // The triangle's slice at v: where its sides cross the line (or touch it).
        double umin = std::numeric_limits<double>::infinity(), umax = -umin;
        for (int i = 0; i < 3; ++i) {
          const K::Point_2 &a = f->vertex(i)->point(), &b = f->vertex((i + 1) % 3)->point();
          if ((a.y() - v) * (b.y() - v) > 0) continue;
          const double t = a.y() == b.y() ? 0.0 : (v - a.y()) / (b.y() - a.y());
          const double u = a.x() + t * (b.x() - a.x());
          umin = std::min(umin, u), umax = std::max(umax, u);
        }
        if (umin > umax) continue;
        bounds.add(evaluate(s, Vec2(0.5 * (umin + umax), v)));
        found = true;
        break;
      }
      if (found) break;
    }
}

}  // namespace

RegionMeasure measure_region(const Surface& s, const std::vector<std::vector<Vec3>>& loops, const AreaOptions& o) {
  RegionMeasure out;
  const ParameterDomain domain = parameter_domain(s, loops, o.reversed);
  if (!domain.problem.empty()) {
    out.problem = domain.problem;
    return out;
  }
  CDT cdt;
  try {
    // All boundary points first, then the sides between them as constraints: CGAL
    // inserts the points in spatial-sort order. Inserting each polygon as one constraint
    // polyline puts its points in one at a time along the boundary, and every insertion
    // next to a long thin run of earlier ones flips a cascade of edges: a B-spline face
    // with a densely sampled boundary spent most of detection there, and 2^20 points on one
    // flat ellipse took minutes.
    std::vector<K::Point_2> pts;
    std::vector<std::pair<std::size_t, std::size_t>> sides;
    for (const auto& poly : domain.polygons) {
      const std::size_t first = pts.size();
      for (const Vec2& p : poly) {
        const K::Point_2 q(p.x(), p.y());
        if (pts.size() == first || pts.back() != q) pts.push_back(q);
      }
      while (pts.size() > first + 1 && pts[first] == pts.back()) pts.pop_back();
      if (pts.size() < first + 3) {
        pts.resize(first);
        continue;
      }
      for (std::size_t i = first; i < pts.size(); ++i) sides.emplace_back(i, i + 1 < pts.size() ? i + 1 : first);
    }
    cdt.insert_constraints(pts.begin(), pts.end(), sides.begin(), sides.end());
  } catch (const std::exception& e) {
    out.problem = std::string("could not triangulate the region in parameter space: ") + e.what();
    return out;
  }
  if (cdt.dimension() < 2) {
    // Every boundary point on one line of the parameter plane: the region has no
    // interior (and CGAL's faces of a 1-dimensional triangulation have no neighbours to
    // walk), so it measures zero.
    std::size_t n = 0;
    for (const auto& loop : loops)
      for (const Vec3& p : loop) out.bounds.add(p), out.centroid += p, ++n;
    if (n > 0) out.centroid /= double(n);
    return out;
  }
  const bool fast = o.area_and_bounds_only;
  // Ruled surfaces in the fast mode: whole domain triangles (no grid), bounds from the boundary.
  const Cone* cone = std::get_if<Cone>(&s);
  const bool ruled = fast && (std::holds_alternative<Plane>(s) || std::holds_alternative<Cylinder>(s) || cone);
  // Spheres and ring tori in the fast mode: each domain triangle's area in closed form and
  // the bounds from the surface's extreme points (revolution_measure.h), so no grid either.
  const bool closed_form = fast && has_exact_triangle_area(s);
  if (!ruled && !closed_form) add_grid(cdt, s, domain, o.max_angle_step > 0 ? o.max_angle_step : 0.05, o.freeform_grid);
  mark_domains(cdt);

  const Rule& rule = radon7();
  // Sign of the parameter orientation relative to the normal (cone far nappe: -1).
  auto orientation = [&](const Vec2& uv) {
    double sense = o.reversed ? -1.0 : 1.0;
    if (const auto* c = std::get_if<Cone>(&s))
      if (c->radius + uv.y() * std::sin(c->half_angle) < 0) sense = -sense;
    return sense;
  };
  double area = 0.0;
  Vec3 moment = Vec3::Zero();
  const double step = o.max_angle_step > 0 ? o.max_angle_step : 0.05;
  struct PairHash {
    std::size_t operator()(const std::pair<double, double>& p) const {
      return std::hash<double>()(p.first) * 0x9E3779B97F4A7C15ull ^ std::hash<double>()(p.second);
    }
  };
  std::unordered_set<std::pair<double, double>, PairHash> bounded;  // parameters already in out.bounds
  // Regular n×n split of the triangle: grid point (i, j) = t0 + i/n (t1 - t0) + j/n (t2 - t0).
  auto split_regular = [&](const std::array<Vec2, 3>& t, int n) {
    const int base = static_cast<int>(out.mesh.vertices.size());
    auto grid = [&](int i, int j) { return t[0] + (double(i) / n) * (t[1] - t[0]) + (double(j) / n) * (t[2] - t[0]); };
    auto index = [&](int i, int j) { return base + i * (n + 1) - i * (i - 1) / 2 + j; };  // rows of shrinking length
    if (!ruled)
      for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n - i; ++j) {
          const Vec2 uv = grid(i, j);
          // For the bounds a point counts once: the triangles' shared corners (each
          // domain vertex is a corner of about six) are evaluated once.
          if (fast && !bounded.insert({uv.x(), uv.y()}).second) continue;
          const Vec3 p = evaluate(s, uv);
          if (fast) out.bounds.add(p);
          else out.mesh.vertices.push_back(p);
        }
    const bool flip = orientation((t[0] + t[1] + t[2]) / 3) < 0;
    auto piece = [&](const Vec2& a, const Vec2& b, const Vec2& c, int ia, int ib, int ic) {
      if (o.mesh_only && !fast) {
        out.mesh.triangles.push_back(flip ? std::array<int, 3>{ia, ic, ib} : std::array<int, 3>{ia, ib, ic});
        return;
      }
      const double jac = 0.5 * std::abs((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
      for (std::size_t q = 0; q < rule.weight.size(); ++q) {
        const Vec2 uv = rule.bary[q][0] * a + rule.bary[q][1] * b + rule.bary[q][2] * c;
        const double w = rule.weight[q] * jac * area_element(s, uv);
        area += w;
        if (!fast) moment += w * evaluate(s, uv);
      }
      if (!fast) out.mesh.triangles.push_back(flip ? std::array<int, 3>{ia, ic, ib} : std::array<int, 3>{ia, ib, ic});
    };
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n - i; ++j) {
        piece(grid(i, j), grid(i + 1, j), grid(i, j + 1), index(i, j), index(i + 1, j), index(i, j + 1));
        if (j + 1 < n - i)
          piece(grid(i + 1, j), grid(i + 1, j + 1), grid(i, j + 1), index(i + 1, j), index(i + 1, j + 1),
                index(i, j + 1));
      }
  };
  // Pieces: no angular parameter may vary by more than `step` across one. Where u alone
  // is angular (cylinders, cones) the triangle is halved at the midpoint of its side
  // longest in u until it is that narrow: about 2·extent/step pieces. A regular n×n split
  // (n = ⌈extent/step⌉) costs n² even for a sliver with one long side, and the CDT makes
  // many of those between a boundary and a distant grid row (one cylinder face of
  // OpenCASCADE's Bottom.brep: 31 million pieces, 12 s). Spheres and tori keep the
  // regular split: their grid is square in (u, v), so their triangles are not slivers,
  // and halving the fans at a pole makes needles whose flat triangles turn inside out
  // (Area.TessellationCoversTheRegion).
  const bool halve = !std::holds_alternative<Sphere>(s) && !std::holds_alternative<Torus>(s);
  for (CDT::Face_handle f : cdt.finite_face_handles()) {
    if (!f->info().in_domain()) continue;
    std::array<Vec2, 3> t;
    for (int i = 0; i < 3; ++i) t[i] = Vec2(f->vertex(i)->point().x(), f->vertex(i)->point().y());
    if (closed_form)
      if (const std::optional<double> exact = exact_triangle_area(s, t)) {
        area += *exact;
        continue;
      }
    if (ruled) {
      // A cone's triangle reaching across the apex has |area element| kinked inside it:
      // split as usual there.
      const double apex = cone ? apex_parameter(*cone) : 0.0;
      const bool across_apex = cone && std::min({t[0].y(), t[1].y(), t[2].y()}) < apex &&
                               std::max({t[0].y(), t[1].y(), t[2].y()}) > apex;
      if (!across_apex) {
        split_regular(t, 1);
        continue;
      }
    }
    std::vector<std::array<Vec2, 3>> stack{t};
    while (!stack.empty()) {
      const std::array<Vec2, 3> k = stack.back();
      stack.pop_back();
      const double extent = angular_extent(s, k[0], k[1], k[2]);
      if (halve && std::isfinite(extent) && extent > step) {
        // Side i runs from k[i] to k[(i+1)%3].
        int longest = 0;
        double widest = -1;
        for (int i = 0; i < 3; ++i) {
          const double e = angular_extent(s, k[i], k[(i + 1) % 3], k[(i + 1) % 3]);
          if (e > widest) widest = e, longest = i;
        }
        const Vec2 &a = k[longest], &b = k[(longest + 1) % 3], &o = k[(longest + 2) % 3];
        const Vec2 m = 0.5 * (a + b);
        stack.push_back({a, m, o});  // both halves keep the triangle's orientation
        stack.push_back({m, b, o});
        continue;
      }
      split_regular(k, std::max(1, static_cast<int>(std::ceil(extent / step))));
    }
  }
  out.area = area;
  out.centroid = area > 0 && !fast ? Vec3(moment / area) : Vec3::Zero();
  if (cone && ruled) {
    // The apex, where the region reaches it (it is on no boundary sample).
    const double apex = apex_parameter(*cone);
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (CDT::Face_handle f : cdt.finite_face_handles())
      if (f->info().in_domain())
        for (int i = 0; i < 3; ++i) lo = std::min(lo, f->vertex(i)->point().y()), hi = std::max(hi, f->vertex(i)->point().y());
    const double slack = 1e-9 * (hi - lo + std::abs(apex) + 1);
    if (lo <= apex + slack && hi >= apex - slack) out.bounds.add(evaluate(s, Vec2(0.0, apex)));
  }
  if (closed_form) add_extreme_points(cdt, s, domain, out.bounds);
  for (const Vec3& v : out.mesh.vertices) out.bounds.add(v);
  for (const auto& loop : loops)
    for (const Vec3& p : loop) out.bounds.add(p);
  return out;
}

}  // namespace kintsugi::geo
