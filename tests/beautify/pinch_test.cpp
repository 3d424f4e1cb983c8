// Pass 4, pinched faces (paper 4.2): each location (necking, spiking, bossing) in both
// configurations (straight, complex) made the way reverse engineering makes it, repaired
// to the clean model's counts and within tolerance of it both ways; the paper's object 5
// (Table 2: 10 faces, 24 edges); the pinches of objects 8 and 10; and the unrealisable
// case of its Figure 32(b), refused with the body unchanged.
#include "invariants/element_geometry.h"
#include "io/native_json.h"
#include "invariants/geometry_check.h"
#include "invariants/region_validity.h"
#include "invariants/topology_check.h"
#include "kernel/builders.h"
#include "repair/beautify.h"
#include "repair/detect.h"
#include "tests/support/two_sided.h"
#include "zoo/defects_pinch.h"
#include "zoo/paper_build.h"
#include "zoo/zoo.h"

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

namespace kintsugi {
namespace {

using geo::Vec3;

constexpr double kTol = 0.5;

geo::Tolerances tol_for(const Body& b) { return geo::Tolerances::for_model(kTol, model_size(b)); }

std::string describe(const BeautifyReport& r) {
  std::string s;
  for (const auto& p : r.problems) {
    s += std::string(problem_name(p.problem.type)) + " [";
    for (const auto& e : element_names(p.problem)) s += e + " ";
    s += "] " + std::string(outcome_name(p.outcome)) + (p.reason.empty() ? "" : ": " + p.reason) + "\n";
  }
  return s;
}

std::vector<Problem> pinches(const Body& b, const geo::Tolerances& tol) {
  std::vector<Problem> out;
  for (const Problem& p : detect(b, tol).problems)
    if (p.type == ProblemType::pinched_face) out.push_back(p);
  return out;
}

// A 20 x 12 x 4 plate; the edge of its top face along the front, (0,0) -> (20,0).
struct Plate {
  Body b = build::box(20, 12, 4);
  HalfedgeH front() const {
    FaceH top = zoo::face_facing(b, Vec3::UnitZ(), Vec3(0, 0, 4));
    return zoo::halfedge_in(b, top, Vec3(0, 0, 4), Vec3(20, 0, 4));
  }
};

enum class Where { necking, spiking, bossing };
const char* name(Where w) { return w == Where::necking ? "necking" : w == Where::spiking ? "spiking" : "bossing"; }

// The defective and the clean model of one case: offsets off0, off1 in [0.1, 0.3] t; a
// kinked near side bends out 0.1 t farther than its ends in the middle (so the
// closest pair is at one end and the other near edge is close elsewhere: complex).
std::pair<Body, Body> make_case(Where w, bool kink, double off0, double off1) {
  Plate bad, good;
  zoo::make::PinchBlock k;
  k.off0 = off0;
  k.off1 = off1;
  k.kink = kink;
  k.kink_bump = std::max(off0, off1) + 0.1 * kTol - (off0 + off1) / 2;
  k.height = 3;
  switch (w) {
    case Where::bossing:
      k.s0 = 2, k.s1 = 18;
      zoo::make::pinch_bossing(bad.b, bad.front(), k, 5);
      zoo::add_flush_block(good.b, good.front(), k.s0, k.s1, std::max(off0, off1) + 5, k.height);
      break;
    case Where::necking:
      k.s0 = 4, k.s1 = 16;
      zoo::make::pinch_necking(bad.b, bad.front(), k, 12);
      zoo::make::pinch_necking_clean(good.b, good.front(), k, 12);
      break;
    case Where::spiking:
      k.s0 = off0, k.s1 = 8;
      zoo::make::pinch_spiking(bad.b, bad.front(), k, 6);
      zoo::make::pinch_spiking_clean(good.b, good.front(), k, 6);
      break;
  }
  return {std::move(bad.b), std::move(good.b)};
}

void check_case(Where w, bool kink, double off0, double off1) {
  auto [bad, good] = make_case(w, kink, off0, off1);
  const std::string label = std::string(name(w)) + (kink ? "/complex" : "/straight") + " off0=" +
                            std::to_string(off0) + " off1=" + std::to_string(off1);
  ASSERT_TRUE(check_topology(bad).empty()) << label;
  ASSERT_TRUE(check_topology(good).empty()) << label;
  geo::Tolerances tol = tol_for(bad);
  std::vector<Problem> found = pinches(bad, tol);
  ASSERT_FALSE(found.empty()) << label;
  EXPECT_EQ(subcase_name(found[0]), std::string(name(w)) + (kink ? "/complex" : "/straight")) << label;
  EXPECT_TRUE(detect(good, tol).problems.empty()) << label << ": the clean model has problems";
  BeautifyReport r = beautify(bad, tol);
  EXPECT_TRUE(check_topology(bad).empty()) << label << "\n" << describe(r);
  EXPECT_TRUE(pinches(bad, tol).empty()) << label << "\n" << describe(r);
  Counts c = bad.counts(), want = good.counts();
  for (const Problem& p : detect(bad, tol).problems) {
    std::string e;
    for (auto& n : element_names(p)) e += n + " ";
    ADD_FAILURE() << label << ": left " << problem_name(p.type) << " " << e << p.measure;
  }
  EXPECT_EQ(c.faces, want.faces) << label << "\n" << describe(r);
  EXPECT_EQ(c.edges, want.edges) << label << "\n" << describe(r);
  EXPECT_EQ(c.vertices, want.vertices) << label << "\n" << describe(r);
  EXPECT_LE(test::two_sided_distance(bad, good, 0.25), kTol) << label << "\n" << describe(r);
}

TEST(Pinch, EachLocationAndConfigurationBecomesTheCleanModel) {
  for (Where w : {Where::necking, Where::spiking, Where::bossing})
    for (bool kink : {false, true}) check_case(w, kink, 0.1 * kTol, 0.3 * kTol);
}

RC_GTEST_PROP(Pinch, AnyOffsetBetweenATenthAndFourTenthsOfTheTolerance, ()) {
  const Where w = *rc::gen::element(Where::necking, Where::spiking, Where::bossing);
  const bool kink = *rc::gen::arbitrary<bool>();
  const double off0 = kTol * (0.1 + 0.2 * *rc::gen::inRange(0, 1001) / 1000.0);
  const double off1 = kTol * (0.1 + 0.2 * *rc::gen::inRange(0, 1001) / 1000.0);
  check_case(w, kink, off0, off1);
  RC_ASSERT(!::testing::Test::HasFailure());
}

TEST(Pinch, PaperObject5BecomesTenFacesAndTwentyFourEdges) {
  zoo::ZooModel m = zoo::paper_object(5, false), clean = zoo::paper_object(5, true);
  geo::Tolerances tol = tol_for(m.body);
  BeautifyReport r = beautify(m.body, tol);
  EXPECT_TRUE(check_topology(m.body).empty()) << describe(r);
  EXPECT_EQ(m.body.counts().faces, 10u) << describe(r);
  EXPECT_EQ(m.body.counts().edges, 24u) << describe(r);
  EXPECT_EQ(m.body.counts().vertices, 16u) << describe(r);
  EXPECT_TRUE(detect(m.body, tol).problems.empty()) << describe(r);
  EXPECT_LE(test::two_sided_distance(m.body, clean.body, 0.25), m.tolerance) << describe(r);
}

// Objects 8 and 10 have gaps, slivers and small-face chains too, whose passes (1-3, 5,
// 6) are not on this branch: here only their pinches are checked.
TEST(Pinch, PinchesOfPaperObjects8And10AreRepaired) {
  for (int n : {8, 10}) {
    zoo::ZooModel m = zoo::paper_object(n, false);
    geo::Tolerances tol = tol_for(m.body);
    ASSERT_FALSE(pinches(m.body, tol).empty()) << "object " << n;
    BeautifyReport r = beautify(m.body, tol);
    int repaired = 0;
    for (const RepairEntry& e : r.problems)
      if (e.problem.type == ProblemType::pinched_face) {
        EXPECT_TRUE(e.repaired()) << "object " << n << ": " << e.reason;
        ++repaired;
      }
    EXPECT_EQ(repaired, n == 8 ? 1 : 2) << "object " << n << "\n" << describe(r);
    EXPECT_TRUE(check_topology(m.body).empty()) << "object " << n;
    EXPECT_TRUE(pinches(m.body, tol).empty()) << "object " << n << "\n" << describe(r);
  }
}

// Figure 32(b): a cylinder on a block, its base circle 0.1-0.4 t from all four sides of
// the block's top. Closing all four pinches would put four vertices on the circle, which
// three points fix; these four are not on one circle.
TEST(Pinch, CylinderPinchedInFourPlacesIsRefusedAndTheBodyUnchanged) {
  const double r = 5, d[4] = {0.05, 0.1, 0.15, 0.075};  // gaps to x = 0, x = W, y = 0, y = D
  const double W = 2 * r + d[0] + d[1], D = 2 * r + d[2] + d[3];
  Body b = build::box(W, D, 4);
  FaceH top = zoo::face_facing(b, Vec3::UnitZ(), Vec3(0, 0, 4));
  const Vec3 centre(r + d[0], r + d[2], 4);
  zoo::extrude_disc(b, zoo::add_circle_face(b, top, centre, r), Vec3(0, 0, 3), r, centre);
  b.clear_journal();
  ASSERT_TRUE(check_topology(b).empty());
  geo::Tolerances tol = tol_for(b);
  ASSERT_FALSE(pinches(b, tol).empty());
  Body before = b;
  BeautifyReport rep = beautify(b, tol);
  bool refused = false;
  for (const RepairEntry& e : rep.problems)
    if (e.problem.type == ProblemType::pinched_face) {
      EXPECT_EQ(e.outcome, Outcome::refused);
      EXPECT_NE(e.reason.find("Figure 32(b)"), std::string::npos) << e.reason;
      EXPECT_NE(e.reason.find("4 vertices on that one circle"), std::string::npos) << e.reason;
      EXPECT_NE(e.reason.find("fixed by three points"), std::string::npos) << e.reason;
      refused = true;
    }
  EXPECT_TRUE(refused) << describe(rep);
  std::string why;
  EXPECT_TRUE(b.equals(before, &why)) << why;
}

// A plate with a cylinder boss (radius 4) 0.1 from its front face.
Body cylinder_almost_flush_with_the_front() {
  const double r = 4;
  Body b = build::box(20, 12, 4);
  FaceH top = zoo::face_facing(b, Vec3::UnitZ(), Vec3(0, 0, 4));
  const Vec3 centre(10, r + 0.1, 4);
  zoo::extrude_disc(b, zoo::add_circle_face(b, top, centre, r), Vec3(0, 0, 3), r, centre);
  b.clear_journal();
  return b;
}

// The curved-versus-planar case on its own: the same cylinder near one side only (the
// others far), 0.1 from the plate's front face. Closing the pinch needs a vertex on the
// circle and on the front face, which do not meet (the cylinder misses the plane by 0.1;
// made tangent, the meeting point is a double root the solve cannot pin to the modelling
// precision). The repair used to be kept with the vertex consistent to the tolerance
// only: an output `kintsugi check` calls invalid (the vertex 0.05 off its surfaces). Now
// the run that ends with it unsolved is undone and the pinch is refused with that reason,
// the model unchanged.
TEST(Pinch, CylinderAlmostFlushWithOneSideIsRefusedRatherThanLeftOffItsSurfaces) {
  Body b = cylinder_almost_flush_with_the_front();
  geo::Tolerances tol = tol_for(b);
  std::vector<Problem> found = pinches(b, tol);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(subcase_name(found[0]), "bossing/complex");
  const Body before = b.clone();
  BeautifyReport rep = beautify(b, tol);
  EXPECT_TRUE(check_topology(b).empty()) << describe(rep);
  ASSERT_EQ(rep.problems.size(), 1u) << describe(rep);
  EXPECT_EQ(rep.problems[0].outcome, Outcome::refused) << describe(rep);
  // Refused at once since session 23: with the boss's bottom circle split into two arcs
  // at a vertex the solve left off its surfaces, the side's loop (same edges as before,
  // its seam still twice) no longer closes in the side's parameter domain
  // (loop_without_seam). Before, the repair was kept consistent to the tolerance and
  // undone at the end of the run, unsolved.
  EXPECT_TRUE(rep.problems[0].reason.find("could not be solved to the modelling precision") != std::string::npos ||
              rep.problems[0].reason.find("loop_without_seam") != std::string::npos)
      << describe(rep);
  std::string why;
  EXPECT_TRUE(b.equals(before, &why)) << why;
  EXPECT_LE(check_geometry(b, tol.precision).max_deviation, tol.precision);
}

// The same, with an edge split elsewhere: the run is undone and done again without the
// pinch, and the other repair is still made.
TEST(Pinch, AnUnsolvedRepairIsRefusedAndTheOthersAreStillMade) {
  Body b = cylinder_almost_flush_with_the_front();
  geo::Tolerances tol = tol_for(b);
  const Counts with_pinch = b.counts();
  std::string err;
  EdgeH far;  // the bottom edge at the back, away from the pinch
  for (EdgeH e : b.edges()) {
    const Vec3 p = b.point(b.origin(halfedge_of(e, 0))), q = b.point(b.target(halfedge_of(e, 0)));
    if (p.z() == 0 && q.z() == 0 && p.y() == 12 && q.y() == 12) far = e;
  }
  ASSERT_TRUE(far.valid());
  ASSERT_TRUE(zoo::inject(b, ProblemType::mergeable_edges, 5, far.str(), tol.length, &err)) << err;
  ASSERT_NE(b.counts(), with_pinch);
  BeautifyReport rep = beautify(b, tol);
  int merged = 0, refused = 0;
  for (const RepairEntry& e : rep.problems) {
    merged += e.problem.type == ProblemType::mergeable_edges && e.repaired();
    refused += e.problem.type == ProblemType::pinched_face && e.outcome == Outcome::refused;
  }
  EXPECT_EQ(merged, 1) << describe(rep);
  EXPECT_EQ(refused, 1) << describe(rep);
  EXPECT_EQ(b.counts(), with_pinch) << describe(rep);
  EXPECT_LE(check_geometry(b, tol.precision).max_deviation, tol.precision) << describe(rep);
}

// A pyramid's base fitted twice (split, one half tilted) with a boss on the tilted half
// near the split line: pass 4 zips the boss to the split edge (a pinch, by the letter of
// the definition), and pass 8 then merges the two halves across what is left of that edge.
// Their last common edge leaves the boss's footprint as a ring of the merged face; kemr
// made the outer boundary the ring instead, and the merge was refused as turning the face
// inside out (found by Beautify.InjectedDefectsOfTypes7To11AreRepaired).
TEST(Pinch, ABossZippedToASplitLineIsARingAgainWhenTheHalvesMerge) {
  // The model the property made (zoo::inject same_geometry_faces seed 0, pinched_face
  // seed 598760485 on a pyramid; the file keeps its loops' first half-edges, which decide
  // the side kemr was given).
  std::string err;
  auto doc = io::read_native_file(std::string(KINTSUGI_TEST_DATA_DIR) + "/native/boss_zipped_to_split_line.json", &err);
  ASSERT_TRUE(doc) << err;
  Body& b = doc->body;
  const geo::Tolerances tol = geo::Tolerances::for_model(0.02, model_size(b));
  ASSERT_EQ(pinches(b, tol).size(), 1u);
  BeautifyReport rep = beautify(b, tol);
  for (const RepairEntry& e : rep.problems) EXPECT_TRUE(e.repaired()) << describe(rep);
  EXPECT_TRUE(detect(b, tol).problems.empty()) << describe(rep);
  EXPECT_TRUE(check_topology(b).empty());
  // The pyramid's five faces and the boss's five; the base has the boss as a ring.
  EXPECT_EQ(b.counts().faces, 10u) << describe(rep);
  EXPECT_EQ(b.counts().loops, 11u) << describe(rep);
  EXPECT_LE(check_geometry(b, tol.precision).max_deviation, tol.precision);
}

}  // namespace
}  // namespace kintsugi

