#include "apps/api.h"
#include "apps/args.h"
#include "apps/commands.h"

#include <iomanip>
#include <ostream>

namespace kintsugi::cli {

namespace {
const char* kHelp =
    "usage: kintsugi detect FILE [--tol T] [--json] [--suggest-tol]\n\n"
    "Finds every topological problem of the paper's eleven types with one length\n"
    "tolerance T (spec/problems.md): face_gap, edge_gap, multi_face_gap, pinched_face,\n"
    "small_face_chain, sliver_face, short_edge_chain, same_geometry_faces, small_face,\n"
    "mergeable_edges, short_edge. Read-only.\n\n"
    "  --tol T  the length tolerance, in the file's units; without it, the file's\n"
    "           meta.tolerance is used, else the tolerance the model suggests when its\n"
    "           confidence is high (see --suggest-tol), else 1e-3 x the model size\n"
    "           (said on stderr); refused\n"
    "           (exit 2) at or above the model size, or below 1e-6 of it\n"
    "  --suggest-tol  report the tolerance the model suggests: a gap between the sizes\n"
    "           of spurious and of intended features (edge lengths, face widths, pinch\n"
    "           distances, surface deviations), with the sizes either side and a\n"
    "           confidence (high, medium, low, none, no defects); then detect with it\n"
    "           when high or no defects (unless --tol is given)\n"
    "  --json   one JSON document: {\"tolerance\", \"problems\": [{\"type\", \"elements\",\n"
    "           \"measure\", \"subcase\"}], \"counts\": {every type: n}}\n\n"
    "Environment: KINTSUGI_THREADS=N (1-64) threads for reading a large .json model (two at\n"
    "most) and for measuring faces and edges in the whole-model detection (default: the\n"
    "machine's, at most 8); the result is the same for any N.\n"
    "Exit: 0 whether or not problems were found; 2 unreadable input or bad usage.\n";
}

int cmd_detect(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err) {
  Args args;
  std::string error;
  if (!args.parse(argv, {"--tol"}, {"--json", "--help", "--suggest-tol"}, &error)) {
    err << "kintsugi detect: " << error << "\n" << kHelp;
    return kExitBadInput;
  }
  if (args.has("--help")) {
    out << kHelp;
    return kExitOk;
  }
  if (args.positional().size() != 1) {
    err << "kintsugi detect: expected one FILE\n" << kHelp;
    return kExitBadInput;
  }
  auto given = args.number("--tol", 0, &error);
  if (!given || (args.has("--tol") && *given <= 0)) {
    err << "kintsugi detect: " << (error.empty() ? "--tol must be a positive number" : error) << "\n";
    return kExitBadInput;
  }
  std::string note;
  nlohmann::json j;
  try {
    j = api::detect(api::read_model(args.positional()[0]), args.has("--tol") ? given : std::nullopt, &note,
                    args.has("--suggest-tol"));
  } catch (const api::Error& e) {
    err << "kintsugi detect: " << e.what() << "\n";
    return kExitBadInput;
  }
  if (!note.empty()) err << "kintsugi detect: " << note << "\n";
  if (args.has("--json")) {
    out << j.dump(2) << "\n";
    return kExitOk;
  }
  if (j.contains("suggested_tolerance")) {
    const auto& s = j["suggested_tolerance"];
    out << "suggested tolerance: ";
    if (s["tolerance"].is_null())
      out << "none (no clear gap)\n";
    else
      out << s["tolerance"].get<double>() << " " << j["units"].get<std::string>() << " (confidence "
          << s["confidence"].get<std::string>() << ")\n";
    out << "  " << s["explanation"].get<std::string>() << "\n";
    for (const auto& e : s["spurious"]) out << "  spurious  " << e["size"].get<double>() << "  " << e["what"].get<std::string>() << "\n";
    for (const auto& e : s["intended"]) out << "  intended  " << e["size"].get<double>() << "  " << e["what"].get<std::string>() << "\n";
  }
  out << "tolerance " << j["tolerance"].get<double>() << " " << j["units"].get<std::string>() << ": "
      << j["problems"].size() << " problem(s)\n";
  for (const auto& p : j["problems"]) {
    out << "  " << std::left << std::setw(20) << p["type"].get<std::string>() << " "
        << p["measure_name"].get<std::string>() << " " << p["measure"].get<double>();
    out << "  at";
    for (const auto& e : p["elements"]) out << " " << e.get<std::string>();
    if (!p["subcase"].is_null()) out << "  (" << p["subcase"].get<std::string>() << ")";
    out << "\n";
  }
  return kExitOk;
}

}  // namespace kintsugi::cli
