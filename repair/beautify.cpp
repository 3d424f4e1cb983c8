// The pipeline of Figure 13: the registered passes in the paper's order, each a queue of
// problems (section 3.3). One whole-body detection at the start; after that, only the
// neighbourhood of what repairs touched is detected again: before each pass, the queued
// problems anchored there are replaced by what detect_near finds there, and after each
// repair its own neighbourhood feeds the running pass's queue.
#include "repair/beautify.h"

#include "invariants/geometry_check.h"
#include "invariants/region_validity.h"
#include "invariants/topology_check.h"
#include "kernel/transaction.h"
#include "repair/beautify_detail.h"
#include "repair/detect.h"
#include "repair/detect_threads.h"
#include "repair/pass.h"
#include "repair/region_solve.h"

#include <algorithm>
#include <chrono>
#include <deque>
#include <map>
#include <set>
#include <sstream>
#include <tuple>
#include <type_traits>
#include <variant>

namespace kintsugi {

const char* outcome_name(Outcome o) {
  switch (o) {
    case Outcome::repaired: return "repaired";
    case Outcome::resolved_earlier: return "resolved by an earlier repair";
    case Outcome::resolved_later: return "resolved by a later repair";
    case Outcome::refused:
    case Outcome::no_pass: return "not repaired";
  }
  return "?";
}

int BeautifyReport::repaired() const {
  int n = 0;
  for (const auto& p : problems) n += p.repaired();
  return n;
}
int BeautifyReport::not_repaired() const {
  int n = 0;
  for (const auto& p : problems) n += p.left();
  return n;
}

bool pass_implemented(ProblemType t) { return find_pass(t) != nullptr; }

namespace {

std::size_t slot(ProblemType t) { return std::size_t(problem_order(t) - 1); }

bool all_alive(const Body& b, const Problem& p) {
  for (const Element& e : p.elements)
    if (!std::visit([&](auto h) { return b.alive(h); }, e)) return false;
  return true;
}

// One repair inside a transaction: committed only when the operators, the new geometry,
// the local geometry check and (optionally) check_topology all succeed.
// A repair kept with the pass's own geometry because the solve could not reach the
// modelling precision then (see attempt()): solved again once later repairs are done.
struct Unsettled {
  std::size_t entry;  // its index in BeautifyReport::problems
  int round = 0;      // the pipeline's round that made it
  Touched touched;
  detail::OriginalFaces original;  // empty when only `touching`
  // The repair left loops of its faces touching (a pinch zipped on one side, its next zip
  // still to come): settled when a later repair has removed the touch.
  bool touching = false;
  // The touch is gone but the external check (which did not see the faces while they
  // touched) rejects them: why.
  std::string external;
};

// Where loops of the faces in `faces` touch without crossing (region_validity.h: a face
// folded onto itself), for faces of at most kManyLoops loops (a plate with a hole per
// feature is left to the whole-model check); "" when none does.
std::string touching_loops(const Body& b, const std::set<FaceH>& faces, const geo::Tolerances& tol) {
  std::set<FaceH> few;
  for (FaceH f : faces)
    if (b.alive(f) && b.loops_of(f).size() <= kManyLoops) few.insert(f);
  for (const Violation& v : loop_violations(b, few, tol))
    if (v.invariant == "loop_touches_itself" || v.invariant == "loops_touch") return v.detail;
  return "";
}

// The faces of `faces` whose loops touch (as touching_loops finds them).
std::set<FaceH> touching_faces(const Body& b, const std::set<FaceH>& faces, const geo::Tolerances& tol) {
  std::set<FaceH> out;
  for (FaceH f : faces)
    if (b.alive(f) && b.loops_of(f).size() <= kManyLoops && !touching_loops(b, {f}, tol).empty()) out.insert(f);
  return out;
}

// The faces whose surface was set from journal entry `from` on: the validity gate checks
// those whole (invariants/region_validity.h).
std::set<FaceH> surfaces_set_since(const Journal& j, std::size_t from) {
  std::set<FaceH> out;
  for (std::size_t i = from; i < j.size(); ++i)
    if (const auto* r = std::get_if<SetSurfaceRecord>(&j.entries()[i].record)) out.insert(r->face);
  return out;
}

RepairEntry attempt(Body& b, const Problem& p, const geo::Tolerances& tol, const BeautifyOptions& options,
                    const Pass& pass, Touched& touched, detail::OriginalFaces* unsettled = nullptr,
                    const FaceBoundsMemo* memo = nullptr) {
  RepairEntry entry{p, Outcome::refused, {}, "", 0.0};
  if (auto u = options.unsolved.find({p.type, p.elements}); u != options.unsolved.end()) {
    entry.reason = u->second;
    return entry;
  }
  Transaction tx(b);
  std::string why, note, solve_why;
  detail::OriginalFaces original;
  try {
    // The faces the repair can act on, as they are before it: the solve's data terms.
    original = detail::snapshot_near(b, p, tol);
    RepairContext call{b, p, tol, touched};
    if (options.shortcuts) call.coincide = options.lies_on > 0 ? options.lies_on : tol.precision;
    why = pass.repair(call);
    note = call.note;
    if (why.empty() && options.after_repair) options.after_repair(b, p.type, touched);
    // Checked before the solve, which keeps each vertex near where the pass put it: the
    // gate would refuse the edge as degenerate after solving for nothing.
    if (why.empty() && call.coincide > 0) why = detail::coinciding_ends(b, touched.vertices, call.coincide);
    // Every pass ends here: the region's surfaces and vertices solved together so that
    // the geometry agrees with the new topology to the modelling precision.
    // When it cannot (near-coincident faces waiting for pass 8 make a vertex's position
    // ill-conditioned), the pass's own geometry stands if it is consistent within the
    // tolerance (the check below), with the solve's reason in the note; otherwise the
    // reason names the constraints that cannot be met together.
    if (why.empty()) {
      detail::RegionSolve solve =
          detail::solve_region(b, touched, original, tol, p.type == ProblemType::pinched_face);
      solve_why = solve.why;
      entry.max_residual = solve.max_residual;
      entry.solve_seconds = solve.seconds;
      if (solve.why.empty())
        for (const auto& m : solve.moved) entry.surfaces_moved.push_back({m.face, m.distance});
    }
  } catch (const std::exception& e) {
    why = std::string("geometry could not be computed: ") + e.what();
  }
  if (why.empty()) {
    double dev = detail::local_deviation(b, touched, tol, &why);
    entry.deviation = dev;
    if (why.empty() && !(dev <= tol.length))
      why = solve_why.empty() ? "the new geometry is not consistent within tolerance (deviation " + detail::fmt(dev) + ")"
                              : solve_why;
  }
  if (why.empty() && !solve_why.empty() && options.unsolved_earlier.count({p.type, p.elements}))
    why = "its geometry could not be solved to the modelling precision, now as in an earlier round after which no "
          "later repair solved it: " + solve_why;
  if (why.empty() && !solve_why.empty() && !options.provisional)
    why = "its geometry could not be solved to the modelling precision, and this late run keeps no repair "
          "provisionally: " + solve_why;
  if (why.empty() && !solve_why.empty()) {
    note += (note.empty() ? "" : "; ") + std::string("consistent to the tolerance only: ") + solve_why;
    entry.unsolved = true;
  }
  // The validity gate: the touched region valid at modelling precision, never worse than
  // the input (options.lies_on). A repair the solve could not bring to that precision is
  // kept consistent to the tolerance (local_deviation above) and solved again later; its
  // distances are gated at the tolerance, but its loops must still neither cross nor turn
  // the wrong way, and it must still be writable.
  if (why.empty()) {
    const double at_precision = options.lies_on > 0 ? options.lies_on : tol.precision;
    const double lies_on = solve_why.empty() ? at_precision : std::max(at_precision, tol.length);
    touched.reshaped = surfaces_set_since(b.journal(), tx.first_entry());
    detail::touch_rearranged_loops(b, tx.first_entry(), touched);
    // Faces left touching are kept provisionally (below) when this run keeps anything so:
    // the external check sees them once a later repair has removed the touch (settle).
    // (Asked only when the external check refuses: finding touching loops for every
    // repair costs time for nothing.)
    auto gate = [&](std::set<FaceH> provisional) {
      return region_validity(b,
                             {touched.vertices, touched.edges, touched.faces, {}, touched.reshaped,
                              memo ? &memo->loops : nullptr, std::move(provisional)},
                             tol, lies_on, at_precision);
    };
    std::string invalid = gate({});
    if (options.provisional && invalid.rfind("external_check", 0) == 0)
      if (std::set<FaceH> provisional = touching_faces(b, touched.faces, tol); !provisional.empty())
        invalid = gate(std::move(provisional));
    if (!invalid.empty()) why = "the result would not be valid: " + invalid;
  }
  if (why.empty() && options.check_topology_each_repair) {
    auto v = check_topology(b);
    if (!v.empty()) why = "check_topology: " + to_string(v.front());
  }
  if (why.empty() && options.veto) why = options.veto(b, p.type);
  std::string touch;
  if (why.empty()) touch = touching_loops(b, touched.faces, tol);
  if (why.empty() && !touch.empty() && !options.provisional)
    why = "it would leave its faces' loops touching, and this late run keeps no repair provisionally: " + touch;
  if (!why.empty()) {
    tx.rollback();
    touched.clear();
    entry.reason = why;
    entry.deviation = 0.0;
    entry.surfaces_moved.clear();
    return entry;
  }
  // Loops left touching (the gate lets them through: a pinch zipped edge by edge passes
  // through them) make the repair provisional, like an unsolved one: a later repair must
  // remove the touch, or the run is undone and the repair refused.
  if (!touch.empty()) {
    note += (note.empty() ? "" : "; ") + std::string("provisional: ") + touch;
    entry.touching = true;
  }
  entry.operators = b.journal().op_names(tx.first_entry());
  entry.note = note;
  tx.commit();
  if (unsettled && !solve_why.empty()) *unsettled = std::move(original);
  entry.outcome = Outcome::repaired;
  return entry;
}

// The problems waiting for each pass (by type), kept current by local re-detection.
struct Queues {
  std::array<std::vector<Problem>, 11> by_type;
  // Shared by the refreshes and the passes' re-detections after each repair: every
  // change the pipeline commits is followed by one of them, as the memo requires.
  FaceBoundsMemo memo;

