// The Table 1 audit: recipes rebuild their models exactly; a pass broken on purpose is
// caught and shrunk to a small model; every saved finding in tests/data/table1/ replays.
#include "audit/audit.h"
#include "geometry/curve.h"
#include "geometry/tolerance.h"
#include "invariants/element_geometry.h"
#include "io/native_json.h"
#include "kernel/euler.h"
#include "repair/detect.h"
#include "repair/pass.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

namespace kintsugi::audit {
namespace {

TEST(AuditRecipe, JsonRoundTripAndDeterministicBuild) {
  std::mt19937_64 rng(7);
  for (int i = 0; i < 20; ++i) {
    Recipe r = random_recipe(kAllProblemTypes[std::size_t(i) % 11], rng);
    Recipe back = Recipe::from_json(nlohmann::json::parse(r.to_json().dump()));
    EXPECT_EQ(back.to_json(), r.to_json());
    auto a = build(r), b = build(back);
    ASSERT_EQ(a.has_value(), b.has_value());
    if (!a) continue;
    std::string why;
    EXPECT_TRUE(a->body.equals(b->body, &why)) << why;
    EXPECT_EQ(a->tolerance, b->tolerance);
  }
}

TEST(AuditRecipe, BadRecipesAreRefusedByName) {
  nlohmann::json j = Recipe{}.to_json();
  j["pass"] = "no_such_pass";
  EXPECT_THROW(Recipe::from_json(j), std::invalid_argument);
  j = Recipe{}.to_json();
  j.erase("base");
  EXPECT_THROW(Recipe::from_json(j), std::invalid_argument);
  Recipe r;
  r.base = "dodecahedron";
  r.injections = {{ProblemType::small_face, 1}};
  EXPECT_THROW(build(r), std::invalid_argument);
}

// Pass 9 broken on purpose: after collapsing a small face it splits an edge at the new
// vertex into two short pieces and the rest — a chain of short edges, type 7, whose pass
// ran before pass 9. The audit must find it in a CI-sized run and shrink it.
TEST(Audit, FindsAPassBrokenOnPurposeAndShrinksIt) {
  Options o;
  o.pass = ProblemType::small_face;
  o.trials = 40;
  o.seed = 3;
  o.beautify.after_repair = [](Body& b, ProblemType t, Touched& touched) {
    if (t != ProblemType::small_face) return;
    for (VertexH v : touched.vertices) {
      if (!b.alive(v)) continue;
      HalfedgeH h = b.out(v);
      const geo::Vec3 p = b.point(v), q = b.point(b.target(h));
      const double len = (q - p).norm();
      if (len <= 0) continue;
      // Two pieces of 1e-4 of the edge each at v: shorter than any audit tolerance.
      auto r1 = euler::semv(b, h, p + 1e-4 * (q - p));
      if (!r1) return;
      auto r2 = euler::semv(b, r1->next, p + 2e-4 * (q - p));
      if (!r2) return;
      touched.vertices.insert(r1->vertex);
      touched.vertices.insert(r2->vertex);
      touched.edges.insert(edge_of(h));
      touched.edges.insert(r1->edge);
      touched.edges.insert(r2->edge);
      return;
    }
  };
  Result r = run(o);
  ASSERT_GT(r.trials[std::size_t(problem_order(ProblemType::small_face) - 1)], 0);
  const Finding* found = nullptr;
  for (const Finding& f : r.counterexamples)
    if (f.created == ProblemType::short_edge_chain) found = &f;
  ASSERT_NE(found, nullptr) << to_json(r).dump(1);
  // 1e-4 of an edge is short at any tolerance: never taken for a threshold flip.
  for (const Finding& f : r.threshold_flips) EXPECT_NE(f.created, ProblemType::short_edge_chain);
  EXPECT_EQ(found->recipe.injections.size(), 1u) << found->recipe.to_json().dump();
  EXPECT_LE(base_faces(found->recipe.base), 7u) << found->recipe.to_json().dump();
  EXPECT_EQ(found->recipe.scale, 1.0);
  // Without the sabotage the shrunk model is no counterexample.
  for (const Problem& p : run_trial(found->recipe).created)
    EXPECT_NE(p.type, ProblemType::short_edge_chain) << found->recipe.to_json().dump();
}

// The real passes: no counterexample to the order in a short run (CI runs more through
// `kintsugi audit`).
TEST(Audit, RegisteredPassesKeepTheOrder) {
  Options o;
  o.trials = 15;
  o.seed = 11;
  o.shrink = false;
  Result r = run(o);
  std::string bad;
  for (const Finding& f : r.counterexamples)
    bad += std::string(problem_name(f.recipe.pass)) + " created " + problem_name(f.created) + ": " +
           f.recipe.to_json().dump() + "\n";
  EXPECT_EQ(bad, "");
  const nlohmann::json j = to_json(r);
  EXPECT_EQ(j["cells"].size(), 121u);
}

// A pinch is one place on a face, reported at its closest pair of edges; the place
// reported at another of its pairs after a pass is the same pinch, a pinch of other edges
// or of another face is not.
TEST(Audit, APinchReportedAtAnotherPairOfItsPlaceExistedBefore) {
  auto pinch = [](std::uint32_t f, std::uint32_t a, std::uint32_t b) {
    Problem p;
    p.type = ProblemType::pinched_face;
    p.elements = {FaceH(f), EdgeH(a), EdgeH(b)};
    return p;
  };
  // The 949ce42 run, shard 7008: f1 refused at (e23, e30) and (e35, e38), then (e30, e38).
  const std::vector<Problem> before = {pinch(1, 23, 30), pinch(1, 35, 38)};
  EXPECT_TRUE(existed_before(pinch(1, 30, 38), before));
  EXPECT_TRUE(existed_before(pinch(1, 23, 30), before));
  EXPECT_FALSE(existed_before(pinch(1, 30, 39), before));  // e39 was in no pinch
  EXPECT_FALSE(existed_before(pinch(2, 30, 38), before));  // another face
  Problem small;
  small.type = ProblemType::small_face;
  small.elements = {FaceH(1), EdgeH(30), EdgeH(38)};
  EXPECT_FALSE(existed_before(small, before));  // another kind at the same elements
}

// Every saved finding replays: a witness still shows its "Yes", a documented disagreement
// still shows, a counterexample (a bug that was fixed) no longer does (or its trial is no
// longer judged: skipped), an "unsolved" one (a counterexample of the 08cd799 run read
// off a model an earlier repair had left unsolved) is skipped as such or, judged, does
// not create its type; the saved native
// model is the one the recipe builds.
TEST(Audit, SavedFindingsReplay) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(KINTSUGI_TEST_DATA_DIR) / "table1";
  int n = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() != ".json" || name.find(".model.") != std::string::npos) continue;
    std::ifstream in(entry.path());
    const nlohmann::json j = nlohmann::json::parse(in);
    const Recipe r = Recipe::from_json(j);
    const ProblemType created = *problem_from_name(j.at("created").get<std::string>());
    const std::string kind = j.at("kind").get<std::string>();
    if (!find_pass(r.pass)) continue;  // its pass is not in this build
    ++n;
    bool creates = false, all_near_threshold = true;
    const TrialResult t = run_trial(r);
    for (const Problem& p : t.created)
      if (p.type == created) creates = true, all_near_threshold = all_near_threshold && existed_before(p, t.near_threshold);
    if (kind == "counterexample")
      EXPECT_FALSE(creates && t.precondition) << name << ": the counterexample is back";
    else if (kind == "unsolved")  // not judged: an earlier repair's geometry was left unsolved;
      // or, judged now that it solves, it does not create its type (since rollbacks restore
      // where each loop starts, unsolved-pinched_face-pinched_face's earlier repairs solve)
      EXPECT_TRUE((t.provisional && !t.precondition) || !creates) << name << ": now judged, and creates its type";
    else
      EXPECT_TRUE(creates) << name << ": the " << kind << " no longer shows";
    // A flip is told from a counterexample (TrialResult::near_threshold).
    if (kind == "threshold_flip") {
      EXPECT_TRUE(all_near_threshold) << name << ": no longer judged a threshold flip";
    }
    fs::path model = entry.path();
    model.replace_extension(".model.json");
    if (fs::exists(model)) {
      std::string error;
      auto read = io::read_native_file(model.string(), &error);
      ASSERT_TRUE(read) << name << ": " << error;
      std::string why;
      EXPECT_TRUE(read->body.equals(build(r)->body, &why))
          << name << ": " << why;
    }
  }
  // The folder holds the documented run's findings (docs/table1-audit.md): a replay that
  // read none of them would pass without checking anything.
  EXPECT_GT(n, 0) << "no saved finding was replayed from " << dir;
  RecordProperty("replayed", n);
}

