#include "kernel/builders.h"

#include "geometry/polygon.h"
#include "kernel/euler.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace kintsugi::build {

namespace {

using geo::Vec2;
using geo::Vec3;

// Builders only issue operators whose preconditions hold by construction; a refusal
// here is a kernel bug, so it is loud.
template <class T>
T must(Result<T> r, const char* what) {
  if (!r) throw std::logic_error(std::string("builder step ") + what + " failed: " + r.error().message);
  return r.value();
}

void need_positive(double v, const char* name) {
  if (!(v > 0) || !std::isfinite(v)) throw std::invalid_argument(std::string(name) + " must be a positive number");
}

double signed_area(const std::vector<Vec2>& p) {
  double a = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec2 &u = p[i], &w = p[(i + 1) % p.size()];
    a += u.x() * w.y() - w.x() * u.y();
  }
  return a / 2;
}

void need_polygon(const std::vector<Vec2>& p) {
  if (p.size() < 3) throw std::invalid_argument("polygon needs at least 3 points");
  for (const Vec2& q : p)
    if (!q.allFinite()) throw std::invalid_argument("polygon has a point that is not finite");
  if (!(signed_area(p) > 0)) throw std::invalid_argument("polygon must be counter-clockwise with positive area");
}

// The half-edge leaving v that lies in loop l (vertex degrees are small here).
HalfedgeH out_in_loop(const Body& b, VertexH v, LoopH l) {
  HalfedgeH start = b.out(v), h = start;
  do {
    if (b.loop(h) == l) return h;
    h = b.next(twin(h));
  } while (h != start);
  throw std::logic_error("vertex " + v.str() + " is not on loop " + l.str());
}

// A two-faced lamina over `pts`: returns the face whose loop visits pts in order
// (counter-clockwise seen from +z when pts are), and the vertices.
struct Lamina {
  FaceH forward, backward;
  std::vector<VertexH> v;
};

Lamina lamina(Body& b, const std::vector<Vec3>& pts) {
  Lamina out;
  MvfsResult m = must(euler::mvfs(b, pts[0]), "mvfs");
  out.forward = m.face;
  out.v.push_back(m.vertex);
  MevResult e = must(euler::mev(b, Corner::in_lone(m.loop), pts[1]), "mev");
  out.v.push_back(e.vertex);
  HalfedgeH back = e.y;   // leaves the newest vertex, back along the chain
  HalfedgeH first = e.x;  // leaves pts[0]
  for (std::size_t i = 2; i < pts.size(); ++i) {
    e = must(euler::mev(b, Corner::before(back), pts[i]), "mev");
    out.v.push_back(e.vertex);
    back = e.y;
  }
  MefResult f = must(euler::mef(b, Corner::before(back), Corner::before(first)), "mef");
  out.backward = f.face;
  return out;
}

// Sweeps face f along d: new vertices at v + d, one side face per edge; f moves to the
// far end. f's loop must be counter-clockwise seen from the side d points to.
void sweep(Body& b, FaceH f, const Vec3& d) {
  LoopH l = b.outer_loop(f);
  std::vector<HalfedgeH> hs = b.loop_halfedges(l);
  std::size_t n = hs.size();
  std::vector<HalfedgeH> leave(n);  // the half-edge of l leaving each new vertex
  for (std::size_t i = 0; i < n; ++i) {
    MevResult e = must(euler::mev(b, Corner::before(hs[i]), b.point(b.origin(hs[i])) + d), "mev");
    leave[i] = e.y;
  }
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t j = (i + 1) % n;
    MefResult m = must(euler::mef(b, Corner::before(leave[i]), Corner::before(leave[j])), "mef");
    leave[i] = m.a;
  }
}

std::vector<Vec3> lift(const std::vector<Vec2>& p, double z = 0) {
  std::vector<Vec3> out;
  for (const Vec2& q : p) out.emplace_back(q.x(), q.y(), z);
  return out;
}

