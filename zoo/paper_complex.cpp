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
  return paper_model(8, std::move(b), d, kTol, clean);
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
  return paper_model(9, std::move(b), d, kTol, clean);
}

// Object 10 (Figure 30, not reproduced in our copy): a 40 x 30 x 5 plate with two blocks
// standing flush on its left and front edges, a conical boss (1) on the left block and
// a spherical boss (10) on the front one. Its defects, numbered as in the paper: the
// blocks fitted 0.25 inside the plate's faces pinch the plate's top face twice (2, 9), a
// chain of small faces at a bottom corner (3), an edge gap across the top back edge (4),
// a corner gap (5) and a small face (11) at the two ends of a sliver (8) along the front
// block's top right edge, a small face at another bottom corner (6) and a face gap in
// the right face (7). docs/paper-objects.md says why the counts differ from Table 2.
ZooModel paper_object10(bool clean) {
  Body b = build::box(40, 30, 5);
  b.clear_journal();
  std::vector<KnownDefect> d;
  FaceH top = face_facing(b, Vec3::UnitZ(), X(0, 0, 5));
  // Left block: y in [10, 22], x up to 12, 6 tall, on the top face's left edge (which
  // runs from (0, 30) to (0, 0)): arc lengths 8..20.
  HalfedgeH left = halfedge_in(b, top, X(0, 30, 5), X(0, 0, 5));
  if (clean)
    add_flush_block(b, left, 8, 20, 12, 6);
  else
    d.push_back(make::boss_pinch(b, left, 8, 20, 0.25, 11.75, 6));  // 2
  // Front block: x in [24, 36], y up to 10, 6 tall, on the front edge ((0, 0) to (40, 0)).
  HalfedgeH front = halfedge_in(b, top, X(0, 0, 5), X(40, 0, 5));
  KnownDefect pinch9;
  if (clean)
    add_flush_block(b, front, 24, 36, 10, 6);
  else
    pinch9 = make::boss_pinch(b, front, 24, 36, 0.25, 9.75, 6);
  // The bosses, on the blocks' tops (found by a corner each block has in both versions).
  FaceH top_left = face_facing(b, faces_around(b, vertex_at(b, X(12, 22, 11))), Vec3::UnitZ());
  FaceH top_front = face_facing(b, faces_around(b, vertex_at(b, X(36, 10, 11))), Vec3::UnitZ());
  raise_cone(b, add_circle_face(b, top_left, X(6, 16, 11), 3.5), X(6, 16, 11), 3.5, 1.5, 4);
  raise_dome(b, add_circle_face(b, top_front, X(30, 5, 11), 3.5), X(30, 5, 11), 3.5, 2.5);
  if (!clean) {
    Rng rng(10);
    d.push_back(make::small_face_chain(b, vertex_at(b, X(40, 30, 0)), 0.3, rng));                      // 3
    FaceH plate_top = face_facing(b, Vec3::UnitZ(), X(0, 0, 5));
    d.push_back(make::edge_gap(b, halfedge_in(b, plate_top, X(40, 30, 5), X(0, 30, 5)), 14, 18, 1.5, 2));  // 4
    // The sliver (8) along the front block's top right edge, then a corner gap (5) at its
    // front end and a small face (11) at its back end, both on the block's top.
    KnownDefect sliver = make::chamfer(b, edge_of(halfedge_in(b, top_front, X(36, 0.25, 11), X(36, 10, 11))),
                                       top_front, 0.3, 0.3);
    d.push_back(make::corner_gap(b, vertex_at(b, X(35.7, 0.25, 11)), 0.05));                         // 5
    d.push_back(make::small_face(b, vertex_at(b, X(40, 0, 0)), 0.4 * kTol * kTol, nullptr));           // 6
    FaceH right = face_facing(b, Vec3::UnitX(), X(40, 0, 0));
    d.push_back(make::face_gap(b, right, X(40, 15, 2.5), 1.5, 5));                                   // 7
    d.push_back(sliver);                                                                             // 8
    d.push_back(pinch9);                                                                             // 9
    d.push_back(make::small_face(b, vertex_at(b, X(35.7, 10, 11)), 0.004, nullptr));                 // 11
  }
  return paper_model(10, std::move(b), d, kTol, clean);
}


}  // namespace kintsugi::zoo
