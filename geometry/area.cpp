#include "geometry/area.h"

#include "geometry/parameter_domain.h"
#include "geometry/surface.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>

#include <cmath>
#include <exception>
#include <limits>
#include <list>

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
void add_grid(CDT& cdt, const Surface& s, const ParameterDomain& d, double step) {
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
  // Free-form: no radius to scale by; a 16 x 16 grid over the region's parameter box
  // keeps the triangles small where the area element varies.
  if (is_freeform(s)) {
    hu = (hi.x() - lo.x()) / 16;
    hv = (hi.y() - lo.y()) / 16;
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
    for (const auto& poly : domain.polygons) {
      std::vector<K::Point_2> pts;
      for (const Vec2& p : poly) {
        const K::Point_2 q(p.x(), p.y());
        if (pts.empty() || pts.back() != q) pts.push_back(q);
      }
      while (pts.size() > 1 && pts.front() == pts.back()) pts.pop_back();
      if (pts.size() < 3) continue;
      cdt.insert_constraint(pts.begin(), pts.end(), /*close=*/true);
    }
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
  add_grid(cdt, s, domain, o.max_angle_step > 0 ? o.max_angle_step : 0.05);
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
  for (CDT::Face_handle f : cdt.finite_face_handles()) {
    if (!f->info().in_domain()) continue;
    std::array<Vec2, 3> t;
    for (int i = 0; i < 3; ++i) t[i] = Vec2(f->vertex(i)->point().x(), f->vertex(i)->point().y());
    const int n = std::max(1, static_cast<int>(std::ceil(angular_extent(s, t[0], t[1], t[2]) / step)));
    // Regular n×n split of the triangle: grid point (i, j) = t0 + i/n (t1 - t0) + j/n (t2 - t0).
    const int base = static_cast<int>(out.mesh.vertices.size());
    auto grid = [&](int i, int j) { return t[0] + (double(i) / n) * (t[1] - t[0]) + (double(j) / n) * (t[2] - t[0]); };
    auto index = [&](int i, int j) { return base + i * (n + 1) - i * (i - 1) / 2 + j; };  // rows of shrinking length
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n - i; ++j) out.mesh.vertices.push_back(evaluate(s, grid(i, j)));
    const bool flip = orientation((t[0] + t[1] + t[2]) / 3) < 0;
    auto piece = [&](const Vec2& a, const Vec2& b, const Vec2& c, int ia, int ib, int ic) {
      const double jac = 0.5 * std::abs((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
      for (std::size_t q = 0; q < rule.weight.size(); ++q) {
        const Vec2 uv = rule.bary[q][0] * a + rule.bary[q][1] * b + rule.bary[q][2] * c;
        const double w = rule.weight[q] * jac * area_element(s, uv);
        area += w;
        moment += w * evaluate(s, uv);
      }
      out.mesh.triangles.push_back(flip ? std::array<int, 3>{ia, ic, ib} : std::array<int, 3>{ia, ib, ic});
    };
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n - i; ++j) {
        piece(grid(i, j), grid(i + 1, j), grid(i, j + 1), index(i, j), index(i + 1, j), index(i, j + 1));
        if (j + 1 < n - i)
          piece(grid(i + 1, j), grid(i + 1, j + 1), grid(i, j + 1), index(i + 1, j), index(i + 1, j + 1),
                index(i, j + 1));
      }
  }
  out.area = area;
  out.centroid = area > 0 ? Vec3(moment / area) : Vec3::Zero();
  for (const Vec3& v : out.mesh.vertices) out.bounds.add(v);
  for (const auto& loop : loops)
    for (const Vec3& p : loop) out.bounds.add(p);
  return out;
}

}  // namespace kintsugi::geo
