#include "zoo/local_ops.h"

#include "geometry/curve.h"
#include "geometry/polygon.h"

#include <Eigen/Dense>

#include <cmath>
#include <stdexcept>

namespace kintsugi::zoo {

HalfedgeH out_in_loop(const Body& b, VertexH v, LoopH l) {
  for (HalfedgeH h : b.outgoing(v))
    if (b.loop(h) == l) return h;
  return HalfedgeH{};
}

HalfedgeH out_in_face(const Body& b, VertexH v, FaceH f) {
  for (HalfedgeH h : b.outgoing(v))
    if (b.face(h) == f) return h;
  return HalfedgeH{};
}

HalfedgeH side_in_face(const Body& b, EdgeH e, FaceH f) {
  for (unsigned s = 0; s < 2; ++s)
    if (b.face(halfedge_of(e, s)) == f) return halfedge_of(e, s);
  return HalfedgeH{};
}

std::vector<FaceH> faces_around(const Body& b, VertexH v) {
  std::vector<FaceH> out;
  for (HalfedgeH h : b.outgoing(v)) out.push_back(b.face(h));
  return out;
}

// nullptr for a border side (no face) as for a face that is not planar.
const geo::Plane* plane_of(const Body& b, FaceH f) {
  if (!b.alive(f)) return nullptr;
  return std::get_if<geo::Plane>(&b.surface(f));
}

Vec3 outward_normal(const Body& b, FaceH f) {
  const geo::Plane* p = plane_of(b, f);
  if (!p) throw std::logic_error("face " + f.str() + " is not planar");
  return b.same_sense(f) ? p->frame.z : Vec3(-p->frame.z);
}

Vec3 newell(const Body& b, LoopH l) { return geo::polygon_normal(loop_points(b, l)); }

std::vector<Vec3> loop_points(const Body& b, LoopH l) {
  std::vector<Vec3> pts;
  for (VertexH v : b.loop_vertices(l)) pts.push_back(b.point(v));
  return pts;
}

double polygon_area(const std::vector<Vec3>& pts) { return geo::polygon_area(pts); }

geo::Plane plane_through(const Vec3& point, const Vec3& normal) {
  geo::Plane p;
  p.frame.origin = point;
  p.frame.z = normal.normalized();
  p.frame.x = p.frame.z.unitOrthogonal();
  return p;
}

void set_plane(Body& b, FaceH f, const Vec3& point, const Vec3& normal) { b.set_surface(f, plane_through(point, normal), true); }

void fit_plane(Body& b, FaceH f) {
  std::vector<Vec3> pts = loop_points(b, b.outer_loop(f));
  Vec3 c = Vec3::Zero();
  for (const Vec3& p : pts) c += p;
  c /= double(pts.size());
  set_plane(b, f, c, newell(b, b.outer_loop(f)));
}

std::optional<Vec3> meet3(const Vec3& p1, const Vec3& n1, const Vec3& p2, const Vec3& n2, const Vec3& p3,
                          const Vec3& n3) {
  Eigen::Matrix3d m;
  m.row(0) = n1.normalized();
  m.row(1) = n2.normalized();
  m.row(2) = n3.normalized();
  if (std::abs(m.determinant()) < 1e-9) return std::nullopt;
  Vec3 rhs(m.row(0).dot(p1), m.row(1).dot(p2), m.row(2).dot(p3));
  return Vec3(m.fullPivLu().solve(rhs));
}

std::optional<Vec3> meet3(const Body& b, FaceH f1, FaceH f2, FaceH f3) {
  const geo::Plane *a = plane_of(b, f1), *c = plane_of(b, f2), *d = plane_of(b, f3);
  if (!a || !c || !d) return std::nullopt;
  return meet3(a->frame.origin, a->frame.z, c->frame.origin, c->frame.z, d->frame.origin, d->frame.z);
}

void set_line(Body& b, EdgeH e) {
  HalfedgeH h = halfedge_of(e, 0);
  Vec3 o = b.point(b.origin(h)), d = b.point(b.target(h)) - o;
  b.set_curve(e, geo::Line{o, d.normalized()});
}

void refit_lines(Body& b, const std::vector<VertexH>& vs) {
  for (VertexH v : vs)
    for (HalfedgeH h : b.outgoing(v)) {
      const geo::Curve& c = b.curve(edge_of(h));
      if (std::holds_alternative<geo::Line>(c) || std::holds_alternative<std::monostate>(c)) set_line(b, edge_of(h));
    }
}

void set_circle(Body& b, HalfedgeH h, const Vec3& centre, const Vec3& normal) {
  EdgeH e = edge_of(h);
  Vec3 p = b.point(b.origin(h));
  geo::Circle c;
  c.frame.origin = centre;
  c.frame.z = (h == halfedge_of(e, 0) ? normal : Vec3(-normal)).normalized();
  Vec3 x = p - centre;
  x -= x.dot(c.frame.z) * c.frame.z;
  c.radius = x.norm();
  c.frame.x = x.normalized();
  b.set_curve(e, c);
}

FaceH add_ring_face(Body& b, FaceH f, const std::vector<Vec3>& pts) {
  // A strut from a vertex of f's outer loop to pts[0], cut loose as a lone-vertex ring.
  HalfedgeH h0 = b.first(b.outer_loop(f));
  MevResult s = must(euler::mev(b, Corner::before(h0), pts[0]), "mev (strut)");
  LoopH ring = must(euler::kemr(b, s.x), "kemr").ring;
  // The chain visits pts backwards, so the ring runs clockwise about f's normal and the
  // face closed by mef (which runs the other way) counter-clockwise.
  MevResult e = must(euler::mev(b, Corner::in_lone(ring), pts.back()), "mev");
  HalfedgeH first = e.x, back = e.y;
  for (std::size_t i = pts.size() - 1; i-- > 1;) {
    e = must(euler::mev(b, Corner::before(back), pts[i]), "mev");
    back = e.y;
  }
  MefResult m = must(euler::mef(b, Corner::before(back), Corner::before(first)), "mef");
  b.set_surface(m.face, b.surface(f), b.same_sense(f));
  for (HalfedgeH h : b.loop_halfedges(b.outer_loop(m.face))) set_line(b, edge_of(h));
  return m.face;
}

FaceH add_circle_face(Body& b, FaceH f, const Vec3& centre, double radius) {
  Vec3 n = outward_normal(b, f);
  Vec3 p0 = centre + radius * n.unitOrthogonal();
  HalfedgeH h0 = b.first(b.outer_loop(f));
  MevResult s = must(euler::mev(b, Corner::before(h0), p0), "mev (strut)");
  LoopH ring = must(euler::kemr(b, s.x), "kemr").ring;
  MefResult m = must(euler::mef(b, Corner::in_lone(ring), Corner::in_lone(ring)), "mef (circle)");
  b.set_surface(m.face, b.surface(f), b.same_sense(f));
  set_circle(b, m.b, centre, n);  // the disc's loop runs counter-clockwise
  return m.face;
}

std::vector<FaceH> extrude(Body& b, FaceH g, const Vec3& d) {
  LoopH l = b.outer_loop(g);
  std::vector<HalfedgeH> hs = b.loop_halfedges(l);
  std::size_t n = hs.size();
  std::vector<HalfedgeH> leave(n);
  std::vector<VertexH> top(n);
  for (std::size_t i = 0; i < n; ++i) {
    MevResult e = must(euler::mev(b, Corner::before(hs[i]), b.point(b.origin(hs[i])) + d), "mev (extrude)");
    leave[i] = e.y;
    top[i] = e.vertex;
  }
  std::vector<FaceH> sides;
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t j = (i + 1) % n;
    MefResult m = must(euler::mef(b, Corner::before(leave[i]), Corner::before(leave[j])), "mef (extrude)");
    leave[i] = m.a;
    sides.push_back(m.face);
  }
  // g is now the far end: its plane moves by d.
  const geo::Plane* p = plane_of(b, g);
  if (p) set_plane(b, g, p->frame.origin + d, outward_normal(b, g));
  for (FaceH s : sides) fit_plane(b, s);
  refit_lines(b, top);
  return sides;
}