  // Replaces the problems anchored near `region` in the queues of types from `from` on
  // (earlier types are done: what is anchored there now goes to `left`... kept in the
  // same table, read at the end) by what detection finds there now.
  void refresh(const Body& b, const geo::Tolerances& tol, const Touched& region) {
    if (region.empty()) return;
    Neighbourhood n = neighbourhood(b, region, tol, &memo);
    std::vector<std::vector<Problem>*> lists;
    for (auto& q : by_type) lists.push_back(&q);
    drop_anchored(b, n, lists);
    for (Problem& p : detect_near(b, tol, n).problems) by_type[slot(p.type)].push_back(std::move(p));
  }
  std::vector<Problem> all() const {
    std::vector<Problem> out;
    for (const auto& q : by_type) out.insert(out.end(), q.begin(), q.end());
    return out;
  }
};

// The attempts of beautify's last run, for the next run to take refusals from
// (beautify(), "Unsolved repairs"). A run done again after one ended unsolved is the same
// run up to the first problem it now refuses: the pipeline is deterministic, so while
// every attempt so far met the same problem with the same outcome as last time, the body
// is as it was then, and a problem refused then at this point is refused again for the
// same reason. Only refusals are taken over (a repair must change the body again); they
// are most of the work on a part repaired at a tolerance well above its defects (Top.brep
// at --tol 0.684: 85 of 93 problems refused, each after its geometry was computed, in
// each of three runs).
struct Replay {
  std::vector<RepairEntry> previous;  // the last run's attempts, in order
  std::vector<RepairEntry> current;   // this run's, so far
  bool same = true;                   // every attempt of this run so far matched the last run's

