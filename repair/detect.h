// Detection: the first half of the paper's algorithm. With one length tolerance, find
// every problem of the eleven types (spec/problems.md) and say where it is. Read-only,
// linear in the model for bounded face degree (paper section 5): each face is measured
// once, pinching compares edge pairs within a face, chains are found by walks over
// flagged elements only.
#pragma once

#include "geometry/tolerance.h"
#include "kernel/body.h"
#include "repair/problem.h"

#include <array>
#include <vector>

namespace kintsugi {

struct Detection {
  std::vector<Problem> problems;  // in the paper's order of types
  std::array<int, 11> counts{};   // indexed by problem_order(type) - 1

  int count(ProblemType t) const { return counts[std::size_t(problem_order(t) - 1)]; }
};

Detection detect(const Body& b, const geo::Tolerances& tol);

}  // namespace kintsugi
