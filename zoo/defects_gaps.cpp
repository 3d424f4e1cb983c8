#include "zoo/defects_gaps.h"

#include "geometry/area.h"
#include "geometry/curve.h"
#include "geometry/distance.h"
#include "geometry/surface.h"
#include "invariants/element_geometry.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace kintsugi::zoo {

namespace {

constexpr int kSamples = 8;  // polyline points per border edge, beyond its ends

Vec3 outward_at(const Body& b, FaceH f, const Vec3& p) {
  geo::SurfacePoint s = geo::closest_point(b.surface(f), p);
  return b.same_sense(f) ? s.normal : Vec3(-s.normal);
}

// The unit tangent of edge_of(h) at p, pointing the way h runs.
Vec3 tangent_along(const Body& b, HalfedgeH h, const Vec3& p) {
  EdgeH e = edge_of(h);
  const geo::Curve& c = b.curve(e);
  Vec3 t;
  if (std::holds_alternative<std::monostate>(c)) t = b.point(b.target(h)) - b.point(b.origin(h));
  else t = geo::tangent(c, geo::parameter(c, p)) * (h == halfedge_of(e, 0) ? 1.0 : -1.0);
  return t.normalized();
}

// The directions out of point c0 into face f: from `out` counter-clockwise about f's
// outward normal through `span` radians (to the direction of the edge arriving at c0).
struct Sector {
  FaceH f;
  Vec3 c0, n, out;
  double span = 0;
  Vec3 dir(double th) const { return std::cos(th) * out + std::sin(th) * n.cross(out); }
};

Sector sector(const Body& b, FaceH f, const Vec3& c0, const Vec3& d_out, const Vec3& d_in_rev) {
  Sector s;
  s.f = f;
  s.c0 = c0;
  s.n = outward_at(b, f, c0);
  s.out = (d_out - d_out.dot(s.n) * s.n).normalized();
  Vec3 back = (d_in_rev - d_in_rev.dot(s.n) * s.n).normalized();
  double a = std::atan2(s.out.cross(back).dot(s.n), s.out.dot(back));
  s.span = a > 1e-9 ? a : a + 2 * M_PI;
  return s;
}

// Where the walk from c0 along `along(t)` leaves the region (bisection on t).
template <class F>
Vec3 leave(const MissingRegion& r, F along, double reach) {
  if (!(r.phi(along(0.0)) < 0)) throw Unsuitable("the region's centre is not inside it");
  if (!(r.phi(along(reach)) > 0)) throw Unsuitable("the region reaches too far");
  double lo = 0, hi = reach;
  for (int i = 0; i < 80; ++i) {
    double mid = 0.5 * (lo + hi);
    (r.phi(along(mid)) < 0 ? lo : hi) = mid;
  }
  return along(hi);
}

Vec3 leave_in_face(const Body& b, const Sector& s, double th, const MissingRegion& r, double reach) {
  Vec3 d = s.dir(th);
  return leave(r, [&](double t) { return geo::closest_point(b.surface(s.f), s.c0 + t * d).point; }, reach);
}

Vec3 leave_on_edge(const Body& b, EdgeH e, const Vec3& c0, const Vec3& d, const MissingRegion& r, double reach) {
  const geo::Curve& c = b.curve(e);
  return leave(r, [&](double t) { return geo::closest_point(c, c0 + t * d).point; }, reach);
}

// The region's border in sector s, from the edge arriving at c0 (exit `first`) to the
// edge leaving it (exit `last`): n_edges * kSamples + 1 points, every kSamples-th a vertex.
std::vector<Vec3> border_in(const Body& b, const Sector& s, const Vec3& first, const Vec3& last, int n_edges,
                            const MissingRegion& r, double reach) {
  const int n = n_edges * kSamples;
  std::vector<Vec3> pts{first};
  for (int k = 1; k < n; ++k) pts.push_back(leave_in_face(b, s, s.span * (1.0 - double(k) / n), r, reach));
  pts.push_back(last);
  return pts;
}

// Gives edge_of(x) the polyline pts (which run the way x does).
void set_polyline(Body& b, HalfedgeH x, std::vector<Vec3> pts) {
  if (x != halfedge_of(edge_of(x), 0)) std::reverse(pts.begin(), pts.end());
  geo::Polyline p;
  p.points = std::move(pts);
  b.set_curve(edge_of(x), p);
}

// Cuts the half-edge x (running along pts' ends) at the vertices of pts and gives the
// pieces their polylines.
void split_along(Body& b, HalfedgeH x, const std::vector<Vec3>& pts) {
  const int n = int(pts.size() - 1) / kSamples;
  for (int j = 0; j < n; ++j) {
    HalfedgeH piece = x;
    if (j + 1 < n) {
      SemvResult s = must(euler::semv(b, x, pts[std::size_t((j + 1) * kSamples)]), "semv (scan gap)");
      x = s.next;
    }
    set_polyline(b, piece, {pts.begin() + j * kSamples, pts.begin() + (j + 1) * kSamples + 1});
  }
}

double reach_of(const MissingRegion& r) { return 4 * r.radius + 2 * r.half_length; }

// Distance from p to the edges of f other than `skip` (edges at vertex `at` are skipped too).
double clearance(const Body& b, FaceH f, const Vec3& p, EdgeH skip, VertexH at) {
  double d = 1e300;
  for (LoopH l : b.loops_of(f))
    for (HalfedgeH h : b.loop_halfedges(l)) {
      if (edge_of(h) == skip || (at.valid() && (b.origin(h) == at || b.target(h) == at))) continue;
      d = std::min(d, geo::point_polyline(p, halfedge_polyline(b, h, 1e-3)).distance);
    }
  return d;
}

std::string name_of(LoopH l) { return l.str(); }

}  // namespace