geo::Frame frame(const Vec3& o, const Vec3& z, const Vec3& x) {
  geo::Frame f;
  f.origin = o;
  f.z = z.normalized();
  f.x = (x - x.dot(f.z) * f.z).normalized();
  return f;
}

}  // namespace

std::vector<Vec2> regular_polygon(int n, double r) {
  if (n < 3) throw std::invalid_argument("a polygon needs at least 3 sides");
  need_positive(r, "radius");
  std::vector<Vec2> p;
  for (int i = 0; i < n; ++i) {
    double t = 2 * M_PI * i / n;
    p.emplace_back(r * std::cos(t), r * std::sin(t));
  }
  return p;
}

void assign_planar_geometry(Body& b) {
  for (FaceH f : b.faces()) {
    std::vector<VertexH> vs = b.loop_vertices(b.outer_loop(f));
    std::vector<Vec3> pts;
    Vec3 c = Vec3::Zero();
    for (VertexH v : vs) {
      pts.push_back(b.point(v));
      c += b.point(v);
    }
    c /= double(vs.size());
    Vec3 n = geo::polygon_normal(pts);
    Vec3 x = b.point(vs[1 % vs.size()]) - b.point(vs[0]);
    if (x.cross(n).norm() < 1e-12 * (1 + x.norm())) x = n.unitOrthogonal();
    b.set_surface(f, geo::Plane{frame(c, n, x)}, true);
  }
  for (EdgeH e : b.edges()) {
    HalfedgeH h = halfedge_of(e, 0);
    Vec3 o = b.point(b.origin(h)), d = b.point(b.target(h)) - o;
    b.set_curve(e, geo::Line{o, d.normalized()});
  }
}

Body prism(const std::vector<Vec2>& polygon, double height) {
  need_polygon(polygon);
  need_positive(height, "height");
  Body b;
  Lamina lam = lamina(b, lift(polygon));
  sweep(b, lam.forward, Vec3(0, 0, height));
  assign_planar_geometry(b);
  b.clear_journal();
  return b;
}

Body box(double sx, double sy, double sz) {
  need_positive(sx, "size x");
  need_positive(sy, "size y");
  need_positive(sz, "size z");
  return prism({Vec2(0, 0), Vec2(sx, 0), Vec2(sx, sy), Vec2(0, sy)}, sz);
}

Body pyramid(const std::vector<Vec2>& polygon, double height) {
  need_polygon(polygon);
  need_positive(height, "height");
  Body b;
  Lamina lam = lamina(b, lift(polygon));
  Vec3 apex = Vec3::Zero();
  for (VertexH v : lam.v) apex += b.point(v);
  apex /= double(lam.v.size());
  apex.z() = height;
  // The forward face's loop: h_0 .. h_{n-1}, h_i leaving v_i. A strut to the apex from
  // v_0, then one triangle cut off per remaining base edge.
  LoopH l = b.outer_loop(lam.forward);
  HalfedgeH h0 = out_in_loop(b, lam.v[0], l);
  MevResult s = must(euler::mev(b, Corner::before(h0), apex), "mev");
  HalfedgeH back = s.y;  // apex → v_0 at first; then apex → v_i
  for (std::size_t i = 1; i < lam.v.size(); ++i) {
    HalfedgeH hi = out_in_loop(b, lam.v[i], b.loop(back));
    MefResult m = must(euler::mef(b, Corner::before(hi), Corner::before(back)), "mef");
    back = m.b;
  }
  assign_planar_geometry(b);
  b.clear_journal();
  return b;
}