  // The measure may differ in its last digits: a projection onto a free-form surface
  // starts from the last one's answer, and the last run's history was longer.
  static bool same_problem(const Problem& a, const Problem& b) {
    return a.type == b.type && a.elements == b.elements && a.measure_kind == b.measure_kind &&
           a.subcase == b.subcase && std::abs(a.measure - b.measure) <= 1e-9 * std::max(std::abs(a.measure), std::abs(b.measure));
  }
  // The last run's refusal of `p` at this point, when this run has been the same so far.
  const RepairEntry* refusal_for(const Problem& p) const {
    if (!same || current.size() >= previous.size()) return nullptr;
    const RepairEntry& e = previous[current.size()];
    return e.outcome == Outcome::refused && same_problem(e.problem, p) ? &e : nullptr;
  }
  void record(const RepairEntry& e) {
    const std::size_t i = current.size();
    same = same && i < previous.size() && same_problem(previous[i].problem, e.problem) &&
           previous[i].outcome == e.outcome && previous[i].reason == e.reason;
    current.push_back(e);
  }
  void next_run() {
    previous = std::move(current);
    current.clear();
    same = true;
  }
};

// Refusals within one run that a later attempt at the same problem can take over: a
// later round tries every problem left again (beautify_once), and a pass tries a refused
// one again after a repair near it, but where nothing was committed near the problem
// since its refusal (no change to a face within two rings of its elements: the faces its
// repair, solve and validity gate work on), the attempt would compute the same geometry
// and meet the same refusal. Refusals by a round's vetoes are not taken over (a later
// round may allow the repair).
struct Refusals {
  std::vector<std::set<FaceH>> changes;  // the faces around each change committed so far, in order
  struct Refused {
    std::size_t changes = 0;  // changes.size() when it was refused
    RepairEntry entry;
  };
  std::map<std::pair<ProblemType, std::vector<Element>>, Refused> by_problem;

