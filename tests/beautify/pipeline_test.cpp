// The pass registry and the pipeline's bookkeeping: passes in the paper's order, Table 1
// read from spec/table1.json, and a report whose "left" list is exactly what detect()
// finds on the output (the local re-detection misses nothing and invents nothing).
#include "invariants/topology_check.h"
#include "kernel/builders.h"
#include "kernel/euler.h"
#include "kernel/transaction.h"
#include "invariants/element_geometry.h"
#include "invariants/region_validity.h"
#include "repair/beautify.h"
#include "repair/detect.h"
#include "repair/detect_threads.h"
#include "io/native_json.h"
#include "repair/pass.h"
#include "tests/support/left_mismatch.h"
#include "zoo/zoo.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <fstream>

namespace kintsugi {
namespace {

geo::Tolerances tol_for(const Body& b, double t) { return geo::Tolerances::for_model(t, model_size(b)); }

using test::left_mismatch;

TEST(PassRegistry, PassesAreInThePapersOrderOncePerType) {
  const auto& ps = passes();
  ASSERT_FALSE(ps.empty());
  for (std::size_t i = 1; i < ps.size(); ++i) EXPECT_LT(problem_order(ps[i - 1]->type), problem_order(ps[i]->type));
  for (const Pass* p : ps) {
    EXPECT_EQ(find_pass(p->type), p);
    EXPECT_NE(p->repair, nullptr) << problem_name(p->type);
    EXPECT_GT(std::string(p->title).size(), 0u);
    EXPECT_GT(std::string(p->summary).size(), 0u);
  }
}

TEST(PassRegistry, MayCreateIsTable1FromSpec) {
  std::ifstream in(std::string(KINTSUGI_SPEC_DIR) + "/table1.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  for (ProblemType t : kAllProblemTypes) {
    std::vector<std::string> want, got;
    for (const auto& x : j["can_cause"][problem_name(t)]) want.push_back(x.get<std::string>());
    for (ProblemType x : may_create(t)) {
      got.push_back(problem_name(x));
      EXPECT_GT(problem_order(x), problem_order(t)) << problem_name(t) << " may create " << problem_name(x);
    }
    EXPECT_EQ(got, want) << problem_name(t);
  }
}

TEST(Pipeline, LeftIsWhatDetectFindsOnPaperObjects) {
  for (int n = 1; n <= 10; ++n) {
    zoo::ZooModel m = zoo::paper_object(n, false);
    geo::Tolerances tol = tol_for(m.body, m.tolerance);
    BeautifyReport r = beautify(m.body, tol);
    EXPECT_EQ(left_mismatch(m.body, tol, r), "") << "object " << n;
    std::array<int, 11> counts{};
    for (const Problem& p : r.left) counts[std::size_t(problem_order(p.type) - 1)]++;
    EXPECT_EQ(counts, r.problems_after) << "object " << n;
  }
}

// A cylinder whose side is two half-cylinders on one surface: the top and bottom circles
// are each cut at the seam's vertex and at the opposite point, where a second vertical
// edge splits the side.
Body two_half_cylinders() {
  Body b = build::cylinder(1, 2);
  FaceH side;
  for (FaceH f : b.faces())
    if (std::holds_alternative<geo::Cylinder>(b.surface(f))) side = f;
  std::vector<VertexH> opposite;
  for (EdgeH e : b.edges()) {
    const auto* c = std::get_if<geo::Circle>(&b.curve(e));
    if (!c) continue;
    HalfedgeH h = halfedge_of(e, 0);
    const geo::Vec3 across = 2 * c->frame.origin - b.point(b.origin(h));
    auto r = euler::semv(b, h, across);
    if (!r) throw std::runtime_error("semv: " + r.error().message);
    opposite.push_back(r->vertex);
  }
  if (opposite.size() != 2) throw std::runtime_error("expected two circles");
  VertexH low = b.point(opposite[0]).z() < b.point(opposite[1]).z() ? opposite[0] : opposite[1];
  VertexH high = low == opposite[0] ? opposite[1] : opposite[0];
  HalfedgeH h1, h2;
  for (HalfedgeH h : b.loop_halfedges(b.outer_loop(side))) {
    if (b.origin(h) == low) h1 = h;
    if (b.origin(h) == high) h2 = h;
  }
  auto m = euler::mef(b, Corner::before(h1), Corner::before(h2));
  if (!m) throw std::runtime_error("mef: " + m.error().message);
  b.set_surface(m->face, b.surface(side), b.same_sense(side));
  const geo::Vec3 p = b.point(b.origin(m->a)), q = b.point(b.target(m->a));
  b.set_curve(m->edge, geo::Line{p, (q - p).normalized()});
  return b;
}

// The same with both vertical edges gone (kef, then kemr: a side bounded by two circles,
// no seam), each circle left with two vertices on two arcs: four mergeable vertices. Pass
// 8 made this body from the two halves until it kept one of the two edges as the side's
// seam. Neither circle closes in the side's parameter domain (OpenCASCADE: the wires are
// not closed), and every repair that leaves a side so is refused: the model stays as it is.
Body seamless_side_with_cut_circles() {
  Body b = two_half_cylinders();
  std::vector<EdgeH> between;
  for (EdgeH e : b.edges())
    if (std::holds_alternative<geo::Line>(b.curve(e))) between.push_back(e);
  if (between.size() != 2) throw std::runtime_error("expected two vertical edges");
  HalfedgeH first = halfedge_of(between[0], 0);
  if (!b.is_outer(b.loop(twin(first)))) first = twin(first);
  if (auto k = euler::kef(b, first); !k) throw std::runtime_error("kef: " + k.error().message);
  if (auto k = euler::kemr(b, halfedge_of(between[1], 0)); !k) throw std::runtime_error("kemr: " + k.error().message);
  return b;
}

TEST(Pipeline, ASideWithoutItsSeamIsLeftAsItIs) {
  Body b = seamless_side_with_cut_circles();
  ASSERT_TRUE(check_topology(b).empty());
  const geo::Tolerances tol = tol_for(b, 0.02);
  ASSERT_EQ(detect(b, tol).count(ProblemType::mergeable_edges), 4);
  const Body before = b.clone();
  BeautifyReport r = beautify(b, tol);
  for (const RepairEntry& e : r.problems) {
    EXPECT_FALSE(e.repaired()) << problem_name(e.problem.type) << ": " << e.reason;
    if (e.outcome == Outcome::refused) {
      EXPECT_NE(e.reason.find("loop_without_seam"), std::string::npos) << e.reason;
    }
  }
  std::string why;
  EXPECT_TRUE(b.equals(before, &why)) << why;
}

// A box with two faces each fitted twice (`kintsugi generate box`, then `kintsugi inject
// --type same_geometry_faces --tol 0.05` with seeds 4 and 13): merging the faces leaves
// their split edges' vertices mergeable, and pass 10's merge at one of them takes an edge
// another problem was anchored on. That problem was removed by the earlier repair and must
// be reported so, not as "not repaired".
TEST(Pipeline, AProblemRemovedByAnEarlierRepairIsReportedResolved) {
  std::string error;
  auto doc = io::read_native_file(std::string(KINTSUGI_TEST_DATA_DIR) + "/native/box_two_faces_fitted_twice.json", &error);
  ASSERT_TRUE(doc) << error;
  Body b = std::move(doc->body);
  const geo::Tolerances tol = tol_for(b, 0.05);
  BeautifyReport r = beautify(b, tol);
  int resolved = 0;
  std::string all;
  for (const RepairEntry& e : r.problems) {
    all += std::string(problem_name(e.problem.type)) + " " + outcome_name(e.outcome) + " " + e.reason + "\n";
    resolved += e.outcome == Outcome::resolved_earlier;
    EXPECT_FALSE(e.left()) << problem_name(e.problem.type) << ": " << e.reason;
  }
  EXPECT_GE(resolved, 1) << all;
  EXPECT_TRUE(r.left.empty()) << all;
  EXPECT_TRUE(check_topology(b).empty());
  EXPECT_EQ(b.counts().faces, 6u) << all;
}

// A random zoo model for the properties below: a base solid with one to four defects of
// any type at tolerance t; *what says which defects were made.
Body random_zoo_model(double t, std::string* what) {
  Body b;
  switch (*rc::gen::inRange(0, 6)) {
    case 0: b = build::box(1, 1, 1); break;
    case 1: b = build::prism(build::regular_polygon(6, 1), 1); break;
    case 2: b = build::pyramid(build::regular_polygon(4, 1), 1); break;
    case 3: b = build::cylinder(1, 2); break;
    case 4: b = build::grid_box(24); break;
    default: b = build::prism(build::regular_polygon(5, 1), 2); break;
  }
  const int n = *rc::gen::inRange(1, 5);
  for (int i = 0; i < n; ++i) {
    ProblemType type = *rc::gen::elementOf(std::vector<ProblemType>(kAllProblemTypes.begin(), kAllProblemTypes.end()));
    std::string err;
    if (auto inj = zoo::inject(b, type, *rc::gen::arbitrary<std::uint32_t>(), std::nullopt, t, &err))
      *what += std::string(problem_name(type)) + ": " + inj->description + "\n";
  }
  return b;
}

RC_GTEST_PROP(Pipeline, LeftIsWhatDetectFindsOnRandomZooModels, ()) {
  const double t = *rc::gen::element(0.01, 0.02, 0.05);
  std::string what;
  Body b = random_zoo_model(t, &what);
  geo::Tolerances tol = tol_for(b, t);
  BeautifyReport r = beautify(b, tol);
  const std::string bad = left_mismatch(b, tol, r);
  if (!bad.empty()) RC_FAIL(what + bad);
}

// Between passes the queues are kept current by detecting near what repairs touched
// (spec/problems.md, "Detecting near a repair"): each time, they must hold exactly what a
// whole-body detection finds, whatever the repairs did. The end-of-run comparison
// (LeftIsWhatDetectFinds) sees only the last state; this sees every one.
std::string stale_queues(Body& b, const geo::Tolerances& tol) {
  std::string bad;
  int step = 0;
  BeautifyOptions o;
  o.check_topology_each_repair = false;
  o.after_refresh = [&](const Body& body, const std::vector<Problem>& known) {
    ++step;
    if (!bad.empty()) return;
    const auto want = test::identities(detect(body, tol).problems), got = test::identities(known);
    if (want == got) return;
    bad = "after refresh " + std::to_string(step) + ", detect() finds:\n";
    for (const auto& x : want) bad += "  " + x + "\n";
    bad += "the queues hold:\n";
    for (const auto& x : got) bad += "  " + x + "\n";
  };
  beautify(b, tol, o);
  return bad;
}

TEST(Pipeline, TheQueuesAreWhatDetectFindsAfterEveryRefreshOnPaperObjects) {
  for (int n = 1; n <= 10; ++n) {
    zoo::ZooModel m = zoo::paper_object(n, false);
    EXPECT_EQ(stale_queues(m.body, tol_for(m.body, m.tolerance)), "") << "paper object " << n;
  }
}

RC_GTEST_PROP(Pipeline, TheQueuesAreWhatDetectFindsAfterEveryRefreshOnRandomZooModels, ()) {
  const double t = *rc::gen::element(0.01, 0.02, 0.05);
  std::string what;
  Body b = random_zoo_model(t, &what);
  const std::string bad = stale_queues(b, tol_for(b, t));
  if (!bad.empty()) RC_FAIL(what + bad);
}

// The same on families with defects of any type put on the plate, a face with more loops
// than kManyLoops: detection near a repair there takes the plate's loops near the change
// only (spec/problems.md, "A face with many loops").
RC_GTEST_PROP(Pipeline, TheQueuesAreWhatDetectFindsAfterEveryRefreshWithDefectsOnThePlate, ()) {
  zoo::ZooModel m = zoo::family(*rc::gen::inRange(150, 700), *rc::gen::element(0.0, 0.05), *rc::gen::inRange(1, 1000));
  Body& b = m.body;
  FaceH plate;
  std::size_t most = 0;
  for (FaceH f : b.faces())
    if (std::size_t k = b.loops_of(f).size(); k > most) most = k, plate = f;
  RC_PRE(most > kManyLoops);
  std::string what;
  const int n = *rc::gen::inRange(1, 7);
  for (int i = 0; i < n; ++i) {
    ProblemType type = *rc::gen::elementOf(std::vector<ProblemType>(kAllProblemTypes.begin(), kAllProblemTypes.end()));
    std::string err;
    if (auto inj = zoo::inject(b, type, *rc::gen::arbitrary<std::uint32_t>(), plate.str(), m.tolerance, &err))
      what += std::string(problem_name(type)) + ": " + inj->description + "\n";
  }
  const std::string bad = stale_queues(b, tol_for(b, m.tolerance));
  if (!bad.empty()) RC_FAIL(what + bad);
}

// The first full detection measures on several threads (repair/detect_threads.h): one
// thread and two give the same report and the same output bytes. Families above the
// size where threads start (512 faces).
TEST(Pipeline, OneAndTwoThreadsGiveTheSameBytes) {
  for (std::uint64_t seed : {3u, 8u}) {
    const zoo::ZooModel m = zoo::family(3000, 0.1, seed);
    const geo::Tolerances tol = tol_for(m.body, m.tolerance);
    std::string out[2], report[2];
    for (int k = 0; k < 2; ++k) {
      set_detect_threads(k + 1);
      Body b = m.body.clone();
      BeautifyOptions o;
      o.check_topology_each_repair = false;
      const BeautifyReport r = beautify(b, tol, o);
      out[k] = io::write_native(b);
      for (const RepairEntry& e : r.problems) {
        report[k] += std::string(problem_name(e.problem.type)) + " " + outcome_name(e.outcome) + " " + e.reason + " |";
        for (const std::string& op : e.operators) report[k] += " " + op;
        report[k] += "\n";
      }
    }
    set_detect_threads(0);
    EXPECT_FALSE(report[0].empty()) << "seed " << seed;
    EXPECT_EQ(report[0], report[1]) << "seed " << seed;
    EXPECT_TRUE(out[0] == out[1]) << "seed " << seed << ": the outputs differ";
  }
}

// The whole-body topology check after every repair (BeautifyOptions::
// check_topology_each_repair; the CLI's --paranoid) only checks: with it and without it
// beautify makes the same repairs and the same body, on the paper objects and on random
// zoo models. (Without it the CLI checks the whole body once, at the end.)
std::string paranoid_difference(const Body& input, const geo::Tolerances& tol) {
  Body fast = input.clone(), paranoid = input.clone();
  BeautifyOptions off, on;
  off.check_topology_each_repair = false;
  on.check_topology_each_repair = true;
  const BeautifyReport rf = beautify(fast, tol, off), rp = beautify(paranoid, tol, on);
  std::string why;
  if (!fast.equals(paranoid, &why)) return "the bodies differ: " + why;
  if (rf.problems.size() != rp.problems.size()) return "the reports list different numbers of problems";
  for (std::size_t i = 0; i < rf.problems.size(); ++i)
    if (rf.problems[i].outcome != rp.problems[i].outcome || rf.problems[i].operators != rp.problems[i].operators)
      return "problem " + std::to_string(i) + " was handled differently";
  if (!check_topology(fast).empty()) return "the body fails the whole-body check at the end";
  return "";
}

TEST(Pipeline, TheCheckAfterEveryRepairChangesNothingOnPaperObjects) {
  for (int n = 1; n <= 10; ++n) {
    zoo::ZooModel m = zoo::paper_object(n, false);
    EXPECT_EQ(paranoid_difference(m.body, tol_for(m.body, m.tolerance)), "") << "paper object " << n;
  }
}

RC_GTEST_PROP(Pipeline, TheCheckAfterEveryRepairChangesNothingOnRandomZooModels, ()) {
  const double t = *rc::gen::element(0.01, 0.02, 0.05);
  std::string what;
  const Body b = random_zoo_model(t, &what);
  const std::string bad = paranoid_difference(b, tol_for(b, t));
  if (!bad.empty()) RC_FAIL(what + bad);
}

// The CLI's fallback when the whole-body check at the end of a run fails: the run is undone
// by one transaction around it and repeated with the check after every repair. That
// needs a whole beautify run to roll back exactly.
TEST(Pipeline, AWholeRunRollsBackExactly) {
  for (int n = 1; n <= 10; ++n) {
    zoo::ZooModel m = zoo::paper_object(n, false);
    const Body before = m.body.clone();
    {
      Transaction whole(m.body);
      beautify(m.body, tol_for(m.body, m.tolerance));
      whole.rollback();
    }
    std::string why;
    EXPECT_TRUE(m.body.equals(before, &why)) << "paper object " << n << ": " << why;
  }
}

}  // namespace
}  // namespace kintsugi
