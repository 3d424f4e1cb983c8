#include "apps/args.h"
#include "apps/commands.h"
#include "apps/model_files.h"
#include "apps/tolerance_choice.h"
#include "repair/detect.h"

#include <iomanip>
#include <ostream>

namespace kintsugi::cli {

namespace {
const char* kHelp =
    "usage: kintsugi detect FILE [--tol T] [--json]\n\n"
    "Finds every topological problem of the paper's eleven types with one length\n"
    "tolerance T (spec/problems.md): face_gap, edge_gap, multi_face_gap, pinched_face,\n"
    "small_face_chain, sliver_face, short_edge_chain, same_geometry_faces, small_face,\n"
    "mergeable_edges, short_edge. Read-only.\n\n"
    "  --tol T  the length tolerance, in the file's units; without it, the file's\n"
    "           meta.tolerance is used, else 1e-3 x the model size (said on stderr)\n"
    "  --json   one JSON document: {\"tolerance\", \"problems\": [{\"type\", \"elements\",\n"
    "           \"measure\", \"subcase\"}], \"counts\": {every type: n}}\n\n"
    "Exit: 0 whether or not problems were found; 2 unreadable input or bad usage.\n";
}

int cmd_detect(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err) {
  Args args;
  std::string error;
  if (!args.parse(argv, {"--tol"}, {"--json", "--help"}, &error)) {
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
  auto model = load_model(args.positional()[0], &error);
  if (!model) {
    err << "kintsugi detect: " << error << "\n";
    return kExitBadInput;
  }
  auto choice = choose_tolerance(*model, args.has("--tol") ? given : std::nullopt, &error);
  if (!choice) {
    err << "kintsugi detect: " << error << "\n";
    return kExitBadInput;
  }
  if (choice->source != "--tol")
    err << "kintsugi detect: tolerance " << choice->tol.length << " " << model->units << " from " << choice->source << "\n";
  Detection d = detect(model->body, choice->tol);
  if (args.has("--json")) {
    nlohmann::json j;
    j["tolerance"] = choice->tol.length;
    j["units"] = model->units;
    j["problems"] = nlohmann::json::array();
    for (const Problem& p : d.problems)
      j["problems"].push_back({{"type", problem_name(p.type)},
                               {"elements", element_names(p)},
                               {"measure", p.measure},
                               {"measure_name", measure_name(p.measure_kind)},
                               {"subcase", subcase_name(p).empty() ? nlohmann::json(nullptr) : nlohmann::json(subcase_name(p))}});
    j["counts"] = nlohmann::json::object();
    for (ProblemType t : kAllProblemTypes) j["counts"][problem_name(t)] = d.count(t);
    out << j.dump(2) << "\n";
    return kExitOk;
  }
  out << "tolerance " << choice->tol.length << " " << model->units << ": " << d.problems.size() << " problem(s)\n";
  for (const Problem& p : d.problems) {
    out << "  " << std::left << std::setw(20) << problem_name(p.type) << " " << measure_name(p.measure_kind) << " "
        << p.measure;
    out << "  at";
    for (const auto& e : p.elements) out << " " << element_name(e);
    if (!subcase_name(p).empty()) out << "  (" << subcase_name(p) << ")";
    out << "\n";
  }
  return kExitOk;
}

}  // namespace kintsugi::cli