FaceH extrude_disc(Body& b, FaceH g, const Vec3& d, double radius, const Vec3& centre) {
  Vec3 n = outward_normal(b, g);
  HalfedgeH h = b.first(b.outer_loop(g));
  MevResult seam = must(euler::mev(b, Corner::before(h), b.point(b.origin(h)) + d), "mev (seam)");
  MefResult top = must(euler::mef(b, Corner::before(seam.y), Corner::before(seam.y)), "mef (top circle)");
  set_line(b, seam.edge);
  set_circle(b, top.b, centre + d, n);  // the top disc's loop is [b], counter-clockwise
  set_plane(b, top.face, centre + d, n);
  geo::Cylinder cyl;
  cyl.frame.origin = centre;
  cyl.frame.z = d.normalized();
  cyl.frame.x = (b.point(b.origin(h)) - centre).normalized();
  cyl.radius = radius;
  b.set_surface(g, cyl, true);
  return g;
}

FaceH raise_cone(Body& b, FaceH g, const Vec3& centre, double r0, double r1, double height) {
  if (!(0 < r1 && r1 < r0 && height > 0)) throw std::logic_error("raise_cone: need 0 < r1 < r0 and height > 0");
  Vec3 n = outward_normal(b, g);
  HalfedgeH h = b.first(b.outer_loop(g));
  Vec3 x = (b.point(b.origin(h)) - centre).normalized(), top = centre + height * n;
  MevResult seam = must(euler::mev(b, Corner::before(h), top + r1 * x), "mev (cone seam)");
  MefResult cap = must(euler::mef(b, Corner::before(seam.y), Corner::before(seam.y)), "mef (cone top)");
  set_line(b, seam.edge);
  set_circle(b, cap.b, top, n);  // the top disc's loop is [b], counter-clockwise
  set_plane(b, cap.face, top, n);
  geo::Cone cone;
  cone.frame.origin = centre;
  cone.frame.z = n;
  cone.frame.x = x;
  cone.radius = r0;
  cone.half_angle = -std::atan2(r0 - r1, height);  // narrowing towards +z
  b.set_surface(g, cone, true);
  return cap.face;
}

