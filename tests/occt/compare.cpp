#include "tests/occt/compare.h"

#include "geometry/transform.h"

#include "geometry/curve.h"
#include "geometry/surface.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <unistd.h>

namespace kintsugi::test {

namespace {

using geo::Vec2;
using geo::Vec3;

Vec3 outward(const Body& b, FaceH f, const Vec2& uv) {
  Vec3 n = geo::normal(b.surface(f), uv);
  return b.same_sense(f) ? n : Vec3(-n);
}

// Parameter samples away from apexes and poles.
const Vec2 kSamples[] = {Vec2(0.1, 0.2), Vec2(1.3, -0.4), Vec2(2.9, 0.7), Vec2(-2.0, 0.05), Vec2(4.0, -0.9)};

// Whether face fb of b carries the same oriented surface as face fa of a.
bool same_face_surface(const Body& a, FaceH fa, const Body& b, FaceH fb, double tol) {
  if (a.surface(fa).index() != b.surface(fb).index()) return false;
  double scale = std::max(1.0, geo::surface_scale(a.surface(fa)));
  for (const Vec2& uv0 : kSamples) {
    Vec2 uv = uv0 * (std::holds_alternative<geo::Plane>(a.surface(fa)) ? scale : 1.0);
    Vec3 p = geo::evaluate(a.surface(fa), uv);
    geo::SurfacePoint q = geo::closest_point(b.surface(fb), p);
    if (std::abs(q.distance) > tol * std::max(1.0, p.norm())) return false;
    Vec3 nb = b.same_sense(fb) ? q.normal : Vec3(-q.normal);
    if (outward(a, fa, uv).dot(nb) < 0.99) return false;
  }
  return true;
}

// Whether every vertex on fa's loops is at a vertex on fb's loops, and the other way.
bool same_boundary_points(const Body& a, FaceH fa, const Body& b, FaceH fb, double tol) {
  auto points = [](const Body& x, FaceH f) {
    std::vector<Vec3> ps;
    for (LoopH l : x.loops_of(f)) {
      if (x.is_lone(l)) {
        ps.push_back(x.point(x.lone_vertex(l)));
        continue;
      }
      for (VertexH v : x.loop_vertices(l)) ps.push_back(x.point(v));
    }
    return ps;
  };
  auto covered = [tol](const std::vector<Vec3>& p, const std::vector<Vec3>& q) {
    for (const Vec3& x : p) {
      bool found = false;
      for (const Vec3& y : q) found = found || (x - y).norm() <= tol * std::max(1.0, x.norm());
      if (!found) return false;
    }
    return true;
  };
  std::vector<Vec3> pa = points(a, fa), pb = points(b, fb);
  return covered(pa, pb) && covered(pb, pa);
}

// The faces around v (border cycles left out).
std::set<FaceH> faces_at(const Body& x, VertexH v) {
  std::set<FaceH> fs;
  for (HalfedgeH h : x.outgoing(v)) {
    if (!x.is_border(h)) fs.insert(x.face(h));
    if (!x.is_border(twin(h))) fs.insert(x.face(twin(h)));
  }
  if (fs.empty())  // a lone vertex in a face has no half-edges
    for (FaceH f : x.faces())
      for (LoopH l : x.loops_of(f))
        if (x.is_lone(l) && x.lone_vertex(l) == v) fs.insert(f);
  return fs;
}

// Whether parameter t is within the range an edge spans on curve c (modulo the period
// on a closed curve), with a little slack.
bool within(const geo::Curve& c, const geo::ParameterRange& r, double t) {
  double lo = std::min(r.t0, r.t1), hi = std::max(r.t0, r.t1);
  double slack = 1e-6 * (hi - lo) + 1e-12;
  double period = geo::period(c);
  if (period <= 0) return t >= lo - slack && t <= hi + slack;
  double d = std::fmod(t - r.t0, period);
  if (d < 0) d += period;
  return d <= (r.t1 - r.t0) + slack || d >= period - slack;
}

std::string str(const Vec3& p) {
  std::ostringstream os;
  os << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return os.str();
}

}  // namespace

std::string compare_bodies(const Body& a, const Body& b, double tol) {
  Counts ca = a.counts(), cb = b.counts();
  if (!(ca == cb)) {
    std::ostringstream os;
    os << "counts differ: V E F L S B = " << ca.vertices << " " << ca.edges << " " << ca.faces << " " << ca.loops << " "
       << ca.shells << " " << ca.border_cycles << " vs " << cb.vertices << " " << cb.edges << " " << cb.faces << " "
       << cb.loops << " " << cb.shells << " " << cb.border_cycles;
    return os.str();
  }
  // Faces matched one to one by oriented surface and, among faces on the same surface
  // (coplanar faces of solids side by side), by their boundary's vertices.
  std::map<FaceH, FaceH> fmap;
  std::vector<std::uint8_t> taken(b.face_slots(), 0);
  for (FaceH fa : a.faces()) {
    FaceH match;
    for (FaceH fb : b.faces())
      if (!taken[fb.idx()] && same_face_surface(a, fa, b, fb, tol)) {
        if (!match.valid()) match = fb;
        if (same_boundary_points(a, fa, b, fb, tol)) {
          match = fb;
          break;
        }
      }
    if (!match.valid())
      return "face " + fa.str() + " (" + geo::surface_type_name(a.surface(fa)) + ", same_sense " +
             std::to_string(a.same_sense(fa)) + ") has no face with the same oriented surface";
    taken[match.idx()] = 1;
    fmap[fa] = match;
  }
  // Vertices matched by position and, among coincident ones (solids that touch), by
  // the faces around them.
  std::map<VertexH, VertexH> vmap;
  for (VertexH va : a.vertices()) {
    std::set<FaceH> around;
    for (FaceH f : faces_at(a, va)) around.insert(fmap[f]);
    VertexH match;
    for (VertexH vb : b.vertices())
      if ((a.point(va) - b.point(vb)).norm() <= tol * std::max(1.0, a.point(va).norm())) {
        if (!match.valid()) match = vb;
        if (faces_at(b, vb) == around) {
          match = vb;
          break;
        }
      }
    if (!match.valid()) return "vertex " + va.str() + " at " + str(a.point(va)) + " has no vertex there";
    vmap[va] = match;
  }
  // Edges: same (mapped) faces on both sides and end vertices, curve through the same points.
  auto face_or_border = [](const Body& x, HalfedgeH h) { return x.is_border(h) ? FaceH{} : x.face(h); };
  std::vector<std::uint8_t> used(b.edge_slots(), 0);
  for (EdgeH ea : a.edges()) {
    HalfedgeH h = halfedge_of(ea, 0);
    FaceH l = face_or_border(a, h), r = face_or_border(a, twin(h));
    FaceH ml = l.valid() ? fmap[l] : FaceH{}, mr = r.valid() ? fmap[r] : FaceH{};
    VertexH v0 = vmap[a.origin(h)], v1 = vmap[a.target(h)];
    geo::ParameterRange pr =
        geo::parameter_range(a.curve(ea), a.point(a.origin(h)), a.point(a.target(h)), 1e-9);
    std::vector<Vec3> pts;
    for (int i = 1; i < 6; ++i) pts.push_back(geo::evaluate(a.curve(ea), pr.t0 + (pr.t1 - pr.t0) * i / 6.0));
    bool found = false;
    for (EdgeH eb : b.edges()) {
      if (used[eb.idx()]) continue;
      for (unsigned s = 0; s < 2 && !found; ++s) {
        HalfedgeH g = halfedge_of(eb, s);
        if (face_or_border(b, g) != ml || face_or_border(b, twin(g)) != mr) continue;
        if (b.origin(g) != v0 || b.target(g) != v1) continue;
        // On b's curve and within the part of it the edge spans (not the rest of a
        // circle through the same end points).
        HalfedgeH g0 = halfedge_of(eb, 0);
        geo::ParameterRange prb =
            geo::parameter_range(b.curve(eb), b.point(b.origin(g0)), b.point(b.target(g0)), 1e-9);
        bool on = true;
        for (const Vec3& p : pts) {
          geo::CurvePoint q = geo::closest_point(b.curve(eb), p);
          if (q.distance > tol * std::max(1.0, p.norm()) || !within(b.curve(eb), prb, q.t)) on = false;
        }
        if (on) {
          found = true;
          used[eb.idx()] = 1;
        }
      }
      if (found) break;
    }
    if (!found)
      return "edge " + ea.str() + " (" + geo::curve_type_name(a.curve(ea)) + " from " + str(a.point(a.origin(h))) +
             " to " + str(a.point(a.target(h))) + ") has no edge between the same faces through the same points";
  }
  return "";
}

void transform(Body& b, const Eigen::Matrix3d& r, const Eigen::Vector3d& t) {
  // Every curve and surface type, free-form ones too (a tee's B-spline edge stayed where
  // it was while its vertices moved: the scan-parts harness made an inconsistent model).
  geo::Similarity s;
  s.rotation = r;
  s.translation = t;
  for (VertexH v : b.vertices()) b.set_point(v, s.point(b.point(v)));
  for (EdgeH e : b.edges()) b.set_curve(e, geo::transformed(b.curve(e), s));
  for (FaceH f : b.faces()) b.set_surface(f, geo::transformed(b.surface(f), s), b.same_sense(f));
  b.clear_journal();
}

std::string temp_path(const std::string& name) {
  static std::string dir = [] {
    auto d = std::filesystem::temp_directory_path() / ("kintsugi_occt_tests_" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d.string();
  }();
  return dir + "/" + name;
}

std::string temp_file(const std::string& name, const std::string& text) {
  std::string p = temp_path(name);
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

Body round_trip(const Body& b, io::CadFormat f, const std::string& name) {
  std::string path = temp_path(name + (f == io::CadFormat::step ? ".step" : f == io::CadFormat::iges ? ".iges" : ".brep"));
  std::string err;
  if (!io::export_cad(b, path, f, &err)) {
    ADD_FAILURE() << "export failed: " << err;
    return Body{};
  }
  std::optional<io::CadImport> in = io::import_cad(path, f, &err);
  if (!in) {
    ADD_FAILURE() << "import failed: " << err;
    return Body{};
  }
  return std::move(in->body);
}

}  // namespace kintsugi::test
