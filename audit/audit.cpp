#include "audit/audit.h"

#include "geometry/tolerance.h"
#include "invariants/element_geometry.h"
#include "repair/beautify.h"
#include "repair/detect.h"
#include "repair/pass.h"

#include <algorithm>
#include <chrono>
#include <set>

namespace kintsugi::audit {

namespace {

std::size_t idx(ProblemType t) { return std::size_t(problem_order(t) - 1); }

double size_of(const Body& b) { return model_size(b); }  // invariants/element_geometry.h

}  // namespace

bool paper_says_yes(ProblemType created, ProblemType pass) {
  for (ProblemType t : may_create(pass))
    if (t == created) return true;
  return false;
}

Verdict verdict(ProblemType created, ProblemType pass) {
  if (problem_order(created) <= problem_order(pass)) return Verdict::counterexample;
  return paper_says_yes(created, pass) ? Verdict::allowed : Verdict::disagreement;
}

TrialResult run_trial(const Recipe& r, const BeautifyOptions& options) {
  TrialResult out;
  std::optional<Built> built = build(r);
  if (!built) return out;
  out.ran = true;
  out.description = built->description;
  Body& b = built->body;
  const geo::Tolerances tol = geo::Tolerances::for_model(built->tolerance, size_of(b));
  BeautifyReport report;
  // The state the pass sees in the pipeline: every registered pass before it has run.
  for (const Pass* p : passes())
    if (problem_order(p->type) < problem_order(r.pass)) run_pass(b, tol, p->type, report, options);
  for (const RepairEntry& e : report.problems)
    if (e.repaired() && e.provisional()) out.precondition = false, out.provisional = true;
  const Detection before = detect(b, tol);
  for (const Problem& p : before.problems)
    if (problem_order(p.type) < problem_order(r.pass)) {
      out.precondition = false;
      if (std::find(out.left.begin(), out.left.end(), p.type) == out.left.end()) out.left.push_back(p.type);
    }
  const std::size_t first = report.problems.size();
  const Body before_pass = b;  // for telling a flip (below); a trial's model is small
  run_pass(b, tol, r.pass, report, options);
  const std::vector<RepairEntry> handled(report.problems.begin() + std::ptrdiff_t(first), report.problems.end());
  // The audited pass's own provisional repairs too: beautify would solve them after the
  // later passes or undo them (5cd8c92 judged its unsolved ones, and its run found a pinch
  // read off one: docs/table1-audit.md, session 26).
  for (const RepairEntry& e : handled)
    if (e.repaired() && e.provisional()) out.precondition = false, out.provisional = true;
  out.created = created_by(r.pass, before.problems, detect(b, tol).problems, handled);
  if (std::any_of(out.created.begin(), out.created.end(),
                  [&](const Problem& p) { return verdict(p.type, r.pass) == Verdict::counterexample; })) {
    const Detection tighter = detect(b, geo::Tolerances::for_model(kFlipMargin * built->tolerance, size_of(b)));
    std::vector<Problem> looser;
    for (double k : kFlipReach) {
      const Detection d = detect(before_pass, geo::Tolerances::for_model(k * built->tolerance, size_of(before_pass)));
      looser.insert(looser.end(), d.problems.begin(), d.problems.end());
    }
    // A small face and a sliver are one face problem told apart by area against t²: a
    // refit that grows a small face's area past it makes it a sliver, no new problem.
    auto as_other_face_problem = [](Problem p) {
      if (p.type == ProblemType::small_face) p.type = ProblemType::sliver_face;
      else if (p.type == ProblemType::sliver_face) p.type = ProblemType::small_face;
      return p;
    };
    for (const Problem& p : out.created)
      if (verdict(p.type, r.pass) == Verdict::counterexample &&
          (!existed_before(p, tighter.problems) || existed_before(p, looser) ||
           existed_before(as_other_face_problem(p), before.problems)))
        out.near_threshold.push_back(p);
  }
  return out;
}

namespace {
bool is_gap(ProblemType t) {
  return t == ProblemType::face_gap || t == ProblemType::edge_gap || t == ProblemType::multi_face_gap;
}
std::vector<Element> anchor(const Problem& p) {
  std::vector<Element> out;
  auto keep = [&](auto pred) {
    for (const Element& e : p.elements)
      if (pred(e)) out.push_back(e);
  };
  if (is_gap(p.type))
    keep([](const Element& e) { return std::holds_alternative<LoopH>(e); });
  else if (p.type == ProblemType::pinched_face)
    keep([](const Element& e) { return std::holds_alternative<EdgeH>(e); });
  else if (p.type == ProblemType::mergeable_edges)
    keep([](const Element& e) { return std::holds_alternative<VertexH>(e); });
  else
    out = p.elements;
  return out;
}
}  // namespace

namespace {
// A place where a face is pinched is a cluster of close pairs of its edges, reported at
// its closest pair (repair/detect_faces.cpp); a repair elsewhere on the face, or one
// refused, can leave the same place reported at another of its pairs. So a pinch existed
// before when pinches of the same face named both of its edges (the 949ce42 run, shard 7008:
// pyramid5's f1 refused at (e23, e30) and (e35, e38), then reported at (e30, e38), 0.0722
// apart before the pass too).
bool pinch_site_existed(const Problem& after, const std::vector<Problem>& before) {
  if (after.elements.size() != 3 || !std::holds_alternative<FaceH>(after.elements[0])) return false;
  bool named[2] = {false, false};
  for (const Problem& q : before) {
    if (q.type != ProblemType::pinched_face || q.elements.empty() || q.elements[0] != after.elements[0]) continue;
    for (int k = 0; k < 2; ++k)
      for (const Element& e : q.elements)
        if (e == after.elements[std::size_t(k) + 1]) named[k] = true;
  }
  return named[0] && named[1];
}
}  // namespace

bool existed_before(const Problem& after, const std::vector<Problem>& before) {
  const std::vector<Element> key = anchor(after);
  for (const Problem& q : before) {
    const bool same_kind = q.type == after.type || (is_gap(q.type) && is_gap(after.type));
    if (same_kind && anchor(q) == key) return true;
  }
  return after.type == ProblemType::pinched_face && pinch_site_existed(after, before);
}

std::vector<Problem> created_by(ProblemType pass, const std::vector<Problem>& before,
                                const std::vector<Problem>& after, const std::vector<RepairEntry>& handled) {
  // A problem of its own type that a repair created — a merged face that now matches a
  // third face under a new name — was taken up by the pass and, if it is still there,
  // refused and reported as not repaired: only one the pass never saw is created.
  std::vector<Problem> refused;
  for (const RepairEntry& e : handled)
    if (e.outcome == Outcome::refused) refused.push_back(e.problem);
  std::vector<Problem> out;
  for (const Problem& p : after)
    if (!existed_before(p, before) && !(p.type == pass && existed_before(p, refused))) out.push_back(p);
  return out;
}

Recipe shrink(Recipe r, const std::function<bool(const Recipe&)>& still) {
  bool progress = true;
  while (progress) {
    progress = false;
    // Fewer defects (the first, of the pass's own type, stays).
    for (std::size_t i = r.injections.size(); i-- > 1;) {
      Recipe c = r;
      c.injections.erase(c.injections.begin() + std::ptrdiff_t(i));
      if (still(c)) {
        r = c;
        progress = true;
      }
    }
    // A simpler base.
    std::vector<std::string> bases = base_names();
    std::stable_sort(bases.begin(), bases.end(),
                     [](const std::string& a, const std::string& b) { return base_faces(a) < base_faces(b); });
    const std::size_t mine = base_faces(r.base);
    for (const std::string& base : bases) {
      if (base_faces(base) >= mine) break;
      Recipe c = r;
      c.base = base;
      if (still(c)) {
        r = c;
        progress = true;
        break;
      }
    }
    // No motion.
    if (r.scale != 1.0 || r.translation != std::array<double, 3>{0, 0, 0} ||
        r.rotation != std::array<double, 4>{1, 0, 0, 0}) {
      Recipe c = r;
      c.scale = 1.0;
      c.translation = {0, 0, 0};
      c.rotation = {1, 0, 0, 0};
      if (still(c)) {
        r = c;
        progress = true;
      }
    }
  }
  return r;
}

namespace {
// Whether a trial created problems of a type, and whether all of them were threshold flips.
enum class Created { none, flips_only, some_not_flips };
Created created_as(const TrialResult& t, ProblemType type) {
  Created k = Created::none;
  for (const Problem& q : t.created)
    if (q.type == type) {
      if (!existed_before(q, t.near_threshold)) return Created::some_not_flips;
      k = Created::flips_only;
    }
  return k;
}
}  // namespace

Result run(const Options& o) {
  const auto start = std::chrono::steady_clock::now();
  Result res;
  std::array<std::array<bool, 11>, 11> recorded{}, recorded_flip{};
  for (const Pass* pass : passes()) {
    if (o.pass && *o.pass != pass->type) continue;
    // One generator per pass, seeded from the run's seed and the pass: a pass's trials do
    // not depend on which other passes are audited.
    std::seed_seq seq{std::uint32_t(o.seed), std::uint32_t(o.seed >> 32), std::uint32_t(problem_order(pass->type))};
    std::mt19937_64 rng(seq);
    for (long i = 0; i < o.trials; ++i) {
      if (o.progress) o.progress(pass->type, i, o.trials);
      const Recipe r = random_recipe(pass->type, rng);
      if (o.trace) o.trace(i, r);
      TrialResult t = run_trial(r, o.beautify);
      if (!t.ran) continue;
      if (!t.precondition) {
        res.skipped[idx(pass->type)]++;
        if (t.provisional) res.skipped_unsolved[idx(pass->type)]++;
        for (ProblemType left : t.left) res.skipped_by[idx(left)][idx(pass->type)]++;
        continue;
      }
      res.trials[idx(pass->type)]++;
      std::set<ProblemType> seen;
      for (const Problem& p : t.created) {
        if (!seen.insert(p.type).second) continue;
        res.cells[idx(p.type)][idx(pass->type)]++;
        const bool flip = created_as(t, p.type) == Created::flips_only;
        if (flip) res.flips[idx(p.type)][idx(pass->type)]++;
        // One finding per cell; a cell with flips only keeps looking for a counterexample.
        bool& done = recorded[idx(p.type)][idx(pass->type)];
        bool& flip_done = recorded_flip[idx(p.type)][idx(pass->type)];
        if (done || (flip && flip_done)) continue;
        (flip ? flip_done : done) = true;
        const Verdict v = verdict(p.type, pass->type);
        const ProblemType created = p.type;
        // The shrunk recipe must still make the same kind of finding: a counterexample
        // must not shrink into a flip, nor a flip into a counterexample.
        auto creates = [created, flip, v, &o](const Recipe& c) {
          const TrialResult t = run_trial(c, o.beautify);
          if (!t.precondition) return false;
          const Created k = created_as(t, created);
          return k != Created::none && (v != Verdict::counterexample || (k == Created::flips_only) == flip);
        };
        Finding f{created, r, p};
        if (o.shrink) {
          f.recipe = shrink(r, creates);
          // The example is the shrunk model's, so its element names match the recipe.
          for (const Problem& q : run_trial(f.recipe, o.beautify).created)
            if (q.type == created) {
              f.example = q;
              break;
            }
        }
        if (v == Verdict::counterexample)
          (flip ? res.threshold_flips : res.counterexamples).push_back(f);
        else if (v == Verdict::disagreement)
          res.disagreements.push_back(f);
        else
          res.witnesses.push_back(f);
      }
    }
    if (o.progress) o.progress(pass->type, o.trials, o.trials);
  }
  res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return res;
}

nlohmann::json to_json(const Result& r) {
  nlohmann::json cells = nlohmann::json::array();
  for (ProblemType col : kAllProblemTypes)
    for (ProblemType row : kAllProblemTypes) {
      const char* v = verdict(row, col) == Verdict::counterexample ? "counterexample"
                      : verdict(row, col) == Verdict::disagreement ? "disagreement"
                                                                   : "allowed";
      cells.push_back({{"fixing", problem_name(col)},
                       {"created", problem_name(row)},
                       {"paper", paper_says_yes(row, col) ? "Yes" : "No"},
                       {"count", r.cells[idx(row)][idx(col)]},
                       {"threshold_flips", r.flips[idx(row)][idx(col)]},
                       {"trials", r.trials[idx(col)]},
                       {"skipped", r.skipped[idx(col)]},
                       {"skipped_with_row_left", r.skipped_by[idx(row)][idx(col)]},
                       {"skipped_unsolved", r.skipped_unsolved[idx(col)]},
                       {"pass_registered", find_pass(col) != nullptr},
                       {"if_found", v}});
    }
  auto findings = [](const std::vector<Finding>& fs) {
    nlohmann::json a = nlohmann::json::array();
    for (const Finding& f : fs) {
      nlohmann::json at = nlohmann::json::array();
      for (const std::string& e : element_names(f.example)) at.push_back(e);
      a.push_back({{"created", problem_name(f.created)}, {"recipe", f.recipe.to_json()}, {"example_elements", at}});
    }
    return a;
  };
  return {{"cells", cells},
          {"counterexamples", findings(r.counterexamples)},
          {"threshold_flips", findings(r.threshold_flips)},
          {"disagreements", findings(r.disagreements)},
          {"witnesses", findings(r.witnesses)},
          {"seconds", r.seconds}};
}

}  // namespace kintsugi::audit
