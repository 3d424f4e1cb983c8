#include "view/tessellate.h"

#include "geometry/bit_hash.h"
#include "geometry/area.h"
#include "invariants/element_geometry.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <unordered_map>
#include <variant>

namespace kintsugi::view {

namespace {

// The largest radius of curvature the face's angular parameters sweep: the one the
// angle step must keep within the chordal tolerance.
double sweep_radius(const geo::Surface& s, const std::vector<std::vector<geo::Vec3>>& loops) {
  if (const auto* c = std::get_if<geo::Cylinder>(&s)) return std::abs(c->radius);
  if (const auto* c = std::get_if<geo::Sphere>(&s)) return std::abs(c->radius);
  if (const auto* c = std::get_if<geo::Torus>(&s)) return std::abs(c->major_radius) + std::abs(c->minor_radius);
  if (const auto* c = std::get_if<geo::Cone>(&s)) {
    // The radius is linear along the cone, so its largest value on the face is on the boundary.
    double r = std::abs(c->radius);
    const geo::Vec3 z = c->frame.z.normalized();
    for (const auto& loop : loops)
      for (const geo::Vec3& p : loop) {
        const geo::Vec3 d = p - c->frame.origin;
        r = std::max(r, (d - d.dot(z) * z).norm());
      }
    return r;
  }
  return 0.0;  // a plane: no angular parameter
}

// Exact-coordinate key: the triangulation evaluates a shared corner from the same
// parameters, so equal points are bit-identical.
struct PointKey {
  std::array<std::uint64_t, 3> bits;
  bool operator==(const PointKey&) const = default;
};
struct PointKeyHash {
  std::size_t operator()(const PointKey& k) const noexcept {
    std::uint64_t h = geo::kFnvOffsetBasis;
    for (std::uint64_t b : k.bits) h = geo::fnv_mix(h, b);
    return std::size_t(h);
  }
};
PointKey key_of(const geo::Vec3& p) {
  PointKey k;
  for (int i = 0; i < 3; ++i) {
    const double d = p[i] == 0.0 ? 0.0 : p[i];  // -0 and +0 are one point
    std::memcpy(&k.bits[std::size_t(i)], &d, sizeof d);
  }
  return k;
}

}  // namespace

// The coarsest step: an octagon. Features this coarse are a few chordal tolerances
// across, a few pixels when the whole model is in view; at 13 segments a turn (0.5 rad)
// the bosses of a 100,000-face model made the page 2.7 million triangles
// (docs/benchmarks.md).
constexpr double kMaxAngleStep = 0.8;

double angle_step(double radius, double chordal) {
  if (!(radius > 0) || !(chordal > 0)) return kMaxAngleStep;
  const double c = std::min(1.0, chordal / radius);
  return std::clamp(2 * std::acos(1 - c), 0.01, kMaxAngleStep);
}

double default_chordal(const Body& b) {
  const double size = model_size(b);
  return size > 0 ? 1e-3 * size : 1e-3;
}

FaceMesh tessellate_face(const Body& b, FaceH f, double chordal) {
  FaceMesh out;
  out.face = f;
  const geo::Surface& s = b.surface(f);
  if (std::holds_alternative<std::monostate>(s)) {
    out.problem = "the face has no surface";
    return out;
  }
  const auto loops = face_boundary(b, f, chordal);
  geo::AreaOptions o;
  o.reversed = !b.same_sense(f);
  // With two angular parameters (sphere, torus) a piece spans the step in both, so its
  // diagonal spans √2 × step, whose sagitta is twice that of one side: halve the budget.
  const bool two_angles = std::holds_alternative<geo::Sphere>(s) || std::holds_alternative<geo::Torus>(s);
  o.max_angle_step = angle_step(sweep_radius(s, loops), two_angles ? chordal / 2 : chordal);
  geo::RegionMeasure m = geo::measure_region(s, loops, o);
  if (!m.ok()) {
    out.problem = m.problem;
    return out;
  }
  std::unordered_map<PointKey, std::uint32_t, PointKeyHash> index;
  std::vector<std::uint32_t> remap(m.mesh.vertices.size());
  for (std::size_t i = 0; i < m.mesh.vertices.size(); ++i) {
    auto [it, added] = index.emplace(key_of(m.mesh.vertices[i]), std::uint32_t(out.vertices.size()));
    if (added) out.vertices.push_back(m.mesh.vertices[i]);
    remap[i] = it->second;
  }
  out.triangles.reserve(m.mesh.triangles.size());
  for (const auto& t : m.mesh.triangles) {
    const std::array<std::uint32_t, 3> w = {remap[std::size_t(t[0])], remap[std::size_t(t[1])], remap[std::size_t(t[2])]};
    if (w[0] == w[1] || w[1] == w[2] || w[0] == w[2]) continue;  // collapsed at a pole or apex
    out.triangles.push_back(w);
  }
  return out;
}

BodyMesh tessellate(const Body& b, double chordal) {
  BodyMesh out;
  for (FaceH f : b.faces()) {
    out.faces.push_back(tessellate_face(b, f, chordal));
    for (const geo::Vec3& p : out.faces.back().vertices) out.bounds.add(p);
  }
  for (EdgeH e : b.edges()) {
    out.edges.push_back({e, halfedge_polyline(b, halfedge_of(e, 0), chordal)});
    for (const geo::Vec3& p : out.edges.back().points) out.bounds.add(p);
  }
  for (VertexH v : b.vertices()) out.bounds.add(b.point(v));
  return out;
}

}  // namespace kintsugi::view
