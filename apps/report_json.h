// The JSON documents the verbs print (check --json, detect --json, beautify --report) and
// the pieces they share. Built here once, so the CLI, `kintsugi batch` and the Python
// package (through apps/api.h) give the same document byte for byte.
#pragma once

#include "apps/tolerance_choice.h"
#include "invariants/geometry_check.h"
#include "invariants/violation.h"
#include "kernel/body.h"
#include "repair/beautify.h"
#include "repair/detect.h"
#include "repair/suggest_tolerance.h"

#include <nlohmann/json.hpp>

#include <array>
#include <string>
#include <vector>

namespace kintsugi::cli {

nlohmann::json counts_json(const Counts& c);
nlohmann::json violation_json(const Violation& v);
// {type name: n} for all eleven types, from counts indexed by problem_order(type) - 1.
nlohmann::json problem_counts_json(const std::array<int, 11>& counts);

// What `check` finds: the topology check, then (on a topologically valid body) the
// geometric one, and OpenCASCADE's verdict when asked for.
struct CheckOutcome {
  bool valid = true;
  Counts counts;
  std::vector<Violation> violations;
  GeometryReport geometry;
  nlohmann::json occt;  // null unless asked for: {"valid", "problems"}
};
CheckOutcome check_body(const Body& b, const geo::Tolerances& tol, bool with_occt);
nlohmann::json check_json(const CheckOutcome& c, const ToleranceChoice& tol);

nlohmann::json detect_json(const Detection& d, const ToleranceChoice& tol, const std::string& units);

// detect --suggest-tol's "suggested_tolerance": {"tolerance" (null when none), "confidence",
// "largest_spurious", "smallest_intended", "gap_ratio", "next_gap_ratio", "spurious",
// "intended" ([{"what", "size"}]), "explanation"}.
nlohmann::json suggestion_json(const ToleranceSuggestion& s);

// Wall-clock seconds of a beautify run's steps; read and write are 0 when the model did
// not come from or go to a file in that run.
struct BeautifyTimes {
  // tolerance: choosing the tolerance (the model's suggestion, when no --tol or
  // meta.tolerance is given: it measures every face).
  double read = 0.0, tolerance = 0.0, beautify = 0.0, write = 0.0;
};
nlohmann::json beautify_json(const BeautifyReport& r, const ToleranceChoice& tol, const std::string& units,
                             const BeautifyTimes& times);

}  // namespace kintsugi::cli