const char* shape_name(MissingRegion::Shape s) {
  switch (s) {
    case MissingRegion::ball: return "ball";
    case MissingRegion::short_cylinder: return "short cylinder";
    case MissingRegion::blob: return "blob";
  }
  return "?";
}

double MissingRegion::phi(const Vec3& p) const {
  Vec3 q = p - centre;
  switch (shape) {
    case ball: return q.norm() - radius;
    case short_cylinder: {
      double h = q.dot(axis);
      return std::max((q - h * axis).norm() - radius, std::abs(h) - half_length);
    }
    case blob: {
      double v = std::sqrt(q.dot(shape_matrix * q)) - radius;
      for (const auto& [n, d] : cuts) v = std::max(v, n.dot(q) - d);
      return v;
    }
  }
  return 1;
}

MissingRegion MissingRegion::random(Shape shape, const Vec3& centre, double across, Rng& rng) {
  MissingRegion r;
  r.shape = shape;
  r.centre = centre;
  auto unit = [&] {
    Vec3 v(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    return v.norm() > 1e-3 ? Vec3(v.normalized()) : Vec3::UnitZ();
  };
  switch (shape) {
    case ball: r.radius = 0.5 * across; break;
    case short_cylinder:
      // Both the diameter and the length stay within `across` (diagonal <= across).
      r.radius = 0.5 * across * rng.uniform(0.45, 0.65);
      r.half_length = std::sqrt(std::max(0.0, 0.25 * across * across - r.radius * r.radius)) * 0.9;
      r.axis = unit();
      break;
    case blob: {
      // An ellipsoid with semi-axes in [0.6, 1] x radius, cut by two or three planes.
      r.radius = 0.5 * across;
      Eigen::Matrix3d q = Eigen::Quaterniond(Eigen::Vector4d(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1),
                                                             rng.uniform(-1, 1)).normalized())
                              .toRotationMatrix();
      Eigen::Vector3d scale(1.0, 1.0 / rng.uniform(0.6, 1.0), 1.0 / rng.uniform(0.6, 1.0));
      r.shape_matrix = q * (scale.array().square().matrix().asDiagonal()) * q.transpose();
      int cuts = 2 + int(rng.below(2));
      for (int i = 0; i < cuts; ++i) r.cuts.push_back({unit(), r.radius * rng.uniform(0.55, 0.85)});
      break;
    }
  }
  return r;
}