Body cylinder(double radius, double height) {
  need_positive(radius, "radius");
  need_positive(height, "height");
  Body b;
  MvfsResult m = must(euler::mvfs(b, Vec3(radius, 0, height)), "mvfs");
  // Top circle: a (counter-clockwise from above) bounds the top disc.
  MefResult top = must(euler::mef(b, Corner::in_lone(m.loop), Corner::in_lone(m.loop)), "mef");
  MevResult seam = must(euler::mev(b, Corner::before(top.b), Vec3(radius, 0, 0)), "mev");
  // Bottom circle, counter-clockwise from above in the side face; its twin bounds the bottom disc.
  MefResult bot = must(euler::mef(b, Corner::before(seam.y), Corner::before(seam.y)), "mef");
  b.set_curve(top.edge, geo::Circle{frame(Vec3(0, 0, height), Vec3::UnitZ(), Vec3::UnitX()), radius});
  b.set_curve(bot.edge, geo::Circle{frame(Vec3::Zero(), Vec3::UnitZ(), Vec3::UnitX()), radius});
  b.set_curve(seam.edge, geo::Line{Vec3(radius, 0, height), -Vec3::UnitZ()});
  b.set_surface(m.face, geo::Plane{frame(Vec3(0, 0, height), Vec3::UnitZ(), Vec3::UnitX())});
  b.set_surface(bot.face, geo::Plane{frame(Vec3::Zero(), -Vec3::UnitZ(), Vec3::UnitX())});
  b.set_surface(top.face, geo::Cylinder{frame(Vec3::Zero(), Vec3::UnitZ(), Vec3::UnitX()), radius});
  b.clear_journal();
  return b;
}

Body cone(double radius, double height) {
  need_positive(radius, "radius");
  need_positive(height, "height");
  Body b;
  MvfsResult m = must(euler::mvfs(b, Vec3(0, 0, height)), "mvfs");
  MevResult seam = must(euler::mev(b, Corner::in_lone(m.loop), Vec3(radius, 0, 0)), "mev");
  MefResult bot = must(euler::mef(b, Corner::before(seam.y), Corner::before(seam.y)), "mef");
  b.set_curve(bot.edge, geo::Circle{frame(Vec3::Zero(), Vec3::UnitZ(), Vec3::UnitX()), radius});
  Vec3 d = Vec3(radius, 0, 0) - Vec3(0, 0, height);
  b.set_curve(seam.edge, geo::Line{Vec3(0, 0, height), d.normalized()});
  b.set_surface(bot.face, geo::Plane{frame(Vec3::Zero(), -Vec3::UnitZ(), Vec3::UnitX())});
  // Radius `radius` at z = 0, narrowing towards +z: negative half-angle.
  b.set_surface(m.face, geo::Cone{frame(Vec3::Zero(), Vec3::UnitZ(), Vec3::UnitX()), radius,
                                  -std::atan2(radius, height)});
  b.clear_journal();
  return b;
}

Body sphere(double radius) {
  need_positive(radius, "radius");
  Body b;
  MvfsResult m = must(euler::mvfs(b, Vec3(0, 0, radius)), "mvfs");
  MevResult seam = must(euler::mev(b, Corner::in_lone(m.loop), Vec3(0, 0, -radius)), "mev");
  // The seam is the meridian through -x (the circle's frame: z = -y, x = +z, so its
  // second axis is z × x = -x), from the north pole down.
  b.set_curve(seam.edge, geo::Circle{frame(Vec3::Zero(), -Vec3::UnitY(), Vec3::UnitZ()), radius});
  b.set_surface(m.face, geo::Sphere{frame(Vec3::Zero(), Vec3::UnitZ(), Vec3::UnitX()), radius});
  b.clear_journal();
  return b;
}

Body torus(double major_radius, double minor_radius) {
  need_positive(major_radius, "major radius");
  need_positive(minor_radius, "minor radius");
  if (!(minor_radius < major_radius)) throw std::invalid_argument("minor radius must be less than the major radius");
  Body b;
  MvfsResult m = must(euler::mvfs(b, Vec3(major_radius + minor_radius, 0, 0)), "mvfs");
  MefResult outer = must(euler::mef(b, Corner::in_lone(m.loop), Corner::in_lone(m.loop)), "mef");
  must(euler::kfmrh(b, m.face, outer.face), "kfmrh");
  // Loop a, c, b, c': the boundary of the (θ, φ) square, counter-clockwise.
  MekrResult minor = must(euler::mekr(b, Corner::before(outer.a), Corner::before(outer.b)), "mekr");
  b.set_curve(outer.edge, geo::Circle{frame(Vec3::Zero(), Vec3::UnitZ(), Vec3::UnitX()), major_radius + minor_radius});
  b.set_curve(minor.edge, geo::Circle{frame(Vec3(major_radius, 0, 0), -Vec3::UnitY(), Vec3::UnitX()), minor_radius});
  b.set_surface(m.face, geo::Torus{frame(Vec3::Zero(), Vec3::UnitZ(), Vec3::UnitX()), major_radius, minor_radius});
  b.clear_journal();
  return b;
}