  const RepairEntry* standing(const Body& b, const Problem& p) const {
    auto it = by_problem.find({p.type, p.elements});
    if (it == by_problem.end() || !Replay::same_problem(it->second.entry.problem, p)) return nullptr;
    if (it->second.changes == changes.size()) return &it->second.entry;
    const std::set<FaceH> near = detail::faces_near(b, p);
    for (std::size_t i = it->second.changes; i < changes.size(); ++i)
      for (FaceH f : changes[i])
        if (near.count(f)) return nullptr;
    return &it->second.entry;
  }
  void refused(const RepairEntry& e) { by_problem[{e.problem.type, e.problem.elements}] = {changes.size(), e}; }
  void changed(const Body& b, const Touched& t) {
    if (!t.empty()) changes.push_back(detail::region_faces(b, t));
  }
};

// Whether refusals are taken over (Replay, Refusals): not with the shortcuts off, nor
// with a test's veto hook, which may count its calls (every attempt is made again then).
bool takes_over_refusals(const BeautifyOptions& options) { return options.shortcuts && !options.veto; }

// Runs one pass over `queue`; returns what its committed repairs touched. Problems it
// does not repair stay in `left_of_type`.
Touched run_queue(Body& b, const geo::Tolerances& tol, const Pass* pass, std::vector<Problem> queue_in,
                  BeautifyReport& report, const BeautifyOptions& options, std::vector<Problem>& left_of_type,
                  std::vector<Unsettled>* unsettled = nullptr, FaceBoundsMemo* memo = nullptr,
                  Replay* replay = nullptr, Refusals* refusals = nullptr) {
  Touched region;
  if (!pass) {
    for (Problem& p : queue_in) {
      report.problems.push_back({p, Outcome::no_pass, {}, "no pass for this type yet", 0.0});
      left_of_type.push_back(std::move(p));
    }
    return region;
  }
  // A problem refused once is tried again after a later repair of this pass changed its
  // neighbourhood (a sliver beside another sliver may only be removable once the other
  // is gone); without that, a second beautify would repair what the first left. Every
  // element set is tried at most kMaxAttempts times, so the queue always drains.
  constexpr int kMaxAttempts = 3;
  std::deque<Problem> queue(queue_in.begin(), queue_in.end());
  std::map<std::vector<Element>, int> attempts;  // per element set: times queued
  std::set<std::vector<Element>> pending;        // element sets now in the queue
  for (const Problem& p : queue) {
    attempts[p.elements] = 1;
    pending.insert(p.elements);
  }
  while (!queue.empty()) {
    Problem p = std::move(queue.front());
    queue.pop_front();
    pending.erase(p.elements);
    if (!all_alive(b, p)) {
      // An earlier repair removed some of its elements; whatever is left of it there was
      // detected again around that repair and queued.
      report.problems.push_back({p, Outcome::resolved_earlier, {}, "", 0.0});
      continue;
    }
    Touched touched;
    detail::OriginalFaces original;
    const bool vetoed = options.unsolved.count({p.type, p.elements}) > 0;
    const RepairEntry* before = replay ? replay->refusal_for(p) : nullptr;
    if (!before && refusals && !vetoed) before = refusals->standing(b, p);
    RepairEntry entry = before ? *before : attempt(b, p, tol, options, *pass, touched, &original, memo);
    report.refusals_taken_over += before != nullptr;
    if (replay) replay->record(entry);
    if (refusals && !entry.repaired() && !vetoed) refusals->refused(entry);
    if (refusals && entry.repaired()) refusals->changed(b, touched);
    const bool ok = entry.repaired(), touching = entry.touching;
    report.problems.push_back(std::move(entry));
    if (ok && unsettled && (!original.empty() || touching))
      unsettled->push_back({report.problems.size() - 1, 0, touched, std::move(original), touching, {}});
    if (!ok) {
      left_of_type.push_back(std::move(p));
      continue;
    }
    region.merge(touched);
    // What the repair left or made of this pass's own type (Table 1's diagonal). A
    // problem refused earlier in this pass may have been changed by this repair: it is
    // dropped and found again if it still exists. The pending ones stay queued (found
    // again, they are already pending), but what is left of them is found too.
    Neighbourhood n = neighbourhood(b, touched, tol, memo);
    std::vector<const Problem*> waiting;
    for (const Problem& q : queue) waiting.push_back(&q);
    drop_anchored(b, n, {&left_of_type}, waiting);
    for (Problem& q : detect_near_for(*pass, b, tol, n)) {
      if (pending.count(q.elements) || attempts[q.elements] >= kMaxAttempts) continue;
      ++attempts[q.elements];
      pending.insert(q.elements);
      queue.push_back(std::move(q));
    }
  }
  return region;
}

Touched alive_part(const Body& b, const Touched& t) {
  Touched out;
  for (VertexH v : t.vertices)
    if (b.alive(v)) out.vertices.insert(v);
  for (EdgeH e : t.edges)
    if (b.alive(e)) out.edges.insert(e);
  for (FaceH f : t.faces)
    if (b.alive(f)) out.faces.insert(f);
  return out;
}

// Solves again, each in its own transaction, the regions of repairs kept at the tolerance
// only. What made their solve fail then is often gone now: two nearly coincident faces
// beside a pinch make a vertex ill-conditioned until pass 8 merges them. A region that
// still cannot be solved stays as it was (consistent within the tolerance). A solve moves
// vertices and surfaces as a repair does, so it passes the repair's validity gate (at the
// modelling precision, `at_precision`), and must not leave loops touching that did not
// touch before; else it is rolled back and the repair stays unsettled. (The Table 1 audit
// found a pinch's region solved after the pass's later zips with an edge of the face lying
// on another: `unsolved-pinched_face-pinched_face-settled-into-a-touch`.) Returns what the
// committed solves touched; the repairs' notes say which were settled.
Touched settle(Body& b, const geo::Tolerances& tol, double at_precision, std::vector<Unsettled>& unsettled,
               BeautifyReport& r) {
  Touched changed;
  std::vector<Unsettled> still;
  for (Unsettled& u : unsettled) {
    Touched t = alive_part(b, u.touched);
    if (t.empty()) continue;  // a later repair removed all of it, and solved its own region
    if (u.original.empty()) {  // only touching: settled once the touch is gone
      if (!touching_loops(b, t.faces, tol).empty()) {
        still.push_back(std::move(u));
        continue;
      }
      // Then the external check sees its faces, which it did not while they touched.
      if (ExternalRegionCheck external = external_region_check()) {
        Region region{t.vertices, t.edges, t.faces, {}, std::nullopt, nullptr, {}};
        if (std::string why = external(b, region); !why.empty()) {
          u.external = why;
          still.push_back(std::move(u));
          continue;
        }
      }
      r.problems[u.entry].note += "; its faces' loops no longer touch after the later repairs";
      r.problems[u.entry].touching = false;
      continue;
    }
    Transaction tx(b);
    std::string why;
    detail::RegionSolve s;
    try {
      s = detail::solve_region(b, t, u.original, tol, r.problems[u.entry].problem.type == ProblemType::pinched_face);
      why = s.why;
      if (why.empty()) {
        double dev = detail::local_deviation(b, t, tol, &why);
        if (why.empty() && !(dev <= tol.length)) why = "deviation " + detail::fmt(dev);
      }
      if (why.empty()) {
        t.reshaped = surfaces_set_since(b.journal(), tx.first_entry());
        // Faces still touching stay provisional (kept from the external check, as when the
        // repair was committed).
        std::set<FaceH> provisional;
        if (u.touching) provisional = touching_faces(b, t.faces, tol);
        why = region_validity(b, {t.vertices, t.edges, t.faces, {}, t.reshaped, nullptr, std::move(provisional)}, tol,
                              at_precision, at_precision);
      }
      if (why.empty() && !u.touching) why = touching_loops(b, t.faces, tol);
    } catch (const std::exception& e) {
      why = e.what();
    }
    if (!why.empty()) {
      tx.rollback();
      still.push_back(std::move(u));
      continue;
    }
    tx.commit();
    changed.merge(t);
    RepairEntry& e = r.problems[u.entry];
    e.note += "; solved to the modelling precision after the later repairs (largest residual " +
              detail::fmt(s.max_residual) + ")";
    e.max_residual = s.max_residual;
    u.original.clear();
    e.unsolved = false;
    if (u.touching && !touching_loops(b, t.faces, tol).empty()) {
      still.push_back(std::move(u));
      continue;
    }
    e.touching = false;
  }
  unsettled = std::move(still);
  return changed;
}

}  // namespace

void run_pass(Body& b, const geo::Tolerances& tol, ProblemType t, BeautifyReport& report, const BeautifyOptions& options) {
  const Pass* pass = find_pass(t);
  std::vector<Problem> mine;
  if (pass) {
    mine = detect_for(*pass, b, tol);
  } else {
    for (Problem& p : detect(b, tol).problems)
      if (p.type == t) mine.push_back(std::move(p));
  }
  std::vector<Problem> left;
  BeautifyOptions opt = options;
  if (!(opt.lies_on > 0)) opt.lies_on = lies_on_limit(tol, check_geometry(b, tol.precision, detect_threads()).max_deviation);
  // As a round of beautify ends: the repairs kept provisionally are solved again, or
  // checked again for touching loops; those that stay so keep RepairEntry::unsolved or
  // RepairEntry::touching.
  std::vector<Unsettled> unsettled;
  run_queue(b, tol, pass, std::move(mine), report, opt, left, &unsettled);
  // What settling moved may make problems of this pass's type (two faces merged apart,
  // solved to the precision, lie in one plane): beautify meets them in its next round; here
  // the pass runs again over them (twice at most), so that what the pass leaves is what
  // it refused.
  Touched settled = settle(b, tol, opt.lies_on, unsettled, report);
  for (int again = 0; again < 2 && !settled.empty() && pass; ++again) {
    std::vector<Problem> more = detect_for(*pass, b, tol);
    if (more.empty()) break;
    std::vector<Problem> still;
    run_queue(b, tol, pass, std::move(more), report, opt, still, &unsettled);
    settled = settle(b, tol, opt.lies_on, unsettled, report);
  }
}

namespace {

// Repairs refused in one round of the pipeline: (round, type, elements) -> why.
using RoundVetoes = std::map<std::tuple<int, ProblemType, std::vector<Element>>, std::string>;

// One run of the pipeline, refusing the repairs in `vetoes` in their rounds. `unsolved`
// gets the repairs still kept at the tolerance only when it ends.
BeautifyReport beautify_once(Body& b, const geo::Tolerances& tol, const BeautifyOptions& options_in,
                             const RoundVetoes& vetoes, RoundVetoes& unsolved, Replay* replay) {
  using clock = std::chrono::steady_clock;
  BeautifyReport r;
  r.counts_before = b.counts();
  auto t0 = clock::now();
  Queues q;
  {
    Detection first = detect(b, tol);
    r.problems_before = first.counts;
    for (Problem& p : first.problems) q.by_type[slot(p.type)].push_back(std::move(p));
  }
  const double first_detect = std::chrono::duration<double>(clock::now() - t0).count();
  Touched since_refresh;  // what repairs touched since the queues were last brought up to date
  // Table 1's order means one round suffices when repairs do not move geometry. They do,
  // within the tolerance (a merged face's refit, the region solve), so a distance just
  // above the tolerance can fall below it and an earlier type appear behind its pass
  // (docs/table1-audit.md, "Threshold flips"), and a problem refused early may become
  // repairable once its neighbours are repaired. So the passes run again over what is
  // left, refused problems included, until a round repairs nothing (a fixed point: a
  // second beautify then finds the same refusals and changes nothing) or kMaxRounds.
  constexpr int kMaxRounds = 3;
  std::vector<Unsettled> unsettled;
  Refusals refusals;
  for (int round = 0; round < kMaxRounds; ++round) {
    int repaired = 0;
    // Refused in this round only: in a later round, after the other repairs, the same
    // problem may solve (as it would in a second beautify: idempotence).
    BeautifyOptions options = options_in;
    for (const auto& [key, why] : vetoes) {
      if (std::get<0>(key) == round) options.unsolved[{std::get<1>(key), std::get<2>(key)}] = why;
      if (std::get<0>(key) < round) options.unsolved_earlier.insert({std::get<1>(key), std::get<2>(key)});
    }
    for (ProblemType t : kAllProblemTypes) {
      auto start = clock::now();
      q.refresh(b, tol, since_refresh);
      since_refresh.clear();
      if (options.after_refresh) options.after_refresh(b, q.all());
      std::vector<Problem> queue = std::move(q.by_type[slot(t)]);
      q.by_type[slot(t)].clear();
      std::vector<Problem> left;
      const std::size_t first_entry = r.problems.size();
      const std::size_t made = unsettled.size();
      since_refresh =
          run_queue(b, tol, find_pass(t), std::move(queue), r, options, left, &unsettled, &q.memo, replay,
                    takes_over_refusals(options) ? &refusals : nullptr);
      for (std::size_t i = made; i < unsettled.size(); ++i) unsettled[i].round = round;
      for (std::size_t i = first_entry; i < r.problems.size(); ++i) repaired += r.problems[i].repaired();
      q.by_type[slot(t)] = std::move(left);  // done with this type: what stays is left
      r.seconds[slot(t)] += std::chrono::duration<double>(clock::now() - start).count();
    }
    const Touched settled = settle(b, tol, options.lies_on > 0 ? options.lies_on : tol.precision, unsettled, r);
    refusals.changed(b, settled);
    since_refresh.merge(settled);
    // What the last pass and the settling touched, and anything a pass created of a type
    // fixed before it (a break of Table 1's order), is found here too.
    q.refresh(b, tol, since_refresh);
    since_refresh.clear();
    if (options.after_refresh) options.after_refresh(b, q.all());
    bool any_left = false;
    for (const auto& by : q.by_type) any_left = any_left || !by.empty();
    if (repaired == 0 || !any_left) break;
  }
  // The first repair left unsolved, and every later one whose faces it did not touch:
  // a later one beside it may be unsolved only because of it (its solve meets the
  // vertex the first left off its surfaces), and is tried again in the next run. Its
  // faces are those its solve takes in: the faces round the vertices and edges it
  // touched too. (A pinch zipped against a pyramid's side left two new vertices of that
  // side off the boss's face; a merge of two edges along the side's base, touching no
  // face of the pinch's, solved a region holding them, failed, and was refused in every
  // run: rapidcheck seed 53 of Beautify.InjectedDefectsOfTypes7To11AreRepaired.)
  std::set<FaceH> near_unsolved;
  for (const Unsettled& u : unsettled) {
    const std::set<FaceH> faces = detail::region_faces(b, u.touched);
    bool beside = false;
    for (FaceH f : faces) beside = beside || near_unsolved.count(f);
    near_unsolved.insert(faces.begin(), faces.end());
    if (beside) continue;
    const RepairEntry& e = r.problems[u.entry];
    unsolved[{u.round, e.problem.type, e.problem.elements}] =
        !u.external.empty()
            ? "it left loops of its faces touching, and once later repairs had removed the touch they were not "
              "valid: " + u.external
        : u.original.empty()
            ? "it left loops of its faces touching, and no later repair removed the touch: the model would not be "
              "valid (" + e.note + ")"
            : "its geometry could not be solved to the modelling precision, even after the later repairs, and the "
              "model would not be valid (" + e.note + ")";
  }
  // A problem refused in one round and taken up again in a later one is reported once,
  // with its last outcome.
  {
    std::map<std::pair<int, std::vector<Element>>, std::size_t> last;
    for (std::size_t i = 0; i < r.problems.size(); ++i)
      last[{problem_order(r.problems[i].problem.type), r.problems[i].problem.elements}] = i;
    std::vector<RepairEntry> kept;
    for (std::size_t i = 0; i < r.problems.size(); ++i) {
      const RepairEntry& e = r.problems[i];
      const bool superseded = last[{problem_order(e.problem.type), e.problem.elements}] != i;
      if (!(superseded && (e.outcome == Outcome::refused || e.outcome == Outcome::no_pass)))
        kept.push_back(std::move(r.problems[i]));
    }
    r.problems = std::move(kept);
  }
  r.seconds[0] += first_detect;  // the first detection is charged to the first pass
  for (auto& by : q.by_type)
    for (Problem& p : by) {
      r.problems_after[slot(p.type)]++;
      r.left.push_back(std::move(p));
    }
  // A refused problem that the output no longer has was removed by a later repair (a
  // pinch seen round a notch of small faces, gone once pass 5 merged them): calling it
  // "not repaired" would send the user to look for a defect that is not there.
  {
    std::set<std::pair<ProblemType, std::vector<Element>>> still;
    for (const Problem& p : r.left) still.insert({p.type, p.elements});
    for (RepairEntry& e : r.problems)
      if (e.outcome == Outcome::refused && !still.count({e.problem.type, e.problem.elements}))
        e.outcome = Outcome::resolved_later;
  }
  r.counts_after = b.counts();
  GeometryReport g = check_geometry(b, tol.precision, detect_threads());
  r.max_deviation = g.max_deviation;
  r.max_elements = g.max_elements;
  return r;
}

}  // namespace

// Unsolved repairs. A repair whose region solve fails is kept when its geometry is
// consistent to the tolerance, because what made the solve fail is often removed by a
// later pass (settle()). When the run ends with such a repair still unsolved, the model
// is off its curves and surfaces by up to the tolerance: not valid, and a repair must
// leave a valid model or change nothing. The repair cannot be undone alone (later
// repairs built on it), so the whole run is undone (one transaction around it) and run
// again with those problems refused in the round that made them (the first, and the
// later ones it did not touch: one beside it may have failed because of it). The
// pipeline is deterministic, so everything before them happens as before and they are
// met under the same names. A later round tries them again after the other repairs, as
// a second beautify would. Each run refuses at least one more (problem, round) pair, so
// this ends.
BeautifyReport beautify(Body& b, const geo::Tolerances& tol, const BeautifyOptions& options_in) {
  // What the input already had off its curves and surfaces: repairs must not make it worse.
  BeautifyOptions options = options_in;
  if (!(options.lies_on > 0)) options.lies_on = lies_on_limit(tol, check_geometry(b, tol.precision, detect_threads()).max_deviation);
  RoundVetoes vetoes;
  Replay replay;
  int runs = 0, taken_over = 0;
  constexpr int kRunsWithProvisional = 3;
  for (;;) {
    Transaction whole(b);
    RoundVetoes unsolved;
    BeautifyReport r =
        beautify_once(b, tol, options, vetoes, unsolved, takes_over_refusals(options) ? &replay : nullptr);
    replay.next_run();
    r.runs = ++runs;
    // Bounded: each run ended with a repair unsolved refuses at least one more, but each
    // refusal changes what the repairs after it meet, and on a part repaired at a
    // tolerance above its features' sizes one new repair after another ends unsolved
    // (MODERN_Sink_1.brep at --tol 0.59: 16 runs, 88 s). From the fourth run on nothing is
    // kept provisionally: a repair that does not solve, or leaves loops touching, is
    // refused at once, so that run ends with nothing unsolved.
    if (runs >= kRunsWithProvisional) options.provisional = false;
    r.refusals_taken_over = taken_over += r.refusals_taken_over;
    std::size_t added = 0;
    for (auto& [key, why] : unsolved) added += vetoes.emplace(key, why).second;
    if (unsolved.empty() || added == 0) {
      whole.commit();
      return r;
    }
    whole.rollback();
  }
}

namespace detail {

void touch_rearranged_loops(const Body& b, std::size_t from, Touched& touched) {
  const Journal& j = b.journal();
  std::set<LoopH> loops;
  std::set<FaceH> faces;
  for (std::size_t i = from; i < j.size(); ++i) {
    const JournalEntry& e = j.entries()[i];
    std::visit(
        [&](const auto& r) {
          using R = std::decay_t<decltype(r)>;
          if constexpr (std::is_same_v<R, MvfsRecord> || std::is_same_v<R, MfkbRecord> ||
                        std::is_same_v<R, MfkrhRecord>)
            faces.insert(r.face);
          if constexpr (std::is_same_v<R, MefRecord>) faces.insert(r.face);
          if constexpr (std::is_same_v<R, KefRecord>)
            for (std::uint32_t l : j.extra_of(e)) loops.insert(LoopH(l));
          if constexpr (std::is_same_v<R, KemrRecord> || std::is_same_v<R, KfmrhRecord>) loops.insert(r.ring);
        },
        e.record);
  }
  for (FaceH f : faces)
    if (b.alive(f))
      for (LoopH l : b.loops_of(f)) loops.insert(l);
  for (LoopH l : loops) {
    if (!b.alive(l) || b.is_border(l)) continue;
    if (b.is_lone(l)) {
      touched.vertices.insert(b.lone_vertex(l));
      continue;
    }
    for (HalfedgeH h : b.loop_halfedges(l)) touched.edges.insert(edge_of(h));
  }
}

}  // namespace detail

}  // namespace kintsugi
