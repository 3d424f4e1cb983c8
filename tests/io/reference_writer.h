// The DOM-based native writer the streamed one replaced, kept as a test oracle.
#pragma once

#include "kernel/body.h"

#include <nlohmann/json.hpp>

#include <string>

namespace kintsugi::io::reference {

std::string write_native(const Body& b, const nlohmann::json& meta = nlohmann::json::object(),
                                   const std::string& units = "mm");

}  // namespace kintsugi::io::reference
