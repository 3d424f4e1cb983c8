#include "apps/tolerance_choice.h"

#include "invariants/element_geometry.h"
#include "repair/suggest_tolerance.h"

#include <cmath>
#include <sstream>

namespace kintsugi::cli {

namespace {

std::string num(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

// The bounds of kMinToleranceRatio / kMaxToleranceRatio, for a model of `size`.
std::optional<ToleranceChoice> within_bounds(ToleranceChoice c, double size, const std::string& units,
                                             std::string* error) {
  if (!(size > 0)) return c;  // an empty model: nothing to decide
  const double t = c.tol.length;
  const std::string from = c.source == "--tol" ? "--tol " + num(t) : num(t) + " (" + c.source + ")";
  if (t >= kMaxToleranceRatio * size) {
    *error = "the tolerance " + from + " " + units + " is not smaller than the model itself (size " + num(size) + " " +
             units + "): every feature would be a defect and the repairs would collapse the model; give a tolerance "
             "well below the size (the default is 1e-3 x size = " + num(1e-3 * size) + ")";
    return std::nullopt;
  }
  if (t < kMinToleranceRatio * size) {
    *error = "the tolerance " + from + " " + units + " is below a millionth of the model's size (" + num(size) + " " +
             units + "): nothing can be decided at that scale; give at least " + num(kMinToleranceRatio * size) +
             " (the default is 1e-3 x size = " + num(1e-3 * size) + ")";
    return std::nullopt;
  }
  return c;
}

}  // namespace

std::optional<ToleranceChoice> choose_tolerance(const Model& m, std::optional<double> given, std::string* error,
                                                bool suggest) {
  double size = model_size(m.body);
  if (given) return within_bounds({geo::Tolerances::for_model(*given, size), "--tol", true, std::nullopt}, size, m.units, error);
  if (m.meta.is_object() && m.meta.contains("tolerance")) {
    const auto& t = m.meta["tolerance"];
    if (!t.is_number() || !std::isfinite(t.get<double>()) || t.get<double>() <= 0) {
      *error = "meta.tolerance must be a positive number";
      return std::nullopt;
    }
    return within_bounds({geo::Tolerances::for_model(t.get<double>(), size), "meta.tolerance", true, std::nullopt}, size, m.units, error);
  }
  if (suggest) {
    ToleranceSuggestion s = suggest_tolerance(m.body);
    if (s.trusted())
      return ToleranceChoice{geo::Tolerances::for_model(s.tolerance, size),
                             "the model's own suggestion (confidence " + s.confidence + ": " + s.explanation + ")", true, s};
    return ToleranceChoice{geo::Tolerances::default_for_model(size),
                           "default (1e-3 x model size), not trusted: the model suggests no tolerance to trust (confidence " + s.confidence + ": " + s.explanation + ")",
                           false, s};
  }
  return ToleranceChoice{geo::Tolerances::default_for_model(size), "default (1e-3 x model size)", true, std::nullopt};
}

}  // namespace kintsugi::cli