namespace make {

KnownDefect scan_gap_in_face(Body& b, FaceH f, const MissingRegion& r, int edges) {
  if (std::holds_alternative<std::monostate>(b.surface(f))) throw Unsuitable(f.str() + " has no surface");
  const double reach = reach_of(r);
  const Vec3 c0 = geo::closest_point(b.surface(f), r.centre).point;
  if (clearance(b, f, c0, EdgeH{}, VertexH{}) < 2 * reach) throw Unsuitable("the region does not fit inside " + f.str());
  Vec3 n = outward_at(b, f, c0), x = n.unitOrthogonal();
  Sector s{f, c0, n, x, 2 * M_PI};
  edges = std::max(edges, 1);
  // The border, counter-clockwise about the outward normal (the disc's loop), from θ = 0.
  const int total = edges * kSamples;
  std::vector<Vec3> pts;
  for (int k = 0; k <= total; ++k) pts.push_back(leave_in_face(b, s, 2 * M_PI * (k % total) / total, r, reach));
  // A lone-vertex ring at pts[0], a self-loop disc through it, cut at the other vertices.
  HalfedgeH h0 = b.first(b.outer_loop(f));
  MevResult strut = must(euler::mev(b, Corner::before(h0), pts[0]), "mev (strut)");
  LoopH ring = must(euler::kemr(b, strut.x), "kemr").ring;
  MefResult disc = must(euler::mef(b, Corner::in_lone(ring), Corner::in_lone(ring)), "mef (disc)");
  b.set_surface(disc.face, b.surface(f), b.same_sense(f));
  split_along(b, disc.b, pts);
  LoopH border = must(euler::kfmb(b, disc.face), "kfmb (scan gap)").border;
  double across = 0;
  for (const Vec3& p : pts)
    for (const Vec3& q : pts) across = std::max(across, (p - q).norm());
  KnownDefect d{ProblemType::face_gap, {f.str(), name_of(border)}, across};
  for (HalfedgeH h : b.loop_halfedges(border)) d.elements.push_back(edge_of(h).str());
  return d;
}

KnownDefect scan_gap_on_edge(Body& b, EdgeH e, const MissingRegion& r, int per_side) {
  HalfedgeH h = halfedge_of(e, 0);
  FaceH f1 = b.face(h), f2 = b.face(twin(h));
  if (!f1.valid() || !f2.valid() || f1 == f2) throw Unsuitable(e.str() + " is not between two faces");
  const geo::Curve& curve = b.curve(e);
  if (!std::holds_alternative<geo::Line>(curve) && !std::holds_alternative<geo::Circle>(curve))
    throw Unsuitable(e.str() + " is neither straight nor circular");
  const double reach = reach_of(r);
  const Vec3 c0 = geo::closest_point(curve, r.centre).point;
  for (VertexH v : {b.origin(h), b.target(h)})
    if ((b.point(v) - c0).norm() < 2 * reach) throw Unsuitable("the region reaches an end of " + e.str());
  for (FaceH f : {f1, f2})
    if (clearance(b, f, c0, e, VertexH{}) < 2 * reach) throw Unsuitable("the region reaches another edge of " + f.str());
  const Vec3 t = tangent_along(b, h, c0);
  const Vec3 a = leave_on_edge(b, e, c0, -t, r, reach), c = leave_on_edge(b, e, c0, t, r, reach);
  // The borders: in f1 from a to c (h runs a -> c there), in f2 from c to a.
  Sector s1 = sector(b, f1, c0, t, -t), s2 = sector(b, f2, c0, -t, t);
  per_side = std::max(per_side, 1);
  std::vector<Vec3> p1 = border_in(b, s1, a, c, per_side, r, reach), p2 = border_in(b, s2, c, a, per_side, r, reach);
  SemvResult sa = must(euler::semv(b, h, a), "semv (scan gap)");
  must(euler::semv(b, sa.next, c), "semv (scan gap)");
  HalfedgeH mid = sa.next;  // a -> c, in f1
  // A path through the face from origin(m) to target(m) along pts; returns the face cut off.
  auto path = [&](HalfedgeH m, const std::vector<Vec3>& pts) {
    Corner at = Corner::before(m);
    HalfedgeH back;
    std::vector<HalfedgeH> made;
    for (int j = 1; j < per_side; ++j) {
      MevResult s = must(euler::mev(b, at, pts[std::size_t(j * kSamples)]), "mev (scan gap)");
      made.push_back(s.x);
      back = s.y;
      at = Corner::before(back);
    }
    MefResult last = back.valid() ? must(euler::mef(b, Corner::before(back), Corner::before(b.next(m))), "mef (scan gap)")
                                  : must(euler::mef(b, Corner::before(m), Corner::before(b.next(m))), "mef (scan gap)");
    // The new face is on m's side; the edges along pts run origin(m) -> ... -> target(m)
    // as made[0].x, made[1].x, ..., and the closing edge's side a (last vertex -> target(m)).
    made.push_back(last.a);
    for (std::size_t j = 0; j < made.size(); ++j)
      set_polyline(b, made[j], {pts.begin() + long(j) * kSamples, pts.begin() + long(j + 1) * kSamples + 1});
    return last.face;
  };
  FaceH g1 = path(mid, p1);
  path(twin(mid), p2);
  must(euler::kef(b, mid), "kef (scan gap)");
  LoopH border = must(euler::kfmb(b, g1), "kfmb (scan gap)").border;
  double across = (a - c).norm();
  for (const auto* ps : {&p1, &p2})
    for (const Vec3& p : *ps) across = std::max({across, (p - a).norm(), (p - c).norm()});
  return {ProblemType::edge_gap, {f1.str(), f2.str(), name_of(border)}, across};
}

KnownDefect scan_gap_at_vertex(Body& b, VertexH v, const MissingRegion& r, int per_face) {
  const std::vector<HalfedgeH> outs = b.outgoing(v);
  if (outs.size() < 3) throw Unsuitable(v.str() + " lies on fewer than three edges");
  std::vector<FaceH> faces;
  for (HalfedgeH o : outs) {
    FaceH f = b.face(o);
    if (!f.valid() || std::find(faces.begin(), faces.end(), f) != faces.end())
      throw Unsuitable(v.str() + " is not a corner of distinct faces");
    faces.push_back(f);
  }
  const double reach = reach_of(r);
  const Vec3 p = b.point(v);
  for (HalfedgeH o : outs) {
    if (b.target(o) == v || (b.point(b.target(o)) - p).norm() < 2 * reach) throw Unsuitable("an edge at " + v.str() + " is too short");
    if (clearance(b, b.face(o), p, EdgeH{}, v) < 2 * reach) throw Unsuitable("the region reaches another edge of " + b.face(o).str());
  }
  // Cut points on every edge, and each face's border from the edge arriving at v (in its
  // loop) to the edge leaving it.
  std::vector<Vec3> cut(outs.size());
  for (std::size_t i = 0; i < outs.size(); ++i)
    cut[i] = leave_on_edge(b, edge_of(outs[i]), p, tangent_along(b, outs[i], p), r, reach);
  auto index_of = [&](HalfedgeH o) { return std::size_t(std::find(outs.begin(), outs.end(), o) - outs.begin()); };
  std::vector<std::vector<Vec3>> border(outs.size());  // by the face of outs[i]
  for (std::size_t i = 0; i < outs.size(); ++i) {
    HalfedgeH o = outs[i], in = b.prev(o);  // in arrives at v in the same loop
    std::size_t k = index_of(twin(in));
    Sector s = sector(b, b.face(o), p, tangent_along(b, o, p), tangent_along(b, twin(in), p));
    border[i] = border_in(b, s, cut[k], cut[i], std::max(per_face, 1), r, reach);
  }
  Truncation t = truncate_vertex(b, v, [&](HalfedgeH o) { return cut[index_of(o)]; });
  // Each cap edge: its other side lies in a face F; split it along F's border.
  for (HalfedgeH x : b.loop_halfedges(b.outer_loop(t.face))) {
    HalfedgeH y = twin(x);
    const Vec3 from = b.point(b.origin(y)), to = b.point(b.target(y));
    bool done = false;
    for (std::size_t i = 0; i < outs.size() && !done; ++i)
      if (faces[i] == b.face(y) && (border[i].front() - from).norm() < 1e-12 && (border[i].back() - to).norm() < 1e-12) {
        split_along(b, y, border[i]);
        done = true;
      }
    if (!done) throw std::logic_error("scan gap: a cap edge matches no face's border");
  }
  std::vector<Vec3> pts;
  for (VertexH w : b.loop_vertices(b.outer_loop(t.face))) pts.push_back(b.point(w));
  LoopH l = must(euler::kfmb(b, t.face), "kfmb (scan gap)").border;
  double across = 0;
  for (const Vec3& a : pts)
    for (const Vec3& c : pts) across = std::max(across, (a - c).norm());
  KnownDefect d{ProblemType::multi_face_gap, {name_of(l)}, across};
  for (FaceH f : faces) d.elements.push_back(f.str());
  return d;
}

}  // namespace make

