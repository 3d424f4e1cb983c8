// Which length tolerance a verb uses: --tol if given, else the model's meta.tolerance,
// else a default relative to the model's size. The choice is said, never silent.
#pragma once

#include "apps/model_files.h"
#include "geometry/tolerance.h"
#include "repair/suggest_tolerance.h"

#include <optional>
#include <string>

namespace kintsugi::cli {

struct ToleranceChoice {
  geo::Tolerances tol;
  std::string source;  // "--tol", "meta.tolerance", "suggested by the model (...)", or "default (1e-3 x model size)"
  // False when the tolerance is only the size default because the model suggests none
  // (no clear gap between spurious and intended features): nothing destructive may use it.
  bool trusted = true;
  // The model's suggestion, when choosing asked for it (kept so that a caller reporting
  // it does not compute it twice: on a large model it is the longest part of detect).
  std::optional<ToleranceSuggestion> suggestion;
};

// A tolerance must lie between these fractions of the model's size (model_size). At or
// above the size every feature of the model would be a defect, and repairs would collapse
// it; below a millionth of it, decisions are made at a scale where the measures (sampled
// within a thousandth of the tolerance) cost millions of points per curve and double
// precision decides nothing (a tolerance of 1e-12 kept beautify of paper object 10 busy
// for over ten minutes). No scanner comes near either bound.
constexpr double kMinToleranceRatio = 1e-6;
constexpr double kMaxToleranceRatio = 1.0;

// `given` is the parsed --tol (already checked positive and finite) or nullopt.
// Returns nullopt and sets *error when meta.tolerance is present but not a positive
// number, or when the tolerance is outside the bounds above (the message names both the
// tolerance and the model's size, and what to give instead).
// With `suggest`, a model without --tol or meta.tolerance gets the tolerance it suggests
// (repair/suggest_tolerance.h); when it suggests none, the default, not trusted.
std::optional<ToleranceChoice> choose_tolerance(const Model& m, std::optional<double> given, std::string* error,
                                                bool suggest = false);

}  // namespace kintsugi::cli
