#include "apps/tolerance_choice.h"

#include "invariants/element_geometry.h"

#include <cmath>

namespace kintsugi::cli {

std::optional<ToleranceChoice> choose_tolerance(const Model& m, std::optional<double> given, std::string* error) {
  double size = model_size(m.body);
  if (given) return ToleranceChoice{geo::Tolerances::for_model(*given, size), "--tol"};
  if (m.meta.is_object() && m.meta.contains("tolerance")) {
    const auto& t = m.meta["tolerance"];
    if (!t.is_number() || !std::isfinite(t.get<double>()) || t.get<double>() <= 0) {
      *error = "meta.tolerance must be a positive number";
      return std::nullopt;
    }
    return ToleranceChoice{geo::Tolerances::for_model(t.get<double>(), size), "meta.tolerance"};
  }
  return ToleranceChoice{geo::Tolerances::default_for_model(size), "default (1e-3 x model size)"};
}

}  // namespace kintsugi::cli
