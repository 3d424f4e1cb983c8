#include "apps/args.h"
#include "apps/commands.h"
#include "apps/model_files.h"
#include "apps/report_json.h"
#include "apps/tolerance_choice.h"

#include <ostream>

namespace kintsugi::cli {

namespace {
const char* kHelp =
    "usage: kintsugi check FILE [--json] [--tol T] [--occt]\n\n"
    "Loads FILE and runs the full invariant check: twin/next/prev, closed loops, vertex\n"
    "rotations, face and shell ownership, connected shells, Euler-Poincare per shell.\n"
    "Prints the counts (vertices, edges, faces, loops, shells, border cycles) and every\n"
    "violation. Then the geometric consistency check: every vertex on its edges' curves\n"
    "and its faces' surfaces, every edge on both faces' surfaces, planar faces turning the\n"
    "right way, loops neither crossing themselves nor each other in their face's parameter\n"
    "domain and turning the right way there, within the modelling precision (1e-6 x the tolerance: --tol, else\n"
    "meta.tolerance, else 1e-3 x the model size); the largest deviation is reported with\n"
    "the elements it belongs to.\n\n"
    "  --json   one JSON document: {\"valid\", \"counts\", \"violations\", \"max_deviation\",\n"
    "           \"max_deviation_elements\", \"precision\"}\n"
    "  --tol T  the length tolerance the precision derives from\n"
    "  --occt   also convert to OpenCASCADE and report BRepCheck_Analyzer's verdict\n\n"
    "Exit: 0 valid, 1 invalid, 2 unreadable input or bad usage.\n";
}

int cmd_check(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err) {
  Args args;
  std::string error;
  if (!args.parse(argv, {"--tol"}, {"--json", "--occt", "--help"}, &error)) {
    err << "kintsugi check: " << error << "\n" << kHelp;
    return kExitBadInput;
  }
  if (args.has("--help")) {
    out << kHelp;
    return kExitOk;
  }
  if (args.positional().size() != 1) {
    err << "kintsugi check: expected one FILE\n" << kHelp;
    return kExitBadInput;
  }
  const std::string& path = args.positional()[0];
#ifndef KINTSUGI_HAVE_OCCT
  if (args.has("--occt")) {
    err << "kintsugi check: this build has no OpenCASCADE, so --occt is not available\n";
    return kExitBadInput;
  }
#endif
  auto model = load_model(path, &error);
  if (!model) {
    err << "kintsugi check: " << error << "\n";
    return kExitBadInput;
  }
  auto given = args.number("--tol", 0, &error);
  if (!given || (args.has("--tol") && *given <= 0)) {
    err << "kintsugi check: " << (error.empty() ? "--tol must be positive" : error) << "\n";
    return kExitBadInput;
  }
  auto choice = choose_tolerance(*model, args.has("--tol") ? given : std::nullopt, &error);
  if (!choice) {
    err << "kintsugi check: " << error << "\n";
    return kExitBadInput;
  }
  CheckOutcome c = check_body(model->body, choice->tol, args.has("--occt"));
  const bool valid = c.valid;
  const GeometryReport& geometry = c.geometry;
  const auto& violations = c.violations;
  const nlohmann::json& occt = c.occt;
  if (args.has("--json")) {
    out << check_json(c, *choice).dump(2) << "\n";
  } else {
    out << path << ": " << (valid ? "valid" : "INVALID") << "\n"
        << "  vertices " << c.counts.vertices << ", edges " << c.counts.edges << ", faces " << c.counts.faces
        << ", loops " << c.counts.loops << ", shells " << c.counts.shells << ", border cycles " << c.counts.border_cycles << "\n";
    out << "  largest geometric deviation " << geometry.max_deviation;
    for (const auto& e : geometry.max_elements) out << " " << e;
    out << " (precision " << choice->tol.precision << ", from " << choice->source << ")\n";
    for (const auto& v : violations) out << "  violation: " << to_string(v) << "\n";
    if (!occt.is_null()) {
      out << "  OpenCASCADE BRepCheck: " << (occt["valid"].get<bool>() ? "valid" : "INVALID") << "\n";
      for (const auto& p : occt["problems"]) out << "    " << p.get<std::string>() << "\n";
    }
  }
  return valid ? kExitOk : kExitInvalid;
}

}  // namespace kintsugi::cli
