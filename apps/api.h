// kintsugi's stable entry points for programs that use it as a library: the Python
// package (python/) and other C++ projects (examples/consumer/). Each returns the same
// JSON document the matching verb prints (check --json, detect --json, beautify
// --report), built by the same code (apps/report_json.h), so a script can switch between
// the CLI and the library without a difference. The internal report structs may change;
// these signatures and documents are what callers rely on.
//
// Errors (unreadable file, bad tolerance, unwritable output) throw api::Error whose
// message is the one the CLI prints after "kintsugi VERB: ".
#pragma once

#include "apps/model_files.h"
#include "repair/beautify.h"

#include <nlohmann/json.hpp>

#include <optional>
#include <stdexcept>
#include <string>

namespace kintsugi::api {

using Model = cli::Model;  // body, meta, units, format

struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// .json (native), .step/.stp and .brep (when built with OpenCASCADE), by extension.
Model read_model(const std::string& path);
// Atomic; never over `input` (the file the model came from, if any).
void write_model(const Model& model, const std::string& path, const std::string& input = "");

// `tol`: the length tolerance; without it the model's meta.tolerance, else (detect and
// beautify) the tolerance the model suggests (repair/suggest_tolerance.h), else 1e-3 x the
// model size (check: directly). `tolerance_note`, when given, is set to what the CLI says
// on stderr about where the tolerance came from ("" when `tol` was given). When the model
// suggests no tolerance to trust (ToleranceSuggestion::trusted), beautify repairs nothing
// and says so in the note.
nlohmann::json check(const Model& model, std::optional<double> tol = std::nullopt, bool with_occt = false);
// `with_suggestion`: the document also holds "suggested_tolerance" (detect --suggest-tol).
nlohmann::json detect(const Model& model, std::optional<double> tol = std::nullopt,
                      std::string* tolerance_note = nullptr, bool with_suggestion = false);

struct BeautifyOptions {
  // The whole-body topology check after every repair (the CLI's --paranoid), for
  // debugging: quadratic in the model. Without it each repair is checked where it acted
  // (its operators' contracts, the validity gate on its region) and the whole body once,
  // at the end; should that find anything (a bug), the run is undone and repeated with
  // this on, so that the repair that breaks the body is refused and named.
  bool check_topology_each_repair = false;
};
// Repairs `model` in place (meta.tolerance set to the tolerance used, meta.defects
// dropped: the injector's record no longer describes it) and returns the report.
nlohmann::json beautify(Model& model, std::optional<double> tol = std::nullopt, const BeautifyOptions& options = {},
                        std::string* tolerance_note = nullptr);
// What a caller that draws the run (the CLI's --html page) needs besides the document:
// the body before and after the repair, the pipeline's own report (its handles name
// elements of `after`) and the tolerance used.
struct BeautifyDetail {
  Body before, after;
  BeautifyReport report;
  geo::Tolerances tol;
};
// Read, beautify, write, as `kintsugi beautify IN -o OUT --report`: the report's
// seconds include the read and the write. `detail`, when given, is filled.
nlohmann::json beautify_file(const std::string& in, const std::string& out, std::optional<double> tol = std::nullopt,
                             const BeautifyOptions& options = {}, std::string* tolerance_note = nullptr,
                             BeautifyDetail* detail = nullptr);

// How many of a beautify report's problems were repaired / not repaired (refused or no
// pass yet; "resolved by an earlier repair" is neither).
int repaired_count(const nlohmann::json& report);
int not_repaired_count(const nlohmann::json& report);

}  // namespace kintsugi::api
