// The tolerance model (spec/tolerances.md).
//
// Two lengths, because the paper (section 3.1) needs one tolerance for *decisions*
// ("this face is small", "these edges have the same geometry") and the arithmetic
// needs a much smaller one for "this point lies on that surface":
//   length     the user's tolerance separating artefacts from intended features;
//   precision  modelling precision, length × 1e-6 by default, but never below
//              1e-12 × model size, so that it stays above floating-point noise for the
//              coordinates of a large model.
// Both scale with the model: scaling the model and the length tolerance by k scales
// both values by k, so every decision stays the same.
#pragma once

#include <algorithm>
#include <cmath>

namespace kintsugi::geo {

struct Tolerances {
  double length = 1e-3;
  double precision = 1e-9;

  // Ratio of the default precision to the length tolerance.
  static constexpr double kPrecisionRatio = 1e-6;
  // Smallest meaningful precision relative to the model size (double has ~16 digits;
  // we keep four for sums and differences of coordinates).
  static constexpr double kRelativeFloor = 1e-12;

  // `model_size` is a characteristic size of the model, e.g. its bounding-box diagonal.
  static Tolerances for_model(double length_tol, double model_size) {
    const double p = std::max(length_tol * kPrecisionRatio, kRelativeFloor * std::abs(model_size));
    return Tolerances{length_tol, p};
  }
};

}  // namespace kintsugi::geo
