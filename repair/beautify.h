// Beautification: the second half of the paper's algorithm (Figure 13, section 3.3).
// The eleven passes run in the paper's order (Table 1); each pass takes the problems of
// its type found by detect() as a queue, and problems that its own repairs create are
// appended to the end of that queue, so each pass visits each problem once and the run
// is linear for bounded face degree (paper section 5).
//
// Every repair is a sequence of Euler operators and geometry changes inside one
// Transaction. When it cannot complete (a precondition, geometry not consistent within
// the length tolerance, check_topology), it is rolled back: the body is exactly as it
// was before that repair, and the problem is reported "not repaired" with the reason.
//
// The passes come from the registry (repair/pass.h); a type with no pass yet has its
// problems reported "not repaired" with the reason "no pass for this type yet".
// spec/beautify.md says what each repair does.
#pragma once

#include "geometry/tolerance.h"
#include "kernel/body.h"
#include "problems/problem.h"
#include "repair/touched.h"

#include <array>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace kintsugi {

// What became of one problem.
enum class Outcome {
  repaired,          // its repair was committed
  resolved_earlier,  // an earlier repair removed it before its turn (its elements are gone)
  refused,           // its repair could not be made and was rolled back; `reason` says why
  resolved_later,    // refused (`reason` says why), then gone from the output: a later
                     // repair removed it (a pinch seen round a notch of small faces that
                     // pass 5 then merged away)
  no_pass,           // no pass for its type is built yet
};
// "repaired", "resolved by an earlier repair", "resolved by a later repair", "not repaired"
// (refused and no_pass).
const char* outcome_name(Outcome o);

struct RepairEntry {
  Problem problem;                     // as it was queued
  Outcome outcome = Outcome::refused;
  std::vector<std::string> operators;  // journal op names of the committed repair
  std::string reason;                  // why not repaired (empty when repaired)
  double deviation = 0.0;              // largest geometric deviation left around the repair
  std::string note = {};               // how it was repaired, where the pass says (e.g. a new face's surface)
  // Committed with its geometry consistent to the tolerance only: its region solve failed
  // (the reason is in `note`); beautify solves it again after later repairs, and undoes
  // the run that ends with it unsolved.
  bool unsolved = false;
  // Committed with loops of its faces touching (a pinch zipped on one side, its next zip
  // to come): beautify undoes the run that ends with the touch still there.
  bool touching = false;
  bool provisional() const { return unsolved || touching; }
  // The region's geometry solve (repair/region_solve.h): how far each solved face moved
  // from its surface before the repair (largest sample distance), and the largest
  // distance left between a vertex and a surface of its faces.
  std::vector<std::pair<FaceH, double>> surfaces_moved = {};
  double max_residual = 0.0;
  double solve_seconds = 0.0;  // wall time of that solve

  bool repaired() const { return outcome == Outcome::repaired; }
  bool left() const { return outcome == Outcome::refused || outcome == Outcome::no_pass; }
};

struct BeautifyReport {
  std::vector<RepairEntry> problems;  // in the order they were handled
  // The problems the output still has: what the pipeline left or created, found by its
  // local detections (a test checks that detect() on the output finds exactly these).
  std::vector<Problem> left;
  Counts counts_before, counts_after;
  std::array<int, 11> problems_before{}, problems_after{};  // by type: detect() before, `left` after
  double max_deviation = 0.0;         // check_geometry over the result
  std::vector<std::string> max_elements;
  std::array<double, 11> seconds{};   // per pass, indexed by problem_order(type) - 1
  // How many times the pipeline ran (again after a run ended with a repair unsolved:
  // beautify.cpp, "Unsolved repairs"), and how many refusals all runs took over from an
  // earlier attempt instead of attempting again (BeautifyOptions::shortcuts).
  int runs = 0;
  int refusals_taken_over = 0;

  int repaired() const;
  int not_repaired() const;  // entries refused or without a pass
};

struct BeautifyOptions {
  // Run the full check_topology after every repair (O(model) each; the operators
  // already check what they touch). Off makes the run linear.
  bool check_topology_each_repair = true;
  // Test hook: called after a repair's operators and geometry, before commit; a
  // non-empty answer rolls the repair back with that reason.
  std::function<std::string(const Body&, ProblemType)> veto;
  // Test hook: runs right after a pass's repair succeeded, before the checks, and may
  // change the body further (through operators) and what was touched. The audit's tests
  // use it to break a pass on purpose and see the audit catch it.
  std::function<void(Body&, ProblemType, Touched&)> after_repair;
  // Test hook: called each time the queues were brought up to date by local re-detection
  // (before each pass and after each round), with every problem they hold. They must be
  // exactly what detect() finds on the body then: the test of spec/problems.md,
  // "Detecting near a repair", at every step rather than only at the end.
  std::function<void(const Body&, const std::vector<Problem>&)> after_refresh;
  // The validity gate's "lies on" limit (invariants/region_validity.h); 0: beautify() and
  // run_pass() set it to max(precision, the input's largest deviation).
  double lies_on = 0.0;
  // Problems not to repair, by type and elements as detected, with why. beautify() fills
  // it itself: a run that ends with repairs whose geometry could not be solved to the
  // modelling precision (kept consistent to the tolerance only, waiting for later repairs
  // that did not help) would write a model that is not valid, so the run is undone and
  // done again without those repairs (beautify.cpp, "Unsolved repairs").
  std::map<std::pair<ProblemType, std::vector<Element>>, std::string> unsolved;
  // Problems refused that way in an earlier round of the run (beautify() fills it too):
  // tried again, they are repaired only when their geometry now solves. Kept unsolved
  // again, they would only end unsettled once more (no later repair settled them
  // before), and each such end costs a whole run again.
  std::set<std::pair<ProblemType, std::vector<Element>>> unsolved_earlier;
  // Shortcuts that must not change the outcome: a refusal taken over where the attempt
  // would meet it again (beautify.cpp, Replay and Refusals), and an edge whose two
  // vertices a repair put at one point refused before its geometry is computed
  // (coinciding_ends). Off only to test that they change nothing.
  bool shortcuts = true;
  // Whether a repair may be kept provisionally (its geometry solved to the tolerance only,
  // or its faces' loops touching) for later repairs to settle; beautify() turns it off
  // for its fourth and later runs ("Unsolved repairs" in beautify.cpp).
  bool provisional = true;
};

// The whole pipeline, passes 1..11.
BeautifyReport beautify(Body& b, const geo::Tolerances& tol, const BeautifyOptions& options = {});

// One pass alone: detects the problems of type `t` and repairs them (appending to
// `report`). Used by beautify() and by the tests of Table 1's ordering.
void run_pass(Body& b, const geo::Tolerances& tol, ProblemType t, BeautifyReport& report,
              const BeautifyOptions& options = {});

// Whether a pass for `t` is registered.
bool pass_implemented(ProblemType t);

}  // namespace kintsugi