VertexH raise_dome(Body& b, FaceH g, const Vec3& centre, double r, double height) {
  if (!(0 < height && height < r)) throw std::logic_error("raise_dome: need 0 < height < r");
  Vec3 n = outward_normal(b, g);
  HalfedgeH h = b.first(b.outer_loop(g));
  Vec3 p0 = b.point(b.origin(h)), pole = centre + height * n;
  // The sphere through the circle and the pole.
  double radius = (r * r + height * height) / (2 * height);
  Vec3 sc = centre + (height - radius) * n;
  MevResult seam = must(euler::mev(b, Corner::before(h), pole), "mev (dome seam)");
  set_circle(b, seam.x, sc, (p0 - sc).cross(pole - sc));  // the meridian, from the circle up
  geo::Sphere sphere;
  sphere.frame.origin = sc;
  sphere.frame.z = n;
  sphere.frame.x = (p0 - centre).normalized();
  sphere.radius = radius;
  b.set_surface(g, sphere, true);
  return seam.vertex;
}

std::vector<FaceH> raise_pyramid(Body& b, FaceH g, const Vec3& apex) {
  LoopH l = b.outer_loop(g);
  std::vector<VertexH> vs = b.loop_vertices(l);
  HalfedgeH h0 = out_in_loop(b, vs[0], l);
  MevResult s = must(euler::mev(b, Corner::before(h0), apex), "mev (apex)");
  HalfedgeH back = s.y;
  std::vector<FaceH> sides;
  for (std::size_t i = 1; i < vs.size(); ++i) {
    HalfedgeH hi = out_in_loop(b, vs[i], b.loop(back));
    MefResult m = must(euler::mef(b, Corner::before(hi), Corner::before(back)), "mef (pyramid)");
    back = m.b;
    sides.push_back(m.face);
  }
  sides.push_back(g);  // what is left of the base is the last side
  for (FaceH f : sides) fit_plane(b, f);
  refit_lines(b, {s.vertex});
  return sides;
}

FaceH cut_off(Body& b, HalfedgeH m, const std::vector<Vec3>& pts) {
  FaceH f = b.face(m);
  Corner at = Corner::before(m);
  HalfedgeH back;
  std::vector<VertexH> made{b.origin(m), b.target(m)};
  for (const Vec3& p : pts) {
    MevResult s = must(euler::mev(b, at, p), "mev (cut off)");
    back = s.y;
    at = Corner::before(back);
    made.push_back(s.vertex);
  }
  MefResult r = must(euler::mef(b, Corner::before(back), Corner::before(b.next(m))), "mef (cut off)");
  b.set_surface(r.face, b.surface(f), b.same_sense(f));
  refit_lines(b, made);
  return r.face;
}

Truncation truncate_vertex(Body& b, VertexH v, const std::function<Vec3(HalfedgeH)>& where) {
  std::vector<HalfedgeH> outs = b.outgoing(v);
  std::size_t n = outs.size();
  Truncation t;
  for (HalfedgeH o : outs) t.corners.push_back(must(euler::semv(b, o, where(o)), "semv (truncate)").vertex);
  std::vector<FaceH> tri(n);
  for (std::size_t i = 0; i < n; ++i) {
    HalfedgeH a = twin(outs[i]), c = b.next(outs[(i + 1) % n]);
    tri[i] = must(euler::mef(b, Corner::before(a), Corner::before(c)), "mef (truncate)").face;
  }
  for (std::size_t i = 1; i < n; ++i) must(euler::kef(b, outs[i]), "kef (truncate)");
  must(euler::kev(b, twin(outs[0])), "kev (truncate)");
  t.face = tri[0];
  for (HalfedgeH h : b.loop_halfedges(b.outer_loop(t.face))) set_line(b, edge_of(h));
  return t;
}

}  // namespace kintsugi::zoo
