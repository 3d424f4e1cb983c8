#include "apps/args.h"
#include "apps/commands.h"
#include "apps/model_files.h"
#include "apps/report_json.h"
#include "invariants/topology_check.h"
#ifdef KINTSUGI_HAVE_OCCT
#include "io/occt/exchange.h"
#endif

#include <ostream>

namespace kintsugi::cli {

namespace {
const char* kHelp =
    "usage: kintsugi check FILE [--json] [--occt]\n\n"
    "Loads FILE and runs the full invariant check: twin/next/prev, closed loops, vertex\n"
    "rotations, face and shell ownership, connected shells, Euler-Poincare per shell.\n"
    "Prints the counts (vertices, edges, faces, loops, shells, border cycles) and every\n"
    "violation.\n\n"
    "  --json   one JSON document: {\"valid\", \"counts\", \"violations\"}\n"
    "  --occt   also convert to OpenCASCADE and report BRepCheck_Analyzer's verdict\n\n"
    "Exit: 0 valid, 1 invalid, 2 unreadable input or bad usage.\n";
}

int cmd_check(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err) {
  Args args;
  std::string error;
  if (!args.parse(argv, {}, {"--json", "--occt", "--help"}, &error)) {
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
  const Body& b = model->body;
  std::vector<Violation> violations = check_topology(b);
  bool valid = violations.empty();
  nlohmann::json occt;
#ifdef KINTSUGI_HAVE_OCCT
  if (args.has("--occt")) {
    io::OcctVerdict v = io::occt_check(b);
    occt = {{"valid", v.valid}, {"problems", v.problems}};
  }
#endif
  Counts c = b.counts();
  if (args.has("--json")) {
    nlohmann::json j;
    j["valid"] = valid;
    j["counts"] = counts_json(c);
    j["violations"] = nlohmann::json::array();
    for (const auto& v : violations) j["violations"].push_back(violation_json(v));
    if (!occt.is_null()) j["occt"] = occt;
    out << j.dump(2) << "\n";
  } else {
    out << path << ": " << (valid ? "valid" : "INVALID") << "\n"
        << "  vertices " << c.vertices << ", edges " << c.edges << ", faces " << c.faces << ", loops " << c.loops
        << ", shells " << c.shells << ", border cycles " << c.border_cycles << "\n";
    for (const auto& v : violations) out << "  violation: " << to_string(v) << "\n";
    if (!occt.is_null()) {
      out << "  OpenCASCADE BRepCheck: " << (occt["valid"].get<bool>() ? "valid" : "INVALID") << "\n";
      for (const auto& p : occt["problems"]) out << "    " << p.get<std::string>() << "\n";
    }
  }
  return valid ? kExitOk : kExitInvalid;
}

}  // namespace kintsugi::cli
