// Every builder solid: exact counts, and the full topology check passes.
#include "invariants/topology_check.h"
#include "kernel/builders.h"

#include <gtest/gtest.h>

namespace kintsugi {
namespace {

void expect_valid(const Body& b) {
  auto v = check_topology(b);
  for (const auto& x : v) ADD_FAILURE() << to_string(x);
}

Counts counts(std::size_t v, std::size_t e, std::size_t f, std::size_t l, std::size_t s = 1, std::size_t bc = 0) {
  Counts c;
  c.vertices = v;
  c.edges = e;
  c.faces = f;
  c.loops = l;
  c.shells = s;
  c.border_cycles = bc;
  return c;
}

TEST(Builders, Box) {
  Body b = build::box(1, 2, 3);
  EXPECT_EQ(b.counts(), counts(8, 12, 6, 6));
  expect_valid(b);
}

TEST(Builders, HexagonalPrism) {
  Body b = build::prism(build::regular_polygon(6, 1.0), 2.0);
  EXPECT_EQ(b.counts(), counts(12, 18, 8, 8));
  expect_valid(b);
}

TEST(Builders, SquarePyramid) {
  Body b = build::pyramid(build::regular_polygon(4, 1.0), 1.0);
  EXPECT_EQ(b.counts(), counts(5, 8, 5, 5));
  expect_valid(b);
}

TEST(Builders, Cylinder) {
  Body b = build::cylinder(1.0, 2.0);
  EXPECT_EQ(b.counts(), counts(2, 3, 3, 3));
  expect_valid(b);
}

TEST(Builders, Cone) {
  Body b = build::cone(1.0, 2.0);
  EXPECT_EQ(b.counts(), counts(2, 2, 2, 2));
  expect_valid(b);
}

TEST(Builders, Sphere) {
  Body b = build::sphere(1.0);
  EXPECT_EQ(b.counts(), counts(2, 1, 1, 1));
  expect_valid(b);
}

TEST(Builders, TorusHasGenusOne) {
  Body b = build::torus(3.0, 1.0);
  EXPECT_EQ(b.counts(), counts(1, 2, 1, 1));
  EXPECT_EQ(b.shell_genus(b.shells().front()), 1u);
  expect_valid(b);
}

TEST(Builders, GridBox) {
  Body b = build::grid_box(600);  // k = 10
  EXPECT_EQ(b.counts().faces, 600u);
  EXPECT_EQ(b.counts().edges, 1200u);
  EXPECT_EQ(b.counts().vertices, 602u);
  expect_valid(b);
  // A true grid: every face a quad, every vertex on 3 (box corners) or 4 edges.
  for (FaceH f : b.faces()) EXPECT_EQ(b.loop_halfedges(b.outer_loop(f)).size(), 4u) << f;
  int corners = 0;
  for (VertexH v : b.vertices()) {
    EXPECT_TRUE(b.degree(v) == 3 || b.degree(v) == 4) << v << " has degree " << b.degree(v);
    corners += b.degree(v) == 3;
  }
  EXPECT_EQ(corners, 8);
}

TEST(Builders, OuterLoopsAreCounterClockwiseFromOutside) {
  // For a convex solid about its centroid, each face's Newell normal points away from it.
  Body b = build::prism(build::regular_polygon(5, 1.0), 1.0);
  geo::Vec3 c = geo::Vec3::Zero();
  for (VertexH v : b.vertices()) c += b.point(v);
  c /= double(b.counts().vertices);
  for (FaceH f : b.faces()) {
    auto vs = b.loop_vertices(b.outer_loop(f));
    geo::Vec3 n = geo::Vec3::Zero(), m = geo::Vec3::Zero();
    for (std::size_t i = 0; i < vs.size(); ++i) {
      n += b.point(vs[i]).cross(b.point(vs[(i + 1) % vs.size()]));
      m += b.point(vs[i]);
    }
    m /= double(vs.size());
    EXPECT_GT(n.dot(m - c), 0) << f;
  }
}

TEST(Builders, RejectBadParameters) {
  EXPECT_THROW(build::box(0, 1, 1), std::invalid_argument);
  EXPECT_THROW(build::box(1, -1, 1), std::invalid_argument);
  EXPECT_THROW(build::cylinder(1, std::nan("")), std::invalid_argument);
  EXPECT_THROW(build::torus(1, 2), std::invalid_argument);
  EXPECT_THROW(build::prism({{0, 0}, {1, 0}}, 1), std::invalid_argument);
  EXPECT_THROW(build::prism({{0, 0}, {0, 1}, {1, 0}}, 1), std::invalid_argument);  // clockwise
  EXPECT_THROW(build::regular_polygon(2, 1), std::invalid_argument);
}

}  // namespace
}  // namespace kintsugi