namespace {

// The point of face f farthest from its edges, among its area centroid and the centres
// of its tessellation's triangles (on the surface); Unsuitable when f cannot be measured.
Vec3 roomiest_point(const Body& b, FaceH f, double tol) {
  auto bound = face_boundary(b, f, 1e-3 * tol);
  // A plane's centroid needs its area; a curved face's tessellation alone will do, and a
  // coarse one (0.2 rad a triangle: about a thousand on a whole torus) spreads candidates
  // far closer than any face is wide. At measure_region's default 0.05 rad, 16 times the
  // triangles, choosing the spot was half the Table 1 audit's time.
  geo::AreaOptions o;
  o.reversed = !b.same_sense(f);
  o.mesh_only = !std::holds_alternative<geo::Plane>(b.surface(f));
  o.max_angle_step = 0.2;
  const geo::RegionMeasure m = geo::measure_region(b.surface(f), bound, o);
  if (!m.ok()) throw Unsuitable(f.str() + " cannot be measured: " + m.problem);
  // At most about 1024 triangles, evenly spread over the tessellation: a curved face's
  // has thousands, and the gap needs room, not the exact farthest point. (Every triangle
  // against every boundary segment took over a minute on a builder cone under the
  // sanitizers: a fuzz_beautify timeout.)
  // The centroid only of a planar face: a curved face's (a cone's band, a cylinder's side)
  // is off the face, and its foot on the surface can be outside the face, where a hole
  // 3D-far from every edge passed for roomy (the scan-parts score, a tee's chamfer; region
  // validity now refuses such a hole: hole_outside).
  std::vector<Vec3> candidates;
  if (std::holds_alternative<geo::Plane>(b.surface(f))) candidates.push_back(m.centroid);
  const std::size_t stride = 1 + m.mesh.triangles.size() / 1024;
  for (std::size_t t = 0; t < m.mesh.triangles.size(); t += stride) {
    const auto& tri = m.mesh.triangles[t];
    candidates.push_back((m.mesh.vertices[std::size_t(tri[0])] + m.mesh.vertices[std::size_t(tri[1])] +
                          m.mesh.vertices[std::size_t(tri[2])]) / 3.0);
  }
  Vec3 best = Vec3::Zero();
  double room = 0;
  for (const Vec3& c : candidates) {
    Vec3 p = geo::closest_point(b.surface(f), c).point;
    double d = 1e300;
    for (const auto& l : bound) d = std::min(d, geo::point_polyline(p, l).distance);
    if (d > room) room = d, best = p;
  }
  if (room <= 0) throw Unsuitable(f.str() + " has no room for a gap");
  return best;
}

}  // namespace

