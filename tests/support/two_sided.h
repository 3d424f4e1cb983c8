// Two-sided distance between the boundaries of two bodies, for "the beautified model lies
// within tolerance of the clean model, both ways": every face is tessellated
// (face_measure), its triangles are sampled on a grid of spacing `step`, and the largest
// distance from a sample of one body to the triangles of the other is taken, each way.
// Sampling makes it a lower bound off by at most about `step`.
#pragma once

#include "invariants/element_geometry.h"

#include <array>
#include <cmath>
#include <vector>

namespace kintsugi::test {

using Triangle = std::array<geo::Vec3, 3>;

inline std::vector<Triangle> triangles_of(const Body& b, double chordal) {
  std::vector<Triangle> out;
  for (FaceH f : b.faces()) {
    geo::RegionMeasure m = face_measure(b, f, chordal);
    for (const auto& t : m.mesh.triangles) out.push_back({m.mesh.vertices[t[0]], m.mesh.vertices[t[1]], m.mesh.vertices[t[2]]});
  }
  return out;
}

// Closest point of triangle abc to p (Ericson, Real-Time Collision Detection, 5.1.5).
inline geo::Vec3 closest_on_triangle(const geo::Vec3& p, const Triangle& t) {
  const geo::Vec3 &a = t[0], &b = t[1], &c = t[2];
  geo::Vec3 ab = b - a, ac = c - a, ap = p - a;
  double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  geo::Vec3 bp = p - b;
  double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  geo::Vec3 cp = p - c;
  double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  double denom = 1 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

inline std::vector<geo::Vec3> sample_triangles(const std::vector<Triangle>& ts, double step) {
  std::vector<geo::Vec3> out;
  for (const Triangle& t : ts) {
    double longest = std::max({(t[1] - t[0]).norm(), (t[2] - t[1]).norm(), (t[0] - t[2]).norm()});
    int n = std::max(1, int(std::ceil(longest / step)));
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) out.push_back(t[0] + (t[1] - t[0]) * (double(i) / n) + (t[2] - t[0]) * (double(j) / n));
  }
  return out;
}

inline double one_sided_distance(const std::vector<geo::Vec3>& from, const std::vector<Triangle>& to) {
  double worst = 0;
  for (const geo::Vec3& p : from) {
    double best = HUGE_VAL;
    for (const Triangle& t : to) best = std::min(best, (closest_on_triangle(p, t) - p).squaredNorm());
    worst = std::max(worst, std::sqrt(best));
  }
  return worst;
}

inline double two_sided_distance(const Body& a, const Body& b, double step, double chordal = 1e-3) {
  std::vector<Triangle> ta = triangles_of(a, chordal), tb = triangles_of(b, chordal);
  return std::max(one_sided_distance(sample_triangles(ta, step), tb), one_sided_distance(sample_triangles(tb, step), ta));
}

}  // namespace kintsugi::test
