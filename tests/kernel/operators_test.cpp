// Each Euler operator: the legal case with its exact change in counts and its inverse,
// and every precondition failure, which must leave the body exactly as it was.
#include "invariants/topology_check.h"
#include "kernel/builders.h"
#include "kernel/euler.h"
#include "kernel/transaction.h"

#include <gtest/gtest.h>

namespace kintsugi {
namespace {

using geo::Vec3;

void expect_valid(const Body& b) {
  for (const auto& v : check_topology(b)) ADD_FAILURE() << to_string(v);
}

// Runs `op` expecting refusal with `code`, and checks nothing changed.
template <class F>
void expect_refused(Body& b, ErrorCode code, F op) {
  Body before = b.clone();
  std::size_t journal = b.journal().size();
  auto r = op();
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, code) << error_code_name(r.error().code) << ": " << r.error().message;
  EXPECT_FALSE(r.error().message.empty());
  std::string why;
  EXPECT_TRUE(b.equals(before, &why)) << why;
  EXPECT_EQ(b.journal().size(), journal);
}

struct Delta {
  long v, e, f, l, s, bc;
};
void expect_delta(const Counts& a, const Counts& b, Delta d) {
  EXPECT_EQ(long(b.vertices) - long(a.vertices), d.v);
  EXPECT_EQ(long(b.edges) - long(a.edges), d.e);
  EXPECT_EQ(long(b.faces) - long(a.faces), d.f);
  EXPECT_EQ(long(b.loops) - long(a.loops), d.l);
  EXPECT_EQ(long(b.shells) - long(a.shells), d.s);
  EXPECT_EQ(long(b.border_cycles) - long(a.border_cycles), d.bc);
}

// Top face of the unit box (normal +z).
FaceH top_face(const Body& b) {
  for (FaceH f : b.faces()) {
    bool top = true;
    for (VertexH v : b.loop_vertices(b.outer_loop(f))) top = top && b.point(v).z() > 0.5;
    if (top) return f;
  }
  return FaceH{};
}

TEST(Mvfs, MakesAShellWithALoneVertexAndKvfsUndoesIt) {
  Body b;
  auto r = euler::mvfs(b, Vec3(1, 2, 3));
  ASSERT_TRUE(r);
  expect_delta(Counts{}, b.counts(), {1, 0, 1, 1, 1, 0});
  EXPECT_TRUE(b.is_lone(r->loop));
  EXPECT_EQ(b.point(r->vertex), Vec3(1, 2, 3));
  expect_valid(b);
  ASSERT_TRUE(euler::kvfs(b, r->face));
  EXPECT_EQ(b.counts(), Counts{});
}

TEST(Kvfs, Refusals) {
  Body b = build::box();
  expect_refused(b, ErrorCode::dead_handle, [&] { return euler::kvfs(b, FaceH(99)); });
  expect_refused(b, ErrorCode::dead_handle, [&] { return euler::kvfs(b, FaceH{}); });
  expect_refused(b, ErrorCode::not_lone, [&] { return euler::kvfs(b, b.faces().front()); });
}

TEST(Mev, LoneStrutAndSplit) {
  Body b;
  auto m = *euler::mvfs(b, Vec3(0, 0, 0));
  Counts c0 = b.counts();
  auto e1 = euler::mev(b, Corner::in_lone(m.loop), Vec3(1, 0, 0));
  ASSERT_TRUE(e1);
  expect_delta(c0, b.counts(), {1, 1, 0, 0, 0, 0});
  EXPECT_EQ(b.origin(e1->x), m.vertex);
  EXPECT_EQ(b.target(e1->x), e1->vertex);
  expect_valid(b);
  // Strut from the new vertex.
  auto e2 = euler::mev(b, Corner::before(e1->y), Vec3(2, 0, 0));
  ASSERT_TRUE(e2);
  EXPECT_EQ(b.degree(e1->vertex), 2u);
  expect_valid(b);
  // Split the middle vertex: its two edges go to different vertices.
  Body before = b.clone();
  HalfedgeH h1 = e2->x, h2 = e1->y;  // both leave e1->vertex
  auto s = euler::mev_split(b, h1, h2, Vec3(1.5, 0, 0));
  ASSERT_TRUE(s) << s.error().message;
  EXPECT_EQ(b.origin(h1), s->vertex);
  EXPECT_EQ(b.origin(h2), e1->vertex);
  expect_valid(b);
  ASSERT_TRUE(euler::kev(b, s->x));
  std::string why;
  EXPECT_TRUE(b.equals(before, &why)) << why;
}

TEST(Mev, Refusals) {
  Body b = build::box();
  HalfedgeH h = b.halfedges().front();
  expect_refused(b, ErrorCode::dead_handle, [&] { return euler::mev(b, Corner::before(HalfedgeH(1000)), Vec3::Zero()); });
  expect_refused(b, ErrorCode::not_lone, [&] { return euler::mev(b, Corner::in_lone(b.loop(h)), Vec3::Zero()); });
  // h2 leaving another vertex.
  expect_refused(b, ErrorCode::wrong_vertex, [&] { return euler::mev_split(b, h, b.next(h), Vec3::Zero()); });
  // A strut into a border cycle.
  ASSERT_TRUE(euler::kfmb(b, top_face(b)));
  LoopH border = b.border_cycles().front();
  expect_refused(b, ErrorCode::border, [&] { return euler::mev(b, Corner::before(b.first(border)), Vec3::Zero()); });
}

TEST(Kev, CollapsesAnEdgeAndMevRestoresIt) {
  Body b = build::box();
  Body before = b.clone();
  HalfedgeH h = b.halfedges()[4];
  Counts c0 = b.counts();
  Transaction tx(b);
  ASSERT_TRUE(euler::kev(b, h));
  expect_delta(c0, b.counts(), {-1, -1, 0, 0, 0, 0});
  expect_valid(b);
  // The journaled inverse (mev reviving the killed slots) brings back exactly what was killed.
  tx.rollback();
  std::string why;
  EXPECT_TRUE(b.equals(before, &why)) << why;
}

TEST(Kev, Refusals) {
  Body b = build::cylinder(1, 1);
  // Circles are self-loops.
  for (EdgeH e : b.edges()) {
    HalfedgeH h = halfedge_of(e, 0);
    if (b.origin(h) == b.target(h)) {
      expect_refused(b, ErrorCode::self_loop, [&] { return euler::kev(b, h); });
      break;
    }
  }
  Body c;
  auto m = *euler::mvfs(c, Vec3::Zero());
  auto e1 = *euler::mev(c, Corner::in_lone(m.loop), Vec3(1, 0, 0));
  auto e2 = *euler::mev(c, Corner::before(e1.y), Vec3(2, 0, 0));
  (void)e2;
  // m.vertex dangles at the start of e1->x: kev(x) would have to keep the dangling end.
  expect_refused(c, ErrorCode::degree, [&] { return euler::kev(c, e1.x); });
  expect_refused(c, ErrorCode::dead_handle, [&] { return euler::kev(c, HalfedgeH{}); });
}

TEST(Mef, SplitsAFaceAndKefMergesItBack) {
  Body b = build::box();
  Body before = b.clone();
  FaceH f = top_face(b);
  auto hs = b.loop_halfedges(b.outer_loop(f));
  Counts c0 = b.counts();
  auto r = euler::mef(b, Corner::before(hs[0]), Corner::before(hs[2]));
  ASSERT_TRUE(r);
  expect_delta(c0, b.counts(), {0, 1, 1, 1, 0, 0});
  EXPECT_EQ(b.loop_halfedges(b.outer_loop(f)).size(), 3u);
  EXPECT_EQ(b.loop_halfedges(r->loop).size(), 3u);
  EXPECT_EQ(b.origin(r->a), b.origin(hs[0]));
  expect_valid(b);
  ASSERT_TRUE(euler::kef(b, r->a));
  std::string why;
  EXPECT_TRUE(b.equals(before, &why)) << why;
}

TEST(Mef, EmptyRangeMakesASelfLoopFace) {
  Body b = build::box();
  FaceH f = top_face(b);
  HalfedgeH h = b.first(b.outer_loop(f));
  auto r = euler::mef(b, Corner::before(h), Corner::before(h));
  ASSERT_TRUE(r);
  EXPECT_EQ(b.loop_halfedges(r->loop).size(), 1u);
  EXPECT_EQ(b.origin(r->b), b.target(r->b));
  expect_valid(b);
}

TEST(Mef, InABorderCycleFillsPartOfTheGap) {
  Body b = build::box();
  ASSERT_TRUE(euler::kfmb(b, top_face(b)));
  LoopH border = b.border_cycles().front();
  auto hs = b.loop_halfedges(border);
  auto r = euler::mef(b, Corner::before(hs[0]), Corner::before(hs[2]));
  ASSERT_TRUE(r);
  EXPECT_TRUE(b.is_border(border));
  EXPECT_FALSE(b.is_border(r->loop));
  EXPECT_EQ(b.counts().border_cycles, 1u);
  expect_valid(b);
}

TEST(Mef, Refusals) {
  Body b = build::box();
  FaceH f = top_face(b);
  HalfedgeH in_top = b.first(b.outer_loop(f));
  HalfedgeH elsewhere = twin(in_top);
  expect_refused(b, ErrorCode::wrong_loop, [&] { return euler::mef(b, Corner::before(in_top), Corner::before(elsewhere)); });
  expect_refused(b, ErrorCode::dead_handle, [&] { return euler::mef(b, Corner::before(HalfedgeH(77)), Corner::before(in_top)); });
  expect_refused(b, ErrorCode::not_lone, [&] { return euler::mef(b, Corner::in_lone(b.outer_loop(f)), Corner::in_lone(b.outer_loop(f))); });
}

TEST(Kef, Refusals) {
  Body b = build::box();
  // An edge with both sides in one loop (a strut): kemr's job.
  FaceH f = top_face(b);
  auto s = *euler::mev(b, Corner::before(b.first(b.outer_loop(f))), Vec3(0.5, 0.5, 1));
  expect_refused(b, ErrorCode::wrong_loop, [&] { return euler::kef(b, s.x); });
  // A ring: kef merges outer loops only.
  ASSERT_TRUE(euler::kemr(b, s.x));
  Body t = build::torus(3, 1);
  HalfedgeH th = t.halfedges().front();
  expect_refused(t, ErrorCode::wrong_loop, [&] { return euler::kef(t, th); });
  // A side face between two gaps cannot be absorbed into one of them: its edge on the
  // other gap would have no face.
  Body c = build::box();
  FaceH top = top_face(c);
  FaceH side = c.face(twin(c.first(c.outer_loop(top))));
  FaceH bottom;
  for (FaceH g : c.faces())
    if (g != top && c.loop_halfedges(c.outer_loop(g)).size() == 4 && c.point(c.loop_vertices(c.outer_loop(g))[0]).z() < 0.5 &&
        c.point(c.loop_vertices(c.outer_loop(g))[1]).z() < 0.5 && c.point(c.loop_vertices(c.outer_loop(g))[2]).z() < 0.5)
      bottom = g;
  ASSERT_TRUE(euler::kfmb(c, top));
  ASSERT_TRUE(euler::kfmb(c, bottom));
  for (HalfedgeH h : c.loop_halfedges(c.outer_loop(side)))
    if (c.is_border(twin(h))) {
      expect_refused(c, ErrorCode::border, [&] { return euler::kef(c, twin(h)); });
      break;
    }
  // The seam of a cylinder's side face: kfmb would leave it with no face.
  Body cy = build::cylinder(1, 1);
  for (FaceH g : cy.faces())
    if (std::holds_alternative<geo::Cylinder>(cy.surface(g)))
      expect_refused(cy, ErrorCode::border, [&] { return euler::kfmb(cy, g); });
}

TEST(Kemr, MakesARingAndMekrJoinsItBack) {
  Body b = build::box();
  FaceH f = top_face(b);
  // A strut, then kemr on it leaves a lone-vertex ring.
  auto s = *euler::mev(b, Corner::before(b.first(b.outer_loop(f))), Vec3(0.5, 0.5, 1));
  Body before = b.clone();
  Counts c0 = b.counts();
  auto r = euler::kemr(b, s.x);
  ASSERT_TRUE(r) << r.error().message;
  expect_delta(c0, b.counts(), {0, -1, 0, 1, 0, 0});
  EXPECT_TRUE(b.is_lone(r->ring));
  EXPECT_EQ(b.lone_vertex(r->ring), s.vertex);
  EXPECT_EQ(b.rings_of(f).size(), 1u);
  expect_valid(b);
  auto k = euler::mekr(b, Corner::before(b.first(b.outer_loop(f))), Corner::in_lone(r->ring));
  ASSERT_TRUE(k) << k.error().message;
  expect_valid(b);
  EXPECT_EQ(b.counts(), c0);
}

TEST(Kemr, Refusals) {
  Body b = build::box();
  HalfedgeH h = b.halfedges().front();
  expect_refused(b, ErrorCode::wrong_loop, [&] { return euler::kemr(b, h); });
  expect_refused(b, ErrorCode::dead_handle, [&] { return euler::kemr(b, HalfedgeH(500)); });
}

TEST(Mekr, Refusals) {
  Body b = build::box();
  FaceH f = top_face(b);
  FaceH g = b.face(twin(b.first(b.outer_loop(f))));
  expect_refused(b, ErrorCode::wrong_loop, [&] {
    return euler::mekr(b, Corner::before(b.first(b.outer_loop(f))), Corner::before(b.first(b.outer_loop(f))));
  });
  expect_refused(b, ErrorCode::wrong_face, [&] {
    return euler::mekr(b, Corner::before(b.first(b.outer_loop(f))), Corner::before(b.first(b.outer_loop(g))));
  });
}

TEST(Kfmrh, MakesAThroughHoleAndMfkrhClosesIt) {
  Body b = build::box();
  FaceH top = top_face(b);
  // Cut an inner square in the top face: strut, kemr → lone ring, grow the ring into a square face.
  auto s = *euler::mev(b, Corner::before(b.first(b.outer_loop(top))), Vec3(0.3, 0.3, 1));
  auto ring = *euler::kemr(b, s.x);
  auto e1 = *euler::mev(b, Corner::in_lone(ring.ring), Vec3(0.6, 0.3, 1));
  auto e2 = *euler::mev(b, Corner::before(e1.y), Vec3(0.6, 0.6, 1));
  auto e3 = *euler::mev(b, Corner::before(e2.y), Vec3(0.3, 0.6, 1));
  auto inner = *euler::mef(b, Corner::before(e3.y), Corner::before(e1.x));
  expect_valid(b);
  Counts c0 = b.counts();
  ShellH sh = b.shell(top);
  ASSERT_TRUE(euler::kfmrh(b, top, inner.face));
  expect_delta(c0, b.counts(), {0, 0, -1, 0, 0, 0});
  EXPECT_EQ(b.shell_genus(sh), 1u);
  expect_valid(b);
  auto m = euler::mfkrh(b, inner.loop);
  ASSERT_TRUE(m);
  EXPECT_EQ(b.shell_genus(sh), 0u);
  expect_valid(b);
}

TEST(Kfmrh, Refusals) {
  Body b = build::box();
  FaceH f = b.faces()[0];
  expect_refused(b, ErrorCode::wrong_face, [&] { return euler::kfmrh(b, f, f); });
  Body two = build::box();
  auto m = *euler::mvfs(two, Vec3(5, 5, 5));
  expect_refused(two, ErrorCode::different_shell, [&] { return euler::kfmrh(two, two.faces()[0], m.face); });
  expect_refused(b, ErrorCode::outer_loop, [&] { return euler::mfkrh(b, b.outer_loop(f)); });
  // A ring in a genus-0 shell: nothing to close.
  Body g = build::box();
  FaceH gf = g.faces()[0];
  auto s = *euler::mev(g, Corner::before(g.first(g.outer_loop(gf))), Vec3(0.5, 0.5, 0.5));
  auto r = *euler::kemr(g, s.x);
  expect_refused(g, ErrorCode::genus, [&] { return euler::mfkrh(g, r.ring); });
}

TEST(Mfkrh, RefusesARingThatIsNotAroundAHole) {
  // A torus has genus 1, but a lone ring made by kemr does not go around its hole.
  Body t = build::torus(3, 1);
  FaceH f = t.faces()[0];
  auto s = *euler::mev(t, Corner::before(t.first(t.outer_loop(f))), Vec3(4, 0, 0.5));
  auto r = *euler::kemr(t, s.x);
  expect_refused(t, ErrorCode::disconnects, [&] { return euler::mfkrh(t, r.ring); });
}

TEST(Kfmb, OpensAGapAndMfkbClosesIt) {
  Body b = build::box();
  Body before = b.clone();
  Counts c0 = b.counts();
  auto r = euler::kfmb(b, top_face(b));
  ASSERT_TRUE(r);
  expect_delta(c0, b.counts(), {0, 0, -1, -1, 0, 1});
  EXPECT_TRUE(b.is_border(r->border));
  expect_valid(b);
  auto m = euler::mfkb(b, r->border);
  ASSERT_TRUE(m);
  EXPECT_EQ(b.counts(), c0);
  expect_valid(b);
}

TEST(Kfmb, Refusals) {
  Body b = build::box();
  FaceH top = top_face(b);
  FaceH side = b.face(twin(b.first(b.outer_loop(top))));
  ASSERT_TRUE(euler::kfmb(b, top));
  // The side face shares an edge with the gap: its edge would have no face.
  expect_refused(b, ErrorCode::border, [&] { return euler::kfmb(b, side); });
  expect_refused(b, ErrorCode::border, [&] { return euler::mfkb(b, b.outer_loop(side)); });
  Body s = build::sphere(1);
  expect_refused(s, ErrorCode::last_face, [&] { return euler::kfmb(s, s.faces()[0]); });
}

TEST(Semv, SplitsAnEdgeAndJekvJoinsIt) {
  Body b = build::box();
  Body before = b.clone();
  HalfedgeH h = b.halfedges()[3];
  Counts c0 = b.counts();
  auto r = euler::semv(b, h, Vec3(9, 9, 9));
  ASSERT_TRUE(r);
  expect_delta(c0, b.counts(), {1, 1, 0, 0, 0, 0});
  EXPECT_EQ(b.target(h), r->vertex);
  EXPECT_EQ(b.next(h), r->next);
  EXPECT_EQ(b.curve(r->edge), b.curve(edge_of(h)));
  expect_valid(b);
  ASSERT_TRUE(euler::jekv(b, h));
  std::string why;
  EXPECT_TRUE(b.equals(before, &why)) << why;
}

TEST(Semv, SplitsASelfLoop) {
  Body b = build::cylinder(1, 1);
  for (EdgeH e : b.edges()) {
    HalfedgeH h = halfedge_of(e, 0);
    if (b.origin(h) != b.target(h)) continue;
    auto r = euler::semv(b, h, Vec3(-1, 0, 0));
    ASSERT_TRUE(r);
    expect_valid(b);
    ASSERT_TRUE(euler::jekv(b, h));
    expect_valid(b);
    break;
  }
}

TEST(Jekv, Refusals) {
  Body b = build::box();
  HalfedgeH h = b.halfedges()[0];
  expect_refused(b, ErrorCode::degree, [&] { return euler::jekv(b, h); });  // box vertices have degree 3
  Body c = build::cylinder(1, 1);
  for (EdgeH e : c.edges()) {
    HalfedgeH k = halfedge_of(e, 0);
    if (c.origin(k) == c.target(k) && c.next(k) == k) {
      expect_refused(c, ErrorCode::self_loop, [&] { return euler::jekv(c, k); });
      break;
    }
  }
}

}  // namespace
}  // namespace kintsugi
