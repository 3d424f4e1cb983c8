#include "invariants/loop_index.h"

#include "invariants/element_geometry.h"

#include <algorithm>
#include <cmath>

namespace kintsugi {

namespace {

// A loop over more cells than this is kept in the `big` list instead.
constexpr double kMaxCells = 4096;
// Cell coordinates are packed in 21 bits each, relative to the face's box.
constexpr std::int64_t kCoordMask = (1 << 21) - 1;

std::uint64_t key(std::int64_t i, std::int64_t j, std::int64_t k) {
  return (std::uint64_t(i & kCoordMask) << 42) | (std::uint64_t(j & kCoordMask) << 21) | std::uint64_t(k & kCoordMask);
}

bool meets(const geo::Box& a, const geo::Box& c) { return !a.empty() && !c.empty() && geo::box_gap(a, c) == 0.0; }

}  // namespace

geo::Box loop_box(const Body& b, LoopH l, double chordal) {
  geo::Box box;
  if (b.is_lone(l)) {
    box.add(b.point(b.lone_vertex(l)));
    return box;
  }
  for (HalfedgeH h : b.loop_halfedges(l)) {
    geo::Box hb = halfedge_box(b, h, chordal);
    box.add(hb.min);
    box.add(hb.max);
  }
  return box;
}

bool has_more_loops_than(const Body& b, FaceH f, std::size_t n) {
  std::size_t k = 0;
  for (LoopH l = b.outer_loop(f); l.valid(); l = b.next_in_face(l))
    if (++k > n) return true;
  return false;
}

std::set<LoopH> loops_through(const Body& b, FaceH f, const std::set<VertexH>& vertices, const std::set<EdgeH>& edges) {
  std::set<LoopH> out;
  for_each_changed_side(
      b, f, vertices, edges, [&](HalfedgeH h) { out.insert(b.loop(h)); },
      [&](VertexH v) {  // a lone vertex: its loop, when it is one of f's
        for (LoopH l = b.outer_loop(f); l.valid(); l = b.next_in_face(l))
          if (b.is_lone(l) && b.lone_vertex(l) == v) out.insert(l);
      });
  return out;
}

void LoopBoxIndex::record(FaceGrid& g, LoopH l, const geo::Box& box) {
  g.boxes[l] = box;
  if (box.empty()) return;
  const geo::Vec3 lo = ((box.min - g.origin) / g.cell).array().floor(), hi = ((box.max - g.origin) / g.cell).array().floor();
  const double cells = (hi.x() - lo.x() + 1) * (hi.y() - lo.y() + 1) * (hi.z() - lo.z() + 1);
  if (!(cells <= kMaxCells)) {
    g.big.push_back(l);
    return;
  }
  for (auto i = std::int64_t(lo.x()); i <= std::int64_t(hi.x()); ++i)
    for (auto j = std::int64_t(lo.y()); j <= std::int64_t(hi.y()); ++j)
      for (auto k = std::int64_t(lo.z()); k <= std::int64_t(hi.z()); ++k) g.cells[key(i, j, k)].push_back(l);
}

void LoopBoxIndex::committed(const Body& b, FaceH f, const std::set<VertexH>& vertices, const std::set<EdgeH>& edges,
                             double chordal) {
  if (!b.alive(f)) {
    faces_.erase(f);
    return;
  }
  auto it = faces_.find(f);
  if (it != faces_.end()) {
    for (LoopH l : loops_through(b, f, vertices, edges)) record(it->second, l, loop_box(b, l, chordal));
    return;
  }
  // New to the index: every loop as it is now. The cell: the median loop's largest
  // extent, so that a loop covers a few cells and a cell holds a few loops.
  FaceGrid g;
  std::vector<std::pair<LoopH, geo::Box>> all;
  geo::Box face;
  std::vector<double> extents;
  for (LoopH l : b.loops_of(f)) {
    geo::Box box = loop_box(b, l, chordal);
    all.push_back({l, box});
    if (box.empty()) continue;
    face.add(box.min);
    face.add(box.max);
    if (!b.is_outer(l)) extents.push_back((box.max - box.min).maxCoeff());
  }
  if (face.empty()) return;
  double cell = 0.0;
  if (!extents.empty()) {
    std::nth_element(extents.begin(), extents.begin() + extents.size() / 2, extents.end());
    cell = extents[extents.size() / 2];
  }
  // At most 2^20 cells along the face's box: the packed coordinates stay distinct.
  cell = std::max({cell, face.diagonal() * std::ldexp(1.0, -20), 1e-300});
  g.origin = face.min - geo::Vec3::Constant(cell);
  g.cell = cell;
  for (const auto& [l, box] : all) record(g, l, box);
  faces_.emplace(f, std::move(g));
}

std::vector<LoopH> LoopBoxIndex::near(const Body& b, FaceH f, const geo::Box& box, const std::set<VertexH>& vertices,
                                      const std::set<EdgeH>& edges, double chordal) const {
  const FaceGrid& g = faces_.at(f);
  std::set<LoopH> found;
  const std::set<LoopH> changed = loops_through(b, f, vertices, edges);
  for (LoopH l : changed)
    if (meets(loop_box(b, l, chordal), box)) found.insert(l);
  auto consider = [&](LoopH l) {
    if (changed.count(l) || found.count(l) || !b.alive(l) || b.is_border(l) || b.face(l) != f) return;
    auto it = g.boxes.find(l);
    if (it != g.boxes.end() && meets(it->second, box)) found.insert(l);
  };
  if (!box.empty()) {
    const geo::Vec3 lo = ((box.min - g.origin) / g.cell).array().floor(), hi = ((box.max - g.origin) / g.cell).array().floor();
    const double cells = (hi.x() - lo.x() + 1) * (hi.y() - lo.y() + 1) * (hi.z() - lo.z() + 1);
    if (cells <= double(g.cells.size())) {
      for (auto i = std::int64_t(lo.x()); i <= std::int64_t(hi.x()); ++i)
        for (auto j = std::int64_t(lo.y()); j <= std::int64_t(hi.y()); ++j)
          for (auto k = std::int64_t(lo.z()); k <= std::int64_t(hi.z()); ++k)
            if (auto c = g.cells.find(key(i, j, k)); c != g.cells.end())
              for (LoopH l : c->second) consider(l);
    } else {
      for (const auto& [l, recorded] : g.boxes) consider(l);
    }
    for (LoopH l : g.big) consider(l);
  }
  std::vector<LoopH> out;
  const LoopH outer = b.outer_loop(f);
  out.push_back(outer);
  for (LoopH l : found)
    if (l != outer) out.push_back(l);
  return out;
}

}  // namespace kintsugi
