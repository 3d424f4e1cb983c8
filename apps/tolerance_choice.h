// Which length tolerance a verb uses: --tol if given, else the model's meta.tolerance,
// else a default relative to the model's size. The choice is said, never silent.
#pragma once

#include "apps/model_files.h"
#include "geometry/tolerance.h"

#include <optional>
#include <string>

namespace kintsugi::cli {

struct ToleranceChoice {
  geo::Tolerances tol;
  std::string source;  // "--tol", "meta.tolerance", or "default (1e-3 x model size)"
};

// `given` is the parsed --tol (already checked positive and finite) or nullopt.
// Returns nullopt and sets *error when meta.tolerance is present but not a positive number.
std::optional<ToleranceChoice> choose_tolerance(const Model& m, std::optional<double> given, std::string* error);

}  // namespace kintsugi::cli