// A chain of small faces where two faces should share an edge breaks that edge in two
// pieces joined through the chain's tiny edges; the faces beside it are notched, not
// pinched (spec/problems.md, "Pinching"). On random models with chains alone (every base,
// random tolerance and motion), detection finds the chains and no pinch: before the notch
// rule, half of these models had a "pinch" on a face beside a chain, which pass 4 refused
// and the Table 1 audit then skipped (small_face_chain: 103 of 317 trials).
TEST(Audit, ChainsOfSmallFacesMakeNoPinchBesideThem) {
  std::mt19937_64 rng(20261205);
  int built = 0, chains = 0;
  for (int k = 0; k < 60; ++k) {
    Recipe r = random_recipe(ProblemType::small_face_chain, rng);
    r.injections.resize(1);  // the chain alone
    std::optional<Built> b = build(r);
    if (!b) continue;
    ++built;
    const geo::Tolerances tol = geo::Tolerances::for_model(b->tolerance, model_size(b->body));
    const Detection d = detect(b->body, tol);
    chains += d.count(ProblemType::small_face_chain) > 0;
    EXPECT_EQ(d.count(ProblemType::pinched_face), 0) << r.to_json().dump();
  }
  EXPECT_GT(built, 40);
  EXPECT_GT(chains, built / 2);
}

// Found by the documented run (`kintsugi audit --pass pinched_face --trials 3000 --seed 2026
// --trace`, trial 523): detection, measuring a face while pass 4 runs, did not come back.
// An edge of the face is a flat ellipse (a = 6360, b = 0.03); sampling it at the step its
// tips need put 2^20 points on its 2-unit arc, and CGAL's constrained triangulation of
// that boundary ran for minutes in flip cascades. Ellipses are now sampled by their local
// curvature (Curve.SamplingAFlatEllipseCostsPointsOnlyAtItsTip); the trial takes 0.1 s.
TEST(Audit, TrialThatHungMeasuringAFlatEllipse) {
  std::ifstream in(std::string(KINTSUGI_TEST_DATA_DIR) + "/audit_slow/pinched_face-seed2026-trial523.json");
  ASSERT_TRUE(in) << "missing recipe";
  const Recipe r = Recipe::from_json(nlohmann::json::parse(in));
  EXPECT_TRUE(run_trial(r).ran);
}

}  // namespace
}  // namespace kintsugi::audit
