// The report's "left" list against a fresh whole-body detection of beautify's output:
// the local re-detection between passes must miss nothing and invent nothing (issue 12;
// spec/problems.md, "Detecting near a repair"). Used by the pipeline tests and by the
// third-party STEP parts' test.
#pragma once

#include "repair/beautify.h"
#include "repair/detect.h"

#include <algorithm>
#include <string>
#include <vector>

namespace kintsugi::test {

// Each problem as "type element element ...", sorted: identity, not counts.
inline std::vector<std::string> identities(const std::vector<Problem>& ps) {
  std::vector<std::string> out;
  for (const Problem& p : ps) {
    std::string s = problem_name(p.type);
    for (const std::string& e : element_names(p)) s += " " + e;
    out.push_back(s);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// "" when the report's left list is exactly what detect() finds on `b` (the output) and
// every problem reported "not repaired" is among them; otherwise what differs.
inline std::string left_mismatch(const Body& b, const geo::Tolerances& tol, const BeautifyReport& r) {
  const auto want = identities(detect(b, tol).problems);
  const auto got = identities(r.left);
  auto joined = [](const std::vector<std::string>& v) {
    std::string s;
    for (const auto& x : v) s += "  " + x + "\n";
    return s;
  };
  if (want != got) return "detect() on the output:\n" + joined(want) + "report's left:\n" + joined(got);
  // Every entry reported "not repaired" names a problem the output still has (a refused
  // problem a later repair removed is "resolved by a later repair").
  for (const RepairEntry& e : r.problems)
    if (e.left() && !std::binary_search(want.begin(), want.end(), identities({e.problem})[0]))
      return "reported not repaired, but the output does not have it: " + identities({e.problem})[0] + " (" +
             e.reason + ")";
  return "";
}

}  // namespace kintsugi::test
