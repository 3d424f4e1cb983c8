#include "apps/report_json.h"

#include "invariants/region_validity.h"
#include "repair/detect_threads.h"
#include "invariants/topology_check.h"
#ifdef KINTSUGI_HAVE_OCCT
#include "io/occt/exchange.h"
#endif

namespace kintsugi::cli {

namespace {
nlohmann::json null_if_empty(const std::string& s) { return s.empty() ? nlohmann::json(nullptr) : nlohmann::json(s); }
}  // namespace

nlohmann::json counts_json(const Counts& c) {
  return {{"vertices", c.vertices}, {"edges", c.edges},   {"faces", c.faces},
          {"loops", c.loops},       {"shells", c.shells}, {"border_cycles", c.border_cycles}};
}

nlohmann::json violation_json(const Violation& v) {
  nlohmann::json j = {{"invariant", v.invariant}, {"elements", v.elements}, {"detail", v.detail}};
  if (v.distance != 0.0) j["distance"] = v.distance;
  return j;
}

nlohmann::json problem_counts_json(const std::array<int, 11>& counts) {
  nlohmann::json j = nlohmann::json::object();
  for (ProblemType t : kAllProblemTypes) j[problem_name(t)] = counts[std::size_t(problem_order(t) - 1)];
  return j;
}

CheckOutcome check_body(const Body& b, const geo::Tolerances& tol, [[maybe_unused]] bool with_occt) {
  CheckOutcome c;
  c.violations = check_topology(b);
  // Geometry is only meaningful on a topologically valid body (walks need closed loops).
  if (c.violations.empty()) {
    c.geometry = check_geometry(b, tol.precision, detect_threads());
    c.violations.insert(c.violations.end(), c.geometry.violations.begin(), c.geometry.violations.end());
    // Loops in each face's parameter domain: crossing themselves or each other, turning
    // the wrong way (what OpenCASCADE's checker calls self-intersecting wires and bad
    // orientation).
    std::vector<Violation> loops = loop_violations(b, whole_body(b).faces, tol);
    c.violations.insert(c.violations.end(), loops.begin(), loops.end());
  }
  c.valid = c.violations.empty();
#ifdef KINTSUGI_HAVE_OCCT
  if (with_occt) {
    io::OcctVerdict v = io::occt_check(b, tol.precision);
    c.occt = {{"valid", v.valid}, {"problems", v.problems}};
  }
#endif
  c.counts = b.counts();
  return c;
}

nlohmann::json check_json(const CheckOutcome& c, const ToleranceChoice& tol) {
  nlohmann::json j;
  j["valid"] = c.valid;
  j["counts"] = counts_json(c.counts);
  j["violations"] = nlohmann::json::array();
  for (const auto& v : c.violations) j["violations"].push_back(violation_json(v));
  j["max_deviation"] = c.geometry.max_deviation;
  j["max_deviation_elements"] = c.geometry.max_elements;
  j["precision"] = tol.tol.precision;
  j["tolerance_source"] = tol.source;
  if (!c.occt.is_null()) j["occt"] = c.occt;
  return j;
}

nlohmann::json detect_json(const Detection& d, const ToleranceChoice& tol, const std::string& units) {
  nlohmann::json j;
  j["tolerance"] = tol.tol.length;
  j["tolerance_source"] = tol.source;
  j["units"] = units;
  j["problems"] = nlohmann::json::array();
  for (const Problem& p : d.problems)
    j["problems"].push_back({{"type", problem_name(p.type)},
                             {"elements", element_names(p)},
                             {"measure", p.measure},
                             {"measure_name", measure_name(p.measure_kind)},
                             {"subcase", null_if_empty(subcase_name(p))}});
  j["counts"] = nlohmann::json::object();
  for (ProblemType t : kAllProblemTypes) j["counts"][problem_name(t)] = d.count(t);
  return j;
}

nlohmann::json suggestion_json(const ToleranceSuggestion& s) {
  auto evidence = [](const std::vector<SizeEvidence>& v) {
    nlohmann::json a = nlohmann::json::array();
    for (const SizeEvidence& e : v) a.push_back({{"what", e.what}, {"size", e.size}});
    return a;
  };
  return {{"tolerance", s.usable() ? nlohmann::json(s.tolerance) : nlohmann::json(nullptr)},
          {"confidence", s.confidence},
          {"largest_spurious", s.below},
          {"smallest_intended", s.above},
          {"gap_ratio", s.ratio},
          {"next_gap_ratio", s.next_ratio},
          {"spurious", evidence(s.spurious)},
          {"intended", evidence(s.intentional)},
          {"explanation", s.explanation}};
}

nlohmann::json beautify_json(const BeautifyReport& r, const ToleranceChoice& tol, const std::string& units,
                             const BeautifyTimes& times) {
  nlohmann::json j;
  j["tolerance"] = tol.tol.length;
  j["units"] = units;
  j["problems"] = nlohmann::json::array();
  for (const RepairEntry& p : r.problems) {
    nlohmann::json moved = nlohmann::json::array();
    for (auto [f, d] : p.surfaces_moved) moved.push_back({{"face", f.str()}, {"distance", d}});
    j["problems"].push_back({{"type", problem_name(p.problem.type)},
                             {"elements", element_names(p.problem)},
                             {"action", outcome_name(p.outcome)},
                             {"operators", p.operators},
                             {"reason", null_if_empty(p.reason)},
                             {"deviation", p.deviation},
                             {"surfaces_moved", moved},
                             {"max_residual", p.max_residual},
                             {"note", null_if_empty(p.note)}});
  }
  j["counts_before"] = counts_json(r.counts_before);
  j["counts_after"] = counts_json(r.counts_after);
  j["problems_before"] = problem_counts_json(r.problems_before);
  j["problems_after"] = problem_counts_json(r.problems_after);
  j["left"] = nlohmann::json::array();
  for (const Problem& p : r.left) j["left"].push_back({{"type", problem_name(p.type)}, {"elements", element_names(p)}});
  j["max_deviation"] = r.max_deviation;
  j["max_deviation_elements"] = r.max_elements;
  j["seconds"] = {{"read", times.read},
                  {"tolerance", times.tolerance},
                  {"beautify", times.beautify},
                  {"write", times.write},
                  {"passes", nlohmann::json::object()}};
  for (ProblemType t : kAllProblemTypes) j["seconds"]["passes"][problem_name(t)] = r.seconds[std::size_t(problem_order(t) - 1)];
  return j;
}

}  // namespace kintsugi::cli
