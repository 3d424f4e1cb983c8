// Independent measures of recorded defects, for the zoo tests: they read the body, not
// the injector's bookkeeping.
#pragma once

#include "geometry/area.h"
#include "geometry/curve.h"
#include "geometry/same_geometry.h"
#include "geometry/surface.h"
#include "kernel/body.h"
#include "zoo/zoo.h"

#include <optional>
#include <string>

namespace kintsugi::zoo::test {

using geo::Vec3;

inline bool element_alive(const Body& b, const std::string& s) {
  if (s.size() < 2) return false;
  std::uint32_t i = std::uint32_t(std::stoul(s.substr(1)));
  switch (s[0]) {
    case 'v': return b.alive(VertexH(i));
    case 'e': return b.alive(EdgeH(i));
    case 'f': return b.alive(FaceH(i));
    case 'l': return b.alive(LoopH(i));
  }
  return false;
}

inline std::uint32_t index_of(const std::string& s) { return std::uint32_t(std::stoul(s.substr(1))); }

// Points along the half-edge h's curve (or chord), origin to target.
inline std::vector<Vec3> sample_halfedge(const Body& b, HalfedgeH h, double chordal) {
  EdgeH e = edge_of(h);
  Vec3 p = b.point(b.origin(h)), q = b.point(b.target(h));
  const geo::Curve& c = b.curve(e);
  if (std::holds_alternative<geo::Circle>(c)) {
    HalfedgeH h0 = halfedge_of(e, 0);
    geo::ParameterRange r = geo::parameter_range(c, b.point(b.origin(h0)), b.point(b.target(h0)), 1e-12);
    std::vector<Vec3> pts = geo::sample_curve(c, r.t0, r.t1, chordal);
    if (h != h0) std::reverse(pts.begin(), pts.end());
    return pts;
  }
  return {p, q};
}

inline double edge_length(const Body& b, EdgeH e) {
  std::vector<Vec3> pts = sample_halfedge(b, halfedge_of(e, 0), 1e-9);
  double l = 0;
  for (std::size_t i = 1; i < pts.size(); ++i) l += (pts[i] - pts[i - 1]).norm();
  return l;
}

inline geo::RegionMeasure face_region(const Body& b, FaceH f, double chordal = 1e-6) {
  std::vector<std::vector<Vec3>> loops;
  for (LoopH l : b.loops_of(f)) {
    std::vector<Vec3> pts;
    for (HalfedgeH h : b.loop_halfedges(l)) {
      std::vector<Vec3> s = sample_halfedge(b, h, chordal);
      pts.insert(pts.end(), s.begin(), s.end() - 1);
    }
    loops.push_back(pts);
  }
  geo::AreaOptions o;
  o.reversed = !b.same_sense(f);
  return geo::measure_region(b.surface(f), loops, o);
}

inline std::vector<Vec3> face_vertices(const Body& b, FaceH f) {
  std::vector<Vec3> out;
  for (LoopH l : b.loops_of(f))
    for (VertexH v : b.loop_vertices(l)) out.push_back(b.point(v));
  return out;
}

// Smallest distance between two straight segments.
inline double segment_distance(Vec3 p1, Vec3 q1, Vec3 p2, Vec3 q2) {
  double best = 1e300;
  const int n = 200;
  for (int i = 0; i <= n; ++i) {
    Vec3 x = p1 + (q1 - p1) * (double(i) / n);
    Vec3 d = q2 - p2;
    double t = std::clamp((x - p2).dot(d) / d.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (x - (p2 + t * d)).norm());
  }
  return best;
}

}  // namespace kintsugi::zoo::test
