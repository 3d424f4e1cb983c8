// Helpers shared by the paper objects (paper_objects.cpp, paper_complex.cpp): elements
// found by position, blocks and pyramids raised on planar faces, compaction.
#pragma once

#include "zoo/local_ops.h"
#include "zoo/zoo.h"

namespace kintsugi::zoo {

VertexH vertex_at(const Body& b, const Vec3& p);
// The half-edge in face f of the edge between the vertices at p and q.
HalfedgeH halfedge_in(const Body& b, FaceH f, const Vec3& p, const Vec3& q);
FaceH face_facing(const Body& b, const std::vector<FaceH>& among, const Vec3& n);
FaceH face_facing(const Body& b, const Vec3& n, const Vec3& through);
// An end point of the edge between f and g: the one with the larger y for which = +1.
Vec3 vertex_point_on(const Body& b, FaceH f, FaceH g, int which);

struct Block {
  std::vector<FaceH> sides;
  FaceH top;
};
// A block [x0,x1] x [y0,y1] standing on horizontal face `on` (+z up), `height` tall.
Block add_block(Body& b, FaceH on, double x0, double y0, double x1, double y1, double height);
// A block standing on the edge between horizontal face `top` and vertical face `side`
// (normal -x), spanning [y0, y1] and reaching to x1, with its left face merged into `side`.
Block add_flush_block(Body& b, FaceH top, FaceH side, double y0, double y1, double x1, double height);
// The same along any straight edge: h is the edge's half-edge in the planar face the block
// stands on; the block covers arc lengths [s0, s1] from origin(h), reaches `depth` into
// that face and is `height` tall; its face over the edge is merged into the face across h.
// make::boss_pinch with the same h, s0, s1 and offset + w = depth is its defective twin.
Block add_flush_block(Body& b, HalfedgeH h, double s0, double s1, double depth, double height);

struct Pyramid {
  std::vector<FaceH> sides;
  VertexH apex;
};
// A square pyramid on planar face `on`, base centred at `centre` (half side `half`, axes
// x and n x x), apex `height` along the face's outward normal.
Pyramid add_pyramid(Body& b, FaceH on, const Vec3& centre, double half, double height);

void compact(ZooModel& m);
// Paper object n as a ZooModel: its body, tolerance and defects, source named, compacted.
ZooModel paper_model(int n, Body b, std::vector<KnownDefect> defects, double tol, bool clean);

ZooModel paper_object8(bool clean);
ZooModel paper_object9(bool clean);
ZooModel paper_object10(bool clean);

}  // namespace kintsugi::zoo
