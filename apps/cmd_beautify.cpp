#include "apps/args.h"
#include "apps/commands.h"
#include "apps/model_files.h"
#include "apps/report_json.h"
#include "apps/report_page.h"
#include "apps/tolerance_choice.h"
#include "repair/beautify.h"
#include "repair/pass.h"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <ostream>

namespace kintsugi::cli {

namespace {
// The passes this build has, from the registry.
std::string pass_list() {
  std::string s, missing;
  for (ProblemType t : kAllProblemTypes) {
    if (const Pass* p = find_pass(t))
      s += "  " + std::to_string(problem_order(t)) + ". " + p->title + ": " + p->summary + "\n";
    else
      missing += (missing.empty() ? "" : ", ") + std::string(problem_name(t));
  }
  if (!missing.empty()) s += "No pass yet (found, reported as not repaired): " + missing + ".\n";
  return s;
}

const std::string kHelp =
    "usage: kintsugi beautify IN [--tol T] -o OUT [--report R.json] [--html PAGE.html] [--png FILE]\n\n"
    "Repairs the topology of the model in IN (paper Figure 13, spec/beautify.md): the\n"
    "problems detect finds are repaired pass by pass in the paper's order:\n" +
    pass_list() +
    "A repair that cannot complete is rolled back and reported with its reason. OUT is\n"
    "written atomically, never over IN.\n\n"
    "  --tol T          the length tolerance (else meta.tolerance, else 1e-3 x model size)\n"
    "  -o OUT           the repaired model\n"
    "  --report R.json  {\"tolerance\", \"problems\": [{\"type\", \"elements\", \"action\",\n"
    "                   \"operators\", \"reason\", \"deviation\", \"note\"}], \"counts_before\",\n"
    "                   \"counts_after\", \"problems_before\", \"problems_after\",\n"
    "                   \"left\": [{\"type\", \"elements\"}] (what the output still has),\n"
    "                   \"max_deviation\", \"seconds\": {\"read\", \"beautify\", \"write\",\n"
    "                   \"passes\": {type: s}}}\n"
    "  --html PAGE.html the model before and after side by side, cameras linked, each\n"
    "                   problem marked and listed with what was done and the operators\n"
    "  --png FILE       a still picture of that page (needs Chromium installed: Debian's\n"
    "                   chromium, or the browser named in KINTSUGI_CHROMIUM)\n\n"
    "Exit: 0 written (whether or not every problem was repaired); 2 bad input or usage.\n";

nlohmann::json problem_counts(const std::array<int, 11>& c) {
  nlohmann::json j = nlohmann::json::object();
  for (ProblemType t : kAllProblemTypes) j[problem_name(t)] = c[std::size_t(problem_order(t) - 1)];
  return j;
}
}  // namespace

int cmd_beautify(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err) {
  using clock = std::chrono::steady_clock;
  auto secs = [](clock::time_point a) { return std::chrono::duration<double>(clock::now() - a).count(); };
  Args args;
  std::string error;
  if (!args.parse(argv, {"--tol", "-o", "--report", "--html", "--png"}, {"--help"}, &error)) {
    err << "kintsugi beautify: " << error << "\n" << kHelp;
    return kExitBadInput;
  }
  if (args.has("--help")) {
    out << kHelp;
    return kExitOk;
  }
  if (args.positional().size() != 1 || !args.has("-o")) {
    err << "kintsugi beautify: expected IN and -o OUT\n" << kHelp;
    return kExitBadInput;
  }
  auto given = args.number("--tol", 0, &error);
  if (!given || (args.has("--tol") && *given <= 0)) {
    err << "kintsugi beautify: " << (error.empty() ? "--tol must be a positive number" : error) << "\n";
    return kExitBadInput;
  }
  const std::string in = args.positional()[0], out_path = *args.value("-o");
  auto t_read = clock::now();
  auto model = load_model(in, &error);
  if (!model) {
    err << "kintsugi beautify: " << error << "\n";
    return kExitBadInput;
  }
  const double read_s = secs(t_read);
  auto choice = choose_tolerance(*model, args.has("--tol") ? given : std::nullopt, &error);
  if (!choice) {
    err << "kintsugi beautify: " << error << "\n";
    return kExitBadInput;
  }
  if (choice->source != "--tol")
    err << "kintsugi beautify: tolerance " << choice->tol.length << " " << model->units << " from " << choice->source << "\n";
  const bool page = args.has("--html") || args.has("--png");
  const Body before = page ? model->body.clone() : Body();
  auto t_fix = clock::now();
  BeautifyReport r = beautify(model->body, choice->tol);
  const double fix_s = secs(t_fix);
  model->meta["tolerance"] = choice->tol.length;
  model->meta.erase("defects");  // the injector's record no longer describes the model
  auto t_write = clock::now();
  if (!save_model(*model, out_path, in, &error)) {
    err << "kintsugi beautify: " << error << "\n";
    return kExitBadInput;
  }
  const double write_s = secs(t_write);
  if (args.has("--report")) {
    nlohmann::json j;
    j["tolerance"] = choice->tol.length;
    j["units"] = model->units;
    j["problems"] = nlohmann::json::array();
    for (const RepairEntry& p : r.problems)
      j["problems"].push_back({{"type", problem_name(p.problem.type)},
                               {"elements", element_names(p.problem)},
                               {"action", outcome_name(p.outcome)},
                               {"operators", p.operators},
                               {"reason", p.reason.empty() ? nlohmann::json(nullptr) : nlohmann::json(p.reason)},
                               {"deviation", p.deviation},
                               {"note", p.note.empty() ? nlohmann::json(nullptr) : nlohmann::json(p.note)}});
    j["counts_before"] = counts_json(r.counts_before);
    j["counts_after"] = counts_json(r.counts_after);
    j["problems_before"] = problem_counts(r.problems_before);
    j["problems_after"] = problem_counts(r.problems_after);
    j["left"] = nlohmann::json::array();
    for (const Problem& p : r.left) j["left"].push_back({{"type", problem_name(p.type)}, {"elements", element_names(p)}});
    j["max_deviation"] = r.max_deviation;
    j["max_deviation_elements"] = r.max_elements;
    j["seconds"] = {{"read", read_s}, {"beautify", fix_s}, {"write", write_s}, {"passes", nlohmann::json::object()}};
    for (ProblemType t : kAllProblemTypes) j["seconds"]["passes"][problem_name(t)] = r.seconds[std::size_t(problem_order(t) - 1)];
    const std::string rp = *args.value("--report");
    if (rp == in) {
      err << "kintsugi beautify: the report would overwrite the input\n";
      return kExitBadInput;
    }
    std::ofstream f(rp);
    f << j.dump(2) << "\n";
    if (!f) {
      err << "kintsugi beautify: cannot write " << rp << "\n";
      return kExitBadInput;
    }
  }
  if (page && !write_report_page(page_from_beautify(before, model->body, std::filesystem::path(in).filename().string(),
                                                    model->units, choice->tol, r),
                                 {args.value("--html"), args.value("--png")}, in, &error)) {
    err << "kintsugi beautify: " << error << "\n";
    return kExitBadInput;
  }
  out << "tolerance " << choice->tol.length << " " << model->units << ": " << r.repaired() << " repaired, "
      << r.not_repaired() << " not repaired; faces " << r.counts_before.faces << " -> " << r.counts_after.faces
      << ", edges " << r.counts_before.edges << " -> " << r.counts_after.edges << "; max deviation " << r.max_deviation
      << "\n";
  for (const RepairEntry& p : r.problems)
    if (p.left() || !p.note.empty()) {
      out << (p.left() ? "  not repaired: " : "  repaired: ") << problem_name(p.problem.type) << " at";
      for (const auto& e : p.problem.elements) out << " " << element_name(e);
      out << ": " << (p.left() ? p.reason : p.note) << "\n";
    }
  return kExitOk;
}

}  // namespace kintsugi::cli
