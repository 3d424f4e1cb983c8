// The paper's complex test objects 8, 9 and 10 (section 6.1, Figures 29 and 30), each
// with several defects. Layout and counts: docs/paper-objects.md.
#include "kernel/builders.h"
#include "zoo/defects.h"
#include "zoo/paper_build.h"

#include <cmath>
#include <stdexcept>

namespace kintsugi::zoo {

namespace {

constexpr double kTol = 0.5;

ZooModel finish(int n, Body b, std::vector<KnownDefect> d, bool clean) {
  ZooModel m;
  m.body = std::move(b);
  m.tolerance = kTol;
  m.defects = std::move(d);
  m.source = "paper object " + std::to_string(n) + (clean ? " (clean)" : "");
  compact(m);
  return m;
}

Vec3 X(double x, double y, double z) { return Vec3(x, y, z); }

}  // namespace

// Object 8: a 40 x 30 x 4 plate; three blocks and two pyramids on top.
ZooModel paper_object8(bool clean) {
  Body b = build::box(40, 30, 4);
  b.clear_journal();
  std::vector<KnownDefect> d;
  FaceH top = face_facing(b, Vec3::UnitZ(), X(0, 0, 4)), left = face_facing(b, -Vec3::UnitX(), X(0, 0, 0));
  // Back left block, standing on the plate's left edge; defective, its left face was
  // fitted 0.25 inside the plate's left face, which pinches the plate's top face.
  if (clean) {
    add_flush_block(b, top, left, 18, 26, 8, 5);
  } else {
    HalfedgeH h = halfedge_in(b, top, X(0, 30, 4), X(0, 0, 4));
    double y = b.point(b.origin(h)).y();
    d.push_back(make::boss_pinch(b, h, std::abs(y - 26), std::abs(y - 18), 0.25, 7.75, 5));
    // An edge gap across its top right edge.
    FaceH top1 = face_facing(b, Vec3::UnitZ(), X(8, 18, 9));
    d.push_back(make::edge_gap(b, halfedge_in(b, top1, X(8, 18, 9), X(8, 26, 9)), 2.5, 5.5, 1.5, 2));
  }
  // Back middle block: a sliver face along its top front edge.
  add_block(b, top, 16, 20, 24, 27, 4);
  // Front middle block: a gap at its top left front corner.
  add_block(b, top, 16, 4, 24, 11, 4);
  // Two pyramids on the right: small face (front) and short edge (back) at the apex.
  Pyramid front = add_pyramid(b, top, X(33, 7, 4), 4, 6);
  Pyramid back = add_pyramid(b, top, X(33, 23, 4), 4, 6);
  if (!clean) {
    FaceH top2 = face_facing(b, Vec3::UnitZ(), X(16, 20, 8));
    HalfedgeH s = halfedge_in(b, top2, X(16, 20, 8), X(24, 20, 8));
    FaceH top3 = face_facing(b, Vec3::UnitZ(), X(16, 4, 8));
    (void)top3;
    d.push_back(make::chamfer(b, edge_of(s), top2, 0.2, 0.2));
    d.push_back(make::corner_gap(b, vertex_at(b, X(16, 4, 8)), 0.8));
    Rng rng(8);
    d.push_back(make::small_face(b, front.apex, 0.4 * kTol * kTol, &rng));
    d.push_back(make::apex_short_edge(b, back.apex, 0.3, rng));
    // A small round gap in the plate's top face between the pyramids.
    d.push_back(make::face_gap(b, top, X(33, 15, 4), 1.5, 0));
  }
  return finish(8, std::move(b), d, clean);
}

// Object 9: a pentagonal prism (circumradius 10, height 12) with a square pyramid on its
// top and bottom faces.
ZooModel paper_object9(bool clean) {
  std::vector<geo::Vec2> pent = build::regular_polygon(5, 10);
  Body b = build::prism(pent, 12);
  b.clear_journal();
  std::vector<KnownDefect> d;
  auto c = [&](int i, double z) { return X(pent[i].x(), pent[i].y(), z); };
  FaceH top = face_facing(b, Vec3::UnitZ(), X(0, 0, 12)), bottom = face_facing(b, -Vec3::UnitZ(), X(0, 0, 0));
  Pyramid up = add_pyramid(b, top, X(0, 0, 12), 3, 6);
  Pyramid down = add_pyramid(b, bottom, X(0, 0, 0), 3, 6);
  if (!clean) {
    Rng rng(9);
    d.push_back(make::apex_short_edge(b, up.apex, 0.3, rng));
    d.push_back(make::small_face(b, down.apex, 0.4 * kTol * kTol, &rng));
    d.push_back(make::corner_gap(b, vertex_at(b, c(2, 12)), 1.5));                          // top left corner
    d.push_back(make::chamfer(b, edge_of(halfedge_in(b, top, c(0, 12), c(1, 12))), top, 0.2, 0.2));  // top right
    d.push_back(make::edge_gap(b, halfedge_in(b, bottom, c(3, 0), c(4, 0)), 4.4, 7.4, 2.0, 3));   // bottom front
  }
  return finish(9, std::move(b), d, clean);
}

ZooModel paper_object10(bool) { throw std::invalid_argument("paper object 10 is not built yet (docs/paper-objects.md)"); }

}  // namespace kintsugi::zoo
