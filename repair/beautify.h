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
// Passes 1-6 (gaps, pinched faces, small face chains, slivers) are not implemented yet:
// their problems are reported "not repaired" with reason "pass not implemented yet".
// spec/beautify.md says what each repair does.
#pragma once

#include "geometry/tolerance.h"
#include "kernel/body.h"
#include "repair/problem.h"

#include <array>
#include <functional>
#include <string>
#include <vector>

namespace kintsugi {

struct RepairEntry {
  ProblemType type;
  std::vector<std::string> elements;   // as detected (printed handles)
  std::string action;                  // "repaired" or "not repaired"
  std::vector<std::string> operators;  // journal op names of the committed repair
  std::string reason;                  // why not repaired (empty when repaired)
  double deviation = 0.0;              // largest geometric deviation left around the repair
};

struct BeautifyReport {
  std::vector<RepairEntry> problems;  // in the order they were handled
  Counts counts_before, counts_after;
  std::array<int, 11> problems_before{}, problems_after{};  // detect() counts by type
  double max_deviation = 0.0;         // check_geometry over the result
  std::vector<std::string> max_elements;
  std::array<double, 11> seconds{};   // per pass, indexed by problem_order(type) - 1

  int repaired() const;
  int not_repaired() const;
};

struct BeautifyOptions {
  // Run the full check_topology after every repair (O(model) each; the operators
  // already check what they touch). Off makes the run linear.
  bool check_topology_each_repair = true;
  // Test hook: called after a repair's operators and geometry, before commit; a
  // non-empty answer rolls the repair back with that reason.
  std::function<std::string(const Body&, ProblemType)> veto;
};

// The whole pipeline, passes 1..11.
BeautifyReport beautify(Body& b, const geo::Tolerances& tol, const BeautifyOptions& options = {});

// One pass alone: detects the problems of type `t` and repairs them (appending to
// `report`). Used by beautify() and by the tests of Table 1's ordering.
void run_pass(Body& b, const geo::Tolerances& tol, ProblemType t, BeautifyReport& report,
              const BeautifyOptions& options = {});

// Whether the pass for `t` is implemented (7..11 are).
bool pass_implemented(ProblemType t);

}  // namespace kintsugi
