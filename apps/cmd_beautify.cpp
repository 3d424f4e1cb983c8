#include "apps/api.h"
#include "apps/args.h"
#include "apps/commands.h"
#include "apps/report_page.h"
#include "repair/pass.h"

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
    "usage: kintsugi beautify IN [--tol T] -o OUT [--report R.json] [--html PAGE.html] [--png FILE]\n"
    "                        [--paranoid]\n\n"
    "Repairs the topology of the model in IN (paper Figure 13, spec/beautify.md): the\n"
    "problems detect finds are repaired pass by pass in the paper's order:\n" +
    pass_list() +
    "A repair that cannot complete is rolled back and reported with its reason. Each\n"
    "repair is checked where it acted, the whole model once at the end. OUT is written\n"
    "atomically, never over IN.\n\n"
    "  --tol T          the length tolerance (else meta.tolerance, else the tolerance the\n"
    "                   model suggests, as kintsugi detect --suggest-tol reports it, when\n"
    "                   its confidence is high; otherwise nothing is repaired and OUT is\n"
    "                   IN unchanged);\n"
    "                   refused (exit 2) at or above the model size, or below 1e-6 of it\n"
    "  -o OUT           the repaired model\n"
    "  --report R.json  {\"tolerance\", \"problems\": [{\"type\", \"elements\", \"action\",\n"
    "                   \"operators\", \"reason\", \"deviation\", \"note\"}], \"counts_before\",\n"
    "                   \"counts_after\", \"problems_before\", \"problems_after\",\n"
    "                   \"left\": [{\"type\", \"elements\"}] (what the output still has),\n"
    "                   \"max_deviation\", \"seconds\": {\"read\", \"tolerance\", \"beautify\",\n"
    "                   \"write\", \"passes\": {type: s}}}\n"
    "  --html PAGE.html the model before and after side by side, cameras linked, each\n"
    "                   problem marked and listed with what was done and the operators\n"
    "  --png FILE       a still picture of that page (needs Chromium installed: Debian's\n"
    "                   chromium, or the browser named in KINTSUGI_CHROMIUM)\n"
    "  --paranoid       also check the whole model's topology after every repair (for\n"
    "                   debugging; quadratic in the model's size)\n\n"
    "Environment: KINTSUGI_THREADS=N (1-64) threads for reading a large .json model (two at\n"
    "most) and for measuring faces and edges in the whole-model detection (default: the\n"
    "machine's, at most 8); the result is the same for any N.\n"
    "Exit: 0 written (whether or not every problem was repaired); 2 bad input or usage.\n";

}  // namespace

int cmd_beautify(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err) {
  Args args;
  std::string error;
  if (!args.parse(argv, {"--tol", "-o", "--report", "--html", "--png"}, {"--help", "--paranoid"}, &error)) {
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
  if (auto bad = args.bad_output({"-o", "--report", "--html", "--png"}, args.positional()[0])) {
    err << "kintsugi beautify: " << *bad << "\n";
    return kExitBadInput;
  }
  const std::string in = args.positional()[0], out_path = *args.value("-o");
  const bool page = args.has("--html") || args.has("--png");
  std::string note;
  nlohmann::json j;
  api::BeautifyDetail detail;  // filled only for the page, which draws before and after
  try {
    api::BeautifyOptions options;
    options.check_topology_each_repair = args.has("--paranoid");
    j = api::beautify_file(in, out_path, args.has("--tol") ? given : std::nullopt, options, &note,
                           page ? &detail : nullptr);
  } catch (const api::Error& e) {
    err << "kintsugi beautify: " << e.what() << "\n";
    return kExitBadInput;
  }
  if (!note.empty()) err << "kintsugi beautify: " << note << "\n";
  if (args.has("--report")) {
    const std::string rp = *args.value("--report");
    std::ofstream f(rp);
    f << j.dump(2) << "\n";
    if (!f) {
      err << "kintsugi beautify: cannot write " << rp << "\n";
      return kExitBadInput;
    }
  }
  if (page) {
    if (!write_report_page(page_from_beautify(detail.before, detail.after, std::filesystem::path(in).filename().string(),
                                              j["units"].get<std::string>(), detail.tol, detail.report),
                           {args.value("--html"), args.value("--png")}, in, &error)) {
      err << "kintsugi beautify: " << error << "\n";
      return kExitBadInput;
    }
  }
  // The summary is read from the report, so it says exactly what the report says.
  out << "tolerance " << j["tolerance"].get<double>() << " " << j["units"].get<std::string>() << ": "
      << api::repaired_count(j) << " repaired, " << api::not_repaired_count(j) << " not repaired; faces "
      << j["counts_before"]["faces"] << " -> " << j["counts_after"]["faces"] << ", edges "
      << j["counts_before"]["edges"] << " -> " << j["counts_after"]["edges"] << "; max deviation "
      << j["max_deviation"].get<double>() << "\n";
  for (const auto& p : j["problems"])
    if (p["action"] == "not repaired" || !p["note"].is_null()) {
      const bool left = p["action"] == "not repaired";
      out << (left ? "  not repaired: " : "  repaired: ") << p["type"].get<std::string>() << " at";
      for (const auto& e : p["elements"]) out << " " << e.get<std::string>();
      const auto& why = left ? p["reason"] : p["note"];
      out << ": " << (why.is_null() ? std::string() : why.get<std::string>()) << "\n";
    }
  return kExitOk;
}

}  // namespace kintsugi::cli
