// Two-sided distance between the surfaces of two bodies, for checking that a repaired
// model lies within tolerance of the clean (designer's) model both ways. Each body is
// tessellated (face_measure); points sampled on one (triangle corners, edge midpoints,
// centroids) are measured against the other's triangles. Brute force: for the small
// models of the tests.
#pragma once

#include "invariants/element_geometry.h"
#include "kernel/body.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace kintsugi::test {

struct Triangles {
  std::vector<std::array<geo::Vec3, 3>> tris;
};

inline Triangles tessellate(const Body& b, double chordal) {
  Triangles out;
  for (FaceH f : b.faces()) {
    geo::RegionMeasure m = face_measure(b, f, chordal);
    for (const auto& t : m.mesh.triangles)
      out.tris.push_back({m.mesh.vertices[std::size_t(t[0])], m.mesh.vertices[std::size_t(t[1])],
                          m.mesh.vertices[std::size_t(t[2])]});
  }
  return out;
}

// Closest point of triangle abc to p (Ericson, Real-Time Collision Detection 5.1.5).
inline double point_triangle(const geo::Vec3& p, const geo::Vec3& a, const geo::Vec3& b, const geo::Vec3& c) {
  const geo::Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return (p - a).norm();
  const geo::Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return (p - b).norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + ab * (d1 / (d1 - d3)))).norm();
  const geo::Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return (p - c).norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + ac * (d2 / (d2 - d6)))).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return (p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))))).norm();
  const double denom = 1 / (va + vb + vc);
  return (p - (a + ab * (vb * denom) + ac * (vc * denom))).norm();
}

// Largest distance from points sampled on `from` to the surface of `to`.
inline double one_sided(const Triangles& from, const Triangles& to) {
  double worst = 0;
  for (const auto& t : from.tris) {
    const geo::Vec3 samples[] = {t[0], t[1], t[2], (t[0] + t[1]) / 2, (t[1] + t[2]) / 2, (t[2] + t[0]) / 2,
                                 (t[0] + t[1] + t[2]) / 3};
    for (const geo::Vec3& p : samples) {
      double best = HUGE_VAL;
      for (const auto& u : to.tris) best = std::min(best, point_triangle(p, u[0], u[1], u[2]));
      worst = std::max(worst, best);
    }
  }
  return worst;
}

// max(one_sided(a, b), one_sided(b, a)).
inline double two_sided_distance(const Body& a, const Body& b, double chordal) {
  Triangles ta = tessellate(a, chordal), tb = tessellate(b, chordal);
  return std::max(one_sided(ta, tb), one_sided(tb, ta));
}

}  // namespace kintsugi::test
