// The paper's test objects 1..10 (section 6.1, Figures 26-30) and the models they should
// become. Sizes, tolerances and the reconciled face/edge counts: docs/paper-objects.md.
#include "kernel/builders.h"
#include "zoo/defects.h"
#include "zoo/paper_build.h"

#include <cmath>
#include <stdexcept>

namespace kintsugi::zoo {

using geo::Vec2;

// ---- finding elements by position ---------------------------------------------------

VertexH vertex_at(const Body& b, const Vec3& p) {
  for (VertexH v : b.vertices())
    if ((b.point(v) - p).norm() < 1e-9) return v;
  throw std::logic_error("no vertex at the expected place");
}

HalfedgeH halfedge_in(const Body& b, FaceH f, const Vec3& p, const Vec3& q) {
  VertexH a = vertex_at(b, p), c = vertex_at(b, q);
  for (HalfedgeH h : b.outgoing(a))
    if (b.target(h) == c) return b.face(h) == f ? h : twin(h);
  throw std::logic_error("no edge between the expected places");
}

FaceH face_facing(const Body& b, const std::vector<FaceH>& among, const Vec3& n) {
  for (FaceH f : among)
    if (plane_of(b, f) && outward_normal(b, f).dot(n.normalized()) > 1 - 1e-9) return f;
  throw std::logic_error("no face with the expected normal");
}

FaceH face_facing(const Body& b, const Vec3& n, const Vec3& through) {
  for (FaceH f : b.faces()) {
    const geo::Plane* p = plane_of(b, f);
    if (p && outward_normal(b, f).dot(n.normalized()) > 1 - 1e-9 && std::abs(p->frame.z.dot(through - p->frame.origin)) < 1e-9)
      return f;
  }
  throw std::logic_error("no face with the expected plane");
}

std::vector<Vec3> rectangle(double x0, double y0, double x1, double y1, double z, bool up = true) {
  std::vector<Vec3> r = {{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}};
  if (!up) std::reverse(r.begin(), r.end());
  return r;
}

Block add_block(Body& b, FaceH on, double x0, double y0, double x1, double y1, double height) {
  double z = plane_of(b, on)->frame.origin.z();
  FaceH g = add_ring_face(b, on, rectangle(x0, y0, x1, y1, z));
  Block k;
  k.sides = extrude(b, g, Vec3(0, 0, height));
  k.top = g;
  return k;
}

Block add_flush_block(Body& b, FaceH top, FaceH side, double y0, double y1, double x1, double height) {
  // The block stands on the edge x = x_edge of `top`, its left face in the plane of `side`.
  double x = plane_of(b, side)->frame.origin.x();
  HalfedgeH h = halfedge_in(b, top, vertex_point_on(b, top, side, +1), vertex_point_on(b, top, side, -1));
  double y = b.point(b.origin(h)).y();
  double s0 = std::abs(y0 - y), s1 = std::abs(y1 - y);
  if (s0 > s1) std::swap(s0, s1);
  return add_flush_block(b, h, s0, s1, x1 - x, height);
}

Block add_flush_block(Body& b, HalfedgeH h, double s0, double s1, double depth, double height) {
  FaceH top = b.face(h);
  Vec3 p = b.point(b.origin(h)), d = (b.point(b.target(h)) - p).normalized();
  SemvResult sa = must(euler::semv(b, h, p + s0 * d), "semv");
  must(euler::semv(b, sa.next, p + s1 * d), "semv");
  HalfedgeH mid = sa.next;
  Vec3 u = outward_normal(b, top).cross(d);
  Vec3 a = p + s0 * d, c = p + s1 * d;
  FaceH r = cut_off(b, mid, {a + depth * u, c + depth * u});
  Block k;
  k.sides = extrude(b, r, outward_normal(b, top) * height);
  k.top = r;
  // The block's face over `mid` lies in the plane of the face across h: one face with it.
  must(euler::kef(b, twin(mid)), "kef (flush)");
  std::vector<FaceH> alive;
  for (FaceH f : k.sides)
    if (b.alive(f)) alive.push_back(f);
  k.sides = alive;
  return k;
}

Vec3 vertex_point_on(const Body& b, FaceH f, FaceH g, int which) {
  // The end points of the edge between f and g, the one with larger y first (which=+1).
  for (HalfedgeH h : b.loop_halfedges(b.outer_loop(f)))
    if (b.face(twin(h)) == g) {
      Vec3 p = b.point(b.origin(h)), q = b.point(b.target(h));
      if ((p.y() < q.y()) == (which > 0)) std::swap(p, q);
      return p;
    }
  throw std::logic_error("faces do not meet");
}

Pyramid add_pyramid(Body& b, FaceH on, const Vec3& centre, double half, double height) {
  Vec3 n = outward_normal(b, on), x = Vec3::UnitX(), y = n.cross(x);
  std::vector<Vec3> pts = {centre - half * x - half * y, centre + half * x - half * y, centre + half * x + half * y,
                           centre - half * x + half * y};
  FaceH g = add_ring_face(b, on, pts);
  Pyramid p;
  p.sides = raise_pyramid(b, g, centre + height * n);
  p.apex = vertex_at(b, centre + height * n);
  return p;
}

// Renumbers the body's handles densely and the recorded defects with them.
void compact(ZooModel& m) {
  Body::Renumbering r = m.body.compact();
  for (KnownDefect& d : m.defects)
    for (std::string& s : d.elements) {
      std::uint32_t i = std::uint32_t(std::stoul(s.substr(1)));
      const std::vector<std::uint32_t>* map = s[0] == 'v' ? &r.vertex : s[0] == 'e' ? &r.edge : s[0] == 'f' ? &r.face : &r.loop;
      if (i >= map->size() || (*map)[i] == Handle<VertexTag>::kInvalid)
        throw std::logic_error("defect element " + s + " was killed while building");
      s = s.substr(0, 1) + std::to_string((*map)[i]);
    }
  m.body.clear_journal();
}

ZooModel paper_model(int n, Body b, std::vector<KnownDefect> defects, double tol, bool clean) {
  ZooModel m;
  m.body = std::move(b);
  m.tolerance = tol;
  m.defects = std::move(defects);
  m.source = "paper object " + std::to_string(n) + (clean ? " (clean)" : "");
  compact(m);
  return m;
}

namespace {

constexpr double kCube = 10, kTol = 0.5;


Body cube() { return build::box(kCube, kCube, kCube); }
Vec3 X(double x, double y, double z) { return Vec3(x, y, z); }

ZooModel object1(bool clean) {
  Body b = cube();
  std::vector<KnownDefect> d;
  if (!clean) d.push_back(make::face_gap(b, face_facing(b, Vec3::UnitZ(), X(0, 0, kCube)), X(5, 5, kCube), 2.5, 4));
  return paper_model(1, std::move(b), d, kTol, clean);
}

ZooModel object2(bool clean) {
  Body b = cube();
  std::vector<KnownDefect> d;
  if (!clean) d.push_back(make::corner_gap(b, vertex_at(b, X(kCube, 0, kCube)), 1.5));
  return paper_model(2, std::move(b), d, kTol, clean);
}

ZooModel object3(bool clean) {
  Body b = cube();
  std::vector<KnownDefect> d;
  if (!clean) {
    FaceH top = face_facing(b, Vec3::UnitZ(), X(0, 0, kCube));
    HalfedgeH h = halfedge_in(b, top, X(kCube, 0, kCube), X(kCube, kCube, kCube));
    d.push_back(make::edge_gap(b, h, 3.5, 6.5, 2.0, 2));
  }
  return paper_model(3, std::move(b), d, kTol, clean);
}

ZooModel object4(bool clean) {
  Body b = cube();
  std::vector<KnownDefect> d;
  if (!clean) {
    FaceH top = face_facing(b, Vec3::UnitZ(), X(0, 0, kCube));
    EdgeH e = edge_of(halfedge_in(b, top, X(0, 0, kCube), X(0, kCube, kCube)));
    d.push_back(make::chamfer(b, e, top, 0.2, 0.25));
  }
  return paper_model(4, std::move(b), d, kTol, clean);
}

// Object 5: a 10 x 10 x 5 block with a 4-wide block on top standing on its left edge;
// defective, the upper block's left face was fitted 0.3 inside the lower block's.
ZooModel object5(bool clean) {
  Body b = build::box(kCube, kCube, 5);
  std::vector<KnownDefect> d;
  FaceH top = face_facing(b, Vec3::UnitZ(), X(0, 0, 5)), left = face_facing(b, -Vec3::UnitX(), X(0, 0, 0));
  if (clean) {
    add_flush_block(b, top, left, 3, 7, 4, 3);
  } else {
    HalfedgeH h = halfedge_in(b, top, X(0, 0, 5), X(0, kCube, 5));
    double s0 = std::abs(b.point(b.origin(h)).y() - 3), s1 = std::abs(b.point(b.origin(h)).y() - 7);
    d.push_back(make::boss_pinch(b, h, std::min(s0, s1), std::max(s0, s1), 0.3, 3.7, 3));
  }
  return paper_model(5, std::move(b), d, kTol, clean);
}

Body square_pyramid() { return build::pyramid({Vec2(0, 0), Vec2(kCube, 0), Vec2(kCube, kCube), Vec2(0, kCube)}, 8); }

ZooModel object6(bool clean) {
  Body b = square_pyramid();
  std::vector<KnownDefect> d;
  if (!clean) {
    Rng rng(6);
    d.push_back(make::small_face(b, vertex_at(b, X(5, 5, 8)), 0.4 * kTol * kTol, &rng));
  }
  return paper_model(6, std::move(b), d, kTol, clean);
}

ZooModel object7(bool clean) {
  Body b = square_pyramid();
  std::vector<KnownDefect> d;
  if (!clean) {
    Rng rng(7);
    d.push_back(make::apex_short_edge(b, vertex_at(b, X(5, 5, 8)), 0.3, rng));
  }
  return paper_model(7, std::move(b), d, kTol, clean);
}

}  // namespace

ZooModel paper_object(int n, bool clean) {
  switch (n) {
    case 1: return object1(clean);
    case 2: return object2(clean);
    case 3: return object3(clean);
    case 4: return object4(clean);
    case 5: return object5(clean);
    case 6: return object6(clean);
    case 7: return object7(clean);
    case 8: return paper_object8(clean);
    case 9: return paper_object9(clean);
    case 10: return paper_object10(clean);
  }
  throw std::invalid_argument("paper objects are numbered 1 to 10, got " + std::to_string(n));
}

}  // namespace kintsugi::zoo