std::vector<GapSite> gap_sites(const Body& b, ProblemType t, double tol, Rng& rng, const std::vector<FaceH>& faces,
                               const std::vector<EdgeH>& edges, const std::vector<VertexH>& vertices) {
  std::vector<GapSite> out;
  auto shape = [&] { return MissingRegion::Shape(rng.below(3)); };
  auto across = [&] { return tol * rng.uniform(0.2, 0.7); };
  switch (t) {
    case ProblemType::face_gap:
      for (FaceH f : faces) {
        if (std::holds_alternative<std::monostate>(b.surface(f))) continue;
        // The region's size, shape and offset are drawn now, in the order they always were
        // (a recipe's seed rebuilds the same model); where on the face it goes is found
        // only when this site is tried: measuring every face up front was most of the
        // Table 1 audit's time, for the one site used.
        MissingRegion r = MissingRegion::random(shape(), Vec3::Zero(), across(), rng);
        const double off_surface = rng.uniform(-0.2, 0.2);  // not always centred on the surface
        int n = 1 + int(rng.below(4));
        out.push_back({[=](Body& x) {
                         MissingRegion placed = r;
                         placed.centre = roomiest_point(x, f, tol);
                         placed.centre += outward_at(x, f, placed.centre) * off_surface * placed.radius;
                         return make::scan_gap_in_face(x, f, placed, n);
                       },
                       f.str() + " (" + shape_name(r.shape) + ")"});
      }
      break;
    case ProblemType::edge_gap:
      for (EdgeH e : edges) {
        const geo::Curve& c = b.curve(e);
        if (!std::holds_alternative<geo::Line>(c) && !std::holds_alternative<geo::Circle>(c)) continue;
        auto pts = halfedge_polyline(b, halfedge_of(e, 0), 1e-3 * tol);
        if (pts.size() < 2) continue;
        // A point along the edge, away from its ends.
        double len = 0;
        for (std::size_t i = 1; i < pts.size(); ++i) len += (pts[i] - pts[i - 1]).norm();
        double want = len * rng.uniform(0.35, 0.65), run = 0;
        Vec3 at = pts.front();
        for (std::size_t i = 1; i < pts.size(); ++i) {
          double s = (pts[i] - pts[i - 1]).norm();
          if (run + s >= want) {
            at = pts[i - 1] + (want - run) / s * (pts[i] - pts[i - 1]);
            break;
          }
          run += s;
        }
        MissingRegion r = MissingRegion::random(shape(), at, across(), rng);
        int n = 1 + int(rng.below(3));
        out.push_back({[=](Body& x) { return make::scan_gap_on_edge(x, e, r, n); },
                       e.str() + " (" + shape_name(r.shape) + ")"});
      }
      break;
    case ProblemType::multi_face_gap:
      for (VertexH v : vertices) {
        MissingRegion r = MissingRegion::random(shape(), b.point(v), across(), rng);
        int n = 1 + int(rng.below(2));
        out.push_back({[=](Body& x) { return make::scan_gap_at_vertex(x, v, r, n); },
                       v.str() + " (" + shape_name(r.shape) + ")"});
      }
      break;
    default: break;
  }
  return out;
}

}  // namespace kintsugi::zoo
