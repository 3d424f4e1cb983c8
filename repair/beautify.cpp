// The pipeline of Figure 13: passes in the paper's order, each a queue of problems.
#include "repair/beautify.h"

#include "invariants/geometry_check.h"
#include "invariants/topology_check.h"
#include "kernel/transaction.h"
#include "repair/beautify_detail.h"
#include "repair/detect.h"

#include <chrono>
#include <deque>
#include <sstream>

namespace kintsugi {

int BeautifyReport::repaired() const {
  int n = 0;
  for (const auto& p : problems) n += p.action == "repaired";
  return n;
}
int BeautifyReport::not_repaired() const { return int(problems.size()) - repaired(); }

bool pass_implemented(ProblemType t) { return problem_order(t) >= problem_order(ProblemType::short_edge_chain); }

namespace {

using RepairFn = std::string (*)(detail::RepairCall&);

RepairFn repair_for(ProblemType t) {
  switch (t) {
    case ProblemType::short_edge_chain: return detail::repair_short_edge_chain;
    case ProblemType::same_geometry_faces: return detail::repair_same_geometry;
    case ProblemType::small_face: return detail::repair_small_face;
    case ProblemType::mergeable_edges: return detail::repair_mergeable_edges;
    case ProblemType::short_edge: return detail::repair_short_edge;
    default: return nullptr;
  }
}

std::string fmt(double d) {
  std::ostringstream os;
  os.precision(3);
  os << d;
  return os.str();
}

// One repair inside a transaction: committed only when the operators, the new geometry,
// the local geometry check and (optionally) check_topology all succeed.
RepairEntry attempt(Body& b, const Problem& p, const geo::Tolerances& tol, const BeautifyOptions& options,
                    RepairFn fn, detail::Touched& touched) {
  RepairEntry entry{p.type, p.elements, "not repaired", {}, "", 0.0};
  Transaction tx(b);
  std::string why;
  try {
    detail::RepairCall call{b, p, tol, touched};
    why = fn(call);
  } catch (const std::exception& e) {
    why = std::string("geometry could not be computed: ") + e.what();
  }
  if (why.empty()) {
    double dev = detail::local_deviation(b, touched, tol, &why);
    entry.deviation = dev;
    if (why.empty() && !(dev <= tol.length))
      why = "the new geometry is not consistent within tolerance (deviation " + fmt(dev) + ")";
  }
  if (why.empty() && options.check_topology_each_repair) {
    auto v = check_topology(b);
    if (!v.empty()) why = "check_topology: " + to_string(v.front());
  }
  if (why.empty() && options.veto) why = options.veto(b, p.type);
  if (!why.empty()) {
    tx.rollback();
    entry.reason = why;
    entry.deviation = 0.0;
    return entry;
  }
  entry.operators = b.journal().op_names(tx.first_entry());
  tx.commit();
  entry.action = "repaired";
  return entry;
}

void run_queue(Body& b, const geo::Tolerances& tol, ProblemType t, std::vector<Problem> queue_in,
               BeautifyReport& report, const BeautifyOptions& options) {
  RepairFn fn = repair_for(t);
  if (!fn) {
    for (const Problem& p : queue_in)
      report.problems.push_back({p.type, p.elements, "not repaired", {}, "pass not implemented yet", 0.0});
    return;
  }
  std::deque<Problem> queue(queue_in.begin(), queue_in.end());
  std::set<std::vector<std::string>> queued;
  for (const Problem& p : queue) queued.insert(p.elements);
  while (!queue.empty()) {
    Problem p = std::move(queue.front());
    queue.pop_front();
    detail::Touched touched;
    RepairEntry entry = attempt(b, p, tol, options, fn, touched);
    const bool ok = entry.action == "repaired";
    report.problems.push_back(std::move(entry));
    if (!ok) continue;
    for (Problem& q : detail::follow_ups(b, tol, t, touched))
      if (queued.insert(q.elements).second) queue.push_back(std::move(q));
  }
}

}  // namespace

void run_pass(Body& b, const geo::Tolerances& tol, ProblemType t, BeautifyReport& report, const BeautifyOptions& options) {
  Detection d = detect(b, tol);
  std::vector<Problem> mine;
  for (const Problem& p : d.problems)
    if (p.type == t) mine.push_back(p);
  run_queue(b, tol, t, std::move(mine), report, options);
}

BeautifyReport beautify(Body& b, const geo::Tolerances& tol, const BeautifyOptions& options) {
  using clock = std::chrono::steady_clock;
  BeautifyReport r;
  r.counts_before = b.counts();
  // One detection serves passes 1..7 (1..6 change nothing yet); passes 8..11 detect
  // afresh, since the passes before them changed the body: a fixed number of linear scans.
  auto t0 = clock::now();
  Detection first = detect(b, tol);
  const double first_detect = std::chrono::duration<double>(clock::now() - t0).count();
  r.problems_before = first.counts;
  for (ProblemType t : kAllProblemTypes) {
    auto start = clock::now();
    if (problem_order(t) <= problem_order(ProblemType::short_edge_chain)) {
      std::vector<Problem> mine;
      for (const Problem& p : first.problems)
        if (p.type == t) mine.push_back(p);
      run_queue(b, tol, t, std::move(mine), r, options);
    } else {
      run_pass(b, tol, t, r, options);
    }
    r.seconds[std::size_t(problem_order(t) - 1)] = std::chrono::duration<double>(clock::now() - start).count();
  }
  r.seconds[0] += first_detect;  // the shared detection is charged to the first pass
  r.counts_after = b.counts();
  r.problems_after = detect(b, tol).counts;
  GeometryReport g = check_geometry(b, tol.precision);
  r.max_deviation = g.max_deviation;
  r.max_elements = g.max_elements;
  return r;
}

}  // namespace kintsugi
