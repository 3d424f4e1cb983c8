// Reading and writing models in every format, chosen by file extension:
//   .json (native), .step / .stp (STEP), .brep (OpenCASCADE). Outputs are written
// atomically and never over the input file.
#pragma once

#include "kernel/body.h"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>

namespace kintsugi::cli {

struct Model {
  Body body;
  nlohmann::json meta = nlohmann::json::object();
  std::string units = "mm";
  std::string format;  // "json", "step", "brep"
};

std::optional<Model> load_model(const std::string& path, std::string* error);
// `input` (may be empty) is the file the model was read from: it is never overwritten.
bool save_model(const Model& m, const std::string& path, const std::string& input, std::string* error);
// Which formats this build reads and writes, for --help.
std::string formats_supported();

}  // namespace kintsugi::cli
