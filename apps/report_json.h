// JSON pieces shared by the verbs' --json outputs.
#pragma once

#include "invariants/violation.h"
#include "kernel/body.h"

#include <nlohmann/json.hpp>

namespace kintsugi::cli {

nlohmann::json counts_json(const Counts& c);
nlohmann::json violation_json(const Violation& v);

}  // namespace kintsugi::cli