Body grid_box(std::size_t faces, double size) {
  need_positive(size, "size");
  if (faces < 6) faces = 6;
  std::size_t k = std::max<std::size_t>(1, std::size_t(std::llround(std::sqrt(double(faces) / 6.0))));
  Body b;
  b.set_journaling(false);  // a bulk build that will never be rolled back
  Body base = box(size, size, size);
  b = std::move(base);
  b.set_journaling(false);
  if (k > 1) {
    // The box's own corners: after the first sides are cut, points along the edges have
    // degree 3 too, so corners are recognised by identity, not by degree.
    std::vector<std::uint8_t> corner(b.vertex_slots(), 0);
    for (VertexH v : b.vertices()) corner[v.idx()] = 1;
    // Split every edge into k pieces.
    for (EdgeH e : b.edges()) {
      HalfedgeH h = halfedge_of(e, 0);
      Vec3 p = b.point(b.origin(h)), q = b.point(b.target(h));
      for (std::size_t i = 1; i < k; ++i) {
        SemvResult s = must(euler::semv(b, h, p + (q - p) * (double(i) / double(k))), "semv");
        h = s.next;
      }
    }
    for (FaceH f : std::vector<FaceH>(b.faces())) {
      // The face's boundary: 4k vertices, starting at one of the box's corners.
      std::vector<VertexH> ring = b.loop_vertices(b.outer_loop(f));
      std::size_t c0 = 0;
      while (!(ring[c0].idx() < corner.size() && corner[ring[c0].idx()])) ++c0;
      std::rotate(ring.begin(), ring.begin() + long(c0), ring.end());
      // Sides (counter-clockwise): bottom ring[0..k], right ring[k..2k], top ring[2k..3k], left ring[3k..4k].
      auto at = [&](std::size_t i) { return ring[i % (4 * k)]; };
      std::vector<std::vector<VertexH>> rows(k + 1);
      for (std::size_t i = 0; i <= k; ++i) rows[0].push_back(at(i));
      for (std::size_t i = 0; i <= k; ++i) rows[k].push_back(at(3 * k - i));
      std::vector<FaceH> strips;
      LoopH l = b.outer_loop(f);
      for (std::size_t j = 1; j < k; ++j) {
        VertexH left = at(4 * k - j), right = at(k + j);
        MefResult m = must(euler::mef(b, Corner::before(out_in_loop(b, left, l)), Corner::before(out_in_loop(b, right, l))), "mef");
        strips.push_back(m.face);  // the strip below this cut
        rows[j].push_back(left);
        HalfedgeH h = m.a;  // left → right
        Vec3 p = b.point(left), q = b.point(right);
        for (std::size_t i = 1; i < k; ++i) {
          SemvResult s = must(euler::semv(b, h, p + (q - p) * (double(i) / double(k))), "semv");
          rows[j].push_back(s.vertex);
          h = s.next;
        }
        rows[j].push_back(right);
      }
      strips.push_back(f);  // the top strip
      for (std::size_t j = 0; j < k; ++j) {
        LoopH sl = b.outer_loop(strips[j]);
        for (std::size_t i = k - 1; i >= 1; --i) {
          must(euler::mef(b, Corner::before(out_in_loop(b, rows[j][i], sl)), Corner::before(out_in_loop(b, rows[j + 1][i], sl))), "mef");
        }
      }
    }
    assign_planar_geometry(b);
  }
  b.set_journaling(true);
  b.clear_journal();
  return b;
}

}  // namespace kintsugi::build
