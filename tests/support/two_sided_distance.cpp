#include "tests/support/two_sided_distance.h"

#include "invariants/element_geometry.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <cmath>
#include <list>
#include <vector>

namespace kintsugi::test {

namespace {

using K = CGAL::Simple_cartesian<double>;
using Triangle = K::Triangle_3;
using Point = K::Point_3;
using Primitive = CGAL::AABB_triangle_primitive<K, std::vector<Triangle>::iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

Point pt(const geo::Vec3& v) { return Point(v.x(), v.y(), v.z()); }

// The triangles of every face and the points to measure from: the tessellation's vertices
// and the centres of its triangles.
bool tessellate(const Body& b, double chordal, std::vector<Triangle>& tris, std::vector<Point>& samples, std::string* why) {
  for (FaceH f : b.faces()) {
    geo::RegionMeasure m = face_measure(b, f, chordal);
    if (!m.ok()) {
      *why = f.str() + ": " + m.problem;
      return false;
    }
    for (const auto& v : m.mesh.vertices) samples.push_back(pt(v));
    for (const auto& t : m.mesh.triangles) {
      const geo::Vec3 &p = m.mesh.vertices[std::size_t(t[0])], &q = m.mesh.vertices[std::size_t(t[1])],
                      &r = m.mesh.vertices[std::size_t(t[2])];
      tris.emplace_back(pt(p), pt(q), pt(r));
      samples.push_back(pt((p + q + r) / 3.0));
    }
  }
  return true;
}

double one_way(const std::vector<Point>& from, std::vector<Triangle>& to) {
  if (to.empty()) return HUGE_VAL;
  Tree tree(to.begin(), to.end());
  tree.accelerate_distance_queries();
  // At most about 50000 points (every k-th): dense tessellations (a cone's apex) would
  // make this the slowest part of a test.
  const std::size_t step = std::max<std::size_t>(1, from.size() / 50000);
  double worst = 0;
  for (std::size_t i = 0; i < from.size(); i += step) worst = std::max(worst, std::sqrt(tree.squared_distance(from[i])));
  return worst;
}

}  // namespace

TwoSided two_sided_distance(const Body& a, const Body& b, double chordal) {
  TwoSided out;
  std::vector<Triangle> ta, tb;
  std::vector<Point> sa, sb;
  if (!tessellate(a, chordal, ta, sa, &out.problem) || !tessellate(b, chordal, tb, sb, &out.problem)) {
    out.a_to_b = out.b_to_a = HUGE_VAL;
    return out;
  }
  out.a_to_b = one_way(sa, tb);
  out.b_to_a = one_way(sb, ta);
  return out;
}

}  // namespace kintsugi::test