namespace kintsugi {
namespace {

// A pinch zipped one edge at a time: after the first zip the zipped side lies along the
// other side (loops touching, which the gate of one repair lets through), and the next zip
// was refused (the face would turn inside out). The Table 1 audit found it (run e4b68bd,
// seed 4001: paper4 with a boss pinch, mergeable edges and two small-face chains); beautify
// then wrote a face touching itself, which `kintsugi check` calls invalid. The first zip is
// now provisional until a later repair removes the touch; the run that ends with it still
// there is undone and the zip refused, so the output's loops touch nowhere.
TEST(Pinch, AZipThatLeavesLoopsTouchingIsUndoneWhenTheNextZipIsRefused) {
  std::string err;
  auto doc = io::read_native_file(std::string(KINTSUGI_TEST_DATA_DIR) + "/native/pinch_zip_left_touching.json", &err);
  ASSERT_TRUE(doc) << err;
  Body& b = doc->body;
  const geo::Tolerances tol = geo::Tolerances::for_model(doc->meta.at("tolerance").get<double>(), model_size(b));
  const std::vector<FaceH> before_faces = b.faces();
  ASSERT_TRUE(loop_violations(b, std::set<FaceH>(before_faces.begin(), before_faces.end()), tol).empty());
  // Here the later passes (the small-face chains) happen to remove the touch; refusing
  // them leaves it to the end of the run.
  BeautifyOptions only_pinches;
  only_pinches.veto = [](const Body&, ProblemType t) {
    return t == ProblemType::pinched_face ? std::string() : std::string("only pinches in this test");
  };
  BeautifyReport rep = beautify(b, tol, only_pinches);
  bool undone = false;
  for (const RepairEntry& e : rep.problems)
    undone = undone || e.reason.find("left loops of its faces touching") != std::string::npos;
  EXPECT_TRUE(undone) << describe(rep);
  EXPECT_TRUE(check_topology(b).empty()) << describe(rep);
  const std::vector<FaceH> fs = b.faces();
  std::vector<Violation> v = loop_violations(b, std::set<FaceH>(fs.begin(), fs.end()), tol);
  EXPECT_TRUE(v.empty()) << (v.empty() ? "" : to_string(v[0])) << "\n" << describe(rep);
  EXPECT_LE(check_geometry(b, tol.precision).max_deviation, tol.precision);
}

// A pinch that cannot be solved (a boss 0.012 from a pyramid's side at t = 0.02, whose
// zip forces a vertex 0.0204) is kept at the tolerance only, with two new vertices of
// the side off the boss's face. A later merge of two edges along that side's base solved
// a region holding them and failed too. At the end the run is undone and run again with
// the pinch refused, but the merge was not counted as beside the pinch (no face of the
// pinch's among the faces it touched, only among those round its vertices), so it was
// refused as well and the two edges stayed apart (rapidcheck seed 53 of
// Beautify.InjectedDefectsOfTypes7To11AreRepaired).
TEST(Pinch, ARepairUnsolvedOnlyBesideAnUnsolvedPinchIsMadeWhenThePinchIsRefused) {
  std::string err;
  auto doc = io::read_native_file(std::string(KINTSUGI_TEST_DATA_DIR) + "/native/pinch_unsolved_beside_a_merge.json", &err);
  ASSERT_TRUE(doc) << err;
  Body& b = doc->body;
  const geo::Tolerances tol = geo::Tolerances::for_model(doc->meta.at("tolerance").get<double>(), model_size(b));
  BeautifyReport rep = beautify(b, tol);
  EXPECT_TRUE(check_topology(b).empty()) << describe(rep);
  EXPECT_LE(check_geometry(b, tol.precision).max_deviation, tol.precision) << describe(rep);
  const Detection d = detect(b, tol);
  EXPECT_EQ(d.count(ProblemType::mergeable_edges), 0u) << describe(rep);
  EXPECT_EQ(d.count(ProblemType::short_edge_chain), 0u) << describe(rep);
  EXPECT_EQ(d.count(ProblemType::small_face_chain), 0u) << describe(rep);
}

}  // namespace
}  // namespace kintsugi
