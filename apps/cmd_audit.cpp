// kintsugi audit: Table 1 checked by machine (audit/audit.h, docs/table1-audit.md).
#include "apps/args.h"
#include "apps/commands.h"
#include "apps/model_files.h"
#include "audit/audit.h"
#include "io/native_json.h"
#include "repair/pass.h"

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <unistd.h>

namespace kintsugi::cli {

namespace {
const char* kHelp =
    "usage: kintsugi audit [--trials N] [--seed S] [--pass P] [--json] [--save DIR] [--no-shrink]\n"
    "                      [--trace]\n"
    "       kintsugi audit --replay FINDING.json\n\n"
    "Checks the paper's ordering claim (Table 1, spec/table1.json) on random defective\n"
    "models from the zoo: every base solid, every defect kind, several defects at once,\n"
    "random tolerances, rotations, translations and scales. For each registered pass, each\n"
    "trial runs the passes before it, then the pass, and counts every problem present after\n"
    "it that was not before it (same kind of problem at the same place) in the cell\n"
    "(created type, pass).\n"
    "A created problem of a type whose pass already ran is a counterexample to the order,\n"
    "unless a repair's refit only moved a measure across the tolerance — a threshold flip\n"
    "(counted apart, listed, not a failure): the problem is gone when the model after the\n"
    "pass is judged at 0.9 of the tolerance, or was already there, at the same place, when\n"
    "the model before it is judged at 1.1, 1.25, 1.5 or 2 times the tolerance, or is a\n"
    "sliver that was a small face before the pass (or the reverse). One the paper marks\n"
    "\"No\" below the diagonal is reported as a disagreement.\n"
    "Findings (counterexamples, threshold flips, disagreements, and a witness for each \"Yes\"\n"
    "cell reached) are shrunk: fewest defects, fewest faces, no motion.\n"
    "A trial where problems of a type earlier than the pass are still there when it runs\n"
    "(no pass for them yet, or refused), or where a repair was kept provisionally at the end\n"
    "of its pass (its geometry consistent to the tolerance only, its region solve failed, or\n"
    "its faces' loops touching: beautify solves it again after later passes, or undoes it),\n"
    "is outside the paper's claim: it is counted as skipped (the second kind also as\n"
    "unsolved), not judged.\n\n"
    "  --trials N    trials per pass (default 200)\n"
    "  --seed S      the run's seed (default 1): the same seed gives the same table\n"
    "  --pass P      audit one pass only (a problem type name, e.g. short_edge)\n"
    "  --json        print the 121 cells (counts, threshold flips, the paper's Yes/No) and the\n"
    "                findings as JSON\n"
    "  --save DIR    write each finding as DIR/<kind>-<pass>-<created>.json (its recipe, the\n"
    "                operation script that rebuilds the model) and .model.json (the native\n"
    "                model); DIR is created if missing, and checked before the run starts\n"
    "  --no-shrink   keep findings as found\n"
    "  --trace       print each trial's recipe to stderr before it runs, so a trial that\n"
    "                hangs or crashes is the last one named (its recipe rebuilds the model)\n"
    "  --replay F    run the one trial a saved finding (F, written by --save, or a --trace\n"
    "                line's recipe) describes and print what its pass created: each problem's\n"
    "                elements and measure, and whether it is a threshold flip\n\n"
    "Progress goes to stderr. Exit: 0 no counterexample; 1 a counterexample to the order was\n"
    "found (with --replay: the trial still creates one); 2 bad usage, an unreadable finding,\n"
    "or a finding that could not be saved.\n";

std::string short_name(ProblemType t) {
  static const char* names[] = {"fgap", "egap", "mgap", "pinch", "sfch", "sliv", "sech", "same", "smf", "merg", "sed"};
  return names[problem_order(t) - 1];
}

bool save_finding(const std::string& dir, const std::string& kind, const audit::Finding& f, std::string* error) {
  const std::string stem = dir + "/" + kind + "-" + problem_name(f.recipe.pass) + "-" + problem_name(f.created);
  nlohmann::json j = f.recipe.to_json();
  j["created"] = problem_name(f.created);
  j["kind"] = kind;
  if (!io::write_file_atomically(stem + ".json", j.dump(2) + "\n", error)) return false;
  auto built = audit::build(f.recipe);
  if (!built) return true;
  nlohmann::json meta = {{"tolerance", built->tolerance}, {"source", "kintsugi audit " + kind}};
  return io::write_native_file(stem + ".model.json", built->body, meta, "mm", error);
}

// --replay: one trial, told in full.
int replay(const std::string& path, std::ostream& out, std::ostream& err) {
  // A recipe is a few hundred bytes: anything past a megabyte is not one.
  std::ifstream f(path, std::ios::binary);
  std::string text(std::size_t(1) << 20, '\0');
  if (f) f.read(text.data(), std::streamsize(text.size()));
  if (!f && !f.eof()) {
    err << "kintsugi audit: --replay " << path << ": cannot read the file\n";
    return kExitBadInput;
  }
  if (f.gcount() == std::streamsize(text.size())) {
    err << "kintsugi audit: --replay " << path << ": larger than a megabyte, not a finding's recipe\n";
    return kExitBadInput;
  }
  text.resize(std::size_t(f.gcount()));
  audit::Recipe r;
  try {
    r = audit::Recipe::from_json(nlohmann::json::parse(text));
  } catch (const std::exception& e) {
    err << "kintsugi audit: " << path << ": not a finding's recipe: " << e.what() << "\n";
    return kExitBadInput;
  }
  if (!find_pass(r.pass)) {
    err << "kintsugi audit: " << path << ": no pass for " << problem_name(r.pass) << " is built\n";
    return kExitBadInput;
  }
  const audit::TrialResult t = audit::run_trial(r);
  if (!t.ran) {
    out << "no defect of the recipe could be injected: nothing ran\n";
    return kExitOk;
  }
  const double tol = audit::build(r)->tolerance;
  out << "base " << r.base << ", tolerance " << tol << ", pass " << problem_name(r.pass) << "\n" << t.description;
  if (!t.description.empty() && t.description.back() != '\n') out << "\n";
  if (!t.precondition && !t.left.empty()) {
    out << "skipped (outside the paper's claim): problems of earlier types were left:";
    for (ProblemType l : t.left) out << " " << problem_name(l);
    out << "\n";
  }
  if (t.provisional)
    out << "skipped (outside the paper's claim): a repair was kept provisionally (its geometry consistent to the "
           "tolerance only, or its faces' loops touching; beautify solves it again later or undoes it)\n";
  bool counterexample = false;
  out << t.created.size() << " problem(s) created\n";
  for (const Problem& p : t.created) {
    const audit::Verdict v = audit::verdict(p.type, r.pass);
    const bool flip = audit::existed_before(p, t.near_threshold);
    counterexample = counterexample || (t.precondition && v == audit::Verdict::counterexample && !flip);
    out << "  " << problem_name(p.type);
    for (const std::string& n : element_names(p)) out << " " << n;
    out << ": " << measure_name(p.measure_kind) << " " << p.measure << " (" << p.measure / tol
        << (p.measure_kind == Measure::area ? " t^2" : " t") << ")";
    out << (v == audit::Verdict::counterexample
                ? (flip ? " — threshold flip" : t.precondition ? " — COUNTEREXAMPLE" : " — above the diagonal, not judged (skipped)")
            : v == audit::Verdict::disagreement ? " — disagreement with the paper"
                                                : "");
    out << "\n";
  }
  return counterexample ? kExitInvalid : kExitOk;
}
}  // namespace

int cmd_audit(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err) {
  Args args;
  std::string error;
  if (!args.parse(argv, {"--trials", "--seed", "--pass", "--save", "--replay"}, {"--json", "--help", "--no-shrink", "--trace"}, &error)) {
    err << "kintsugi audit: " << error << "\n" << kHelp;
    return kExitBadInput;
  }
  if (args.has("--help")) {
    out << kHelp;
    return kExitOk;
  }
  if (!args.positional().empty()) {
    err << "kintsugi audit: unexpected argument " << args.positional()[0] << "\n" << kHelp;
    return kExitBadInput;
  }
  if (auto f = args.value("--replay")) return replay(*f, out, err);
  audit::Options o;
  auto trials = args.integer("--trials", 200, 1, 1000000000, &error);
  auto seed = args.integer("--seed", 1, 0, (1LL << 62), &error);
  if (!trials || !seed) {
    err << "kintsugi audit: " << error << "\n";
    return kExitBadInput;
  }
  o.trials = long(*trials);
  o.seed = std::uint64_t(*seed);
  o.shrink = !args.has("--no-shrink");
  if (auto p = args.value("--pass")) {
    auto t = problem_from_name(*p);
    if (!t) {
      err << "kintsugi audit: --pass " << *p << " is not a problem type (kintsugi --help lists them)\n";
      return kExitBadInput;
    }
    if (!find_pass(*t)) {
      err << "kintsugi audit: no pass for " << *p << " is built yet\n";
      return kExitBadInput;
    }
    o.pass = t;
  }
  if (auto dir = args.value("--save")) {
    // Before the run, which may take hours: a directory that cannot be made fails now.
    std::error_code ec;
    std::filesystem::create_directories(*dir, ec);
    if (ec || !std::filesystem::is_directory(*dir)) {
      err << "kintsugi audit: --save " << *dir << ": cannot create the directory"
          << (ec ? " (" + ec.message() + ")" : std::string()) << "\n";
      return kExitBadInput;
    }
  }
  const bool tty = isatty(STDERR_FILENO);
  long last = -1;
  o.progress = [&](ProblemType pass, long done, long total) {
    const long pct = total ? done * 100 / total : 100;
    if (tty) {
      err << "\raudit " << std::setw(20) << std::left << problem_name(pass) << std::right << " " << done << "/" << total
          << std::flush;
      if (done == total) err << "\n";
    } else if (pct / 25 != last / 25 || done == total) {
      err << "audit " << problem_name(pass) << " " << done << "/" << total << "\n";
    }
    last = done == total ? -1 : pct;
  };
  if (args.has("--trace"))
    o.trace = [&](long trial, const audit::Recipe& r) {
      err << "trial " << problem_name(r.pass) << " " << trial << ": " << r.to_json().dump() << "\n" << std::flush;
    };
  audit::Result r = audit::run(o);
  bool saved = true;
  if (auto dir = args.value("--save")) {
    auto save = [&](const char* kind, const std::vector<audit::Finding>& fs) {
      for (const auto& f : fs)
        if (!save_finding(*dir, kind, f, &error)) {
          err << "kintsugi audit: " << error << "\n";
          saved = false;
        }
    };
    save("counterexample", r.counterexamples);
    save("threshold_flip", r.threshold_flips);
    save("disagreement", r.disagreements);
    save("witness", r.witnesses);
  }
  if (args.has("--json")) {
    nlohmann::json j = audit::to_json(r);
    j["seed"] = o.seed;
    j["trials_per_pass"] = o.trials;
    out << j.dump(2) << "\n";
  } else {
    out << "Table 1 audit, seed " << o.seed << ", " << o.trials << " trials per pass, " << std::fixed
        << std::setprecision(1) << r.seconds << std::defaultfloat << " s\n";
    out << "cell: trials in which fixing the column created the row [paper's Yes/No]; "
           "* counterexample to the order, ~ threshold flips only, ! disagreement with the paper\n";
    out << std::setw(6) << "";
    for (ProblemType col : kAllProblemTypes) out << std::setw(10) << short_name(col);
    out << "\n";
    for (ProblemType row : kAllProblemTypes) {
      out << std::setw(6) << short_name(row);
      for (ProblemType col : kAllProblemTypes) {
        std::ostringstream cell;
        const std::size_t i = std::size_t(problem_order(row) - 1), k = std::size_t(problem_order(col) - 1);
        const long n = r.cells[i][k], flips = r.flips[i][k];
        const char* mark = n == 0                                                         ? " "
                           : audit::verdict(row, col) == audit::Verdict::counterexample ? (n > flips ? "*" : "~")
                           : audit::verdict(row, col) == audit::Verdict::disagreement   ? "!"
                                                                                        : " ";
        if (!find_pass(col))
          cell << "-";
        else
          cell << n << mark << (audit::paper_says_yes(row, col) ? "Y" : "N");
        out << std::setw(10) << cell.str();
      }
      out << "\n";
    }
    out << "trials  ";
    for (ProblemType col : kAllProblemTypes) out << std::setw(10) << r.trials[std::size_t(problem_order(col) - 1)];
    out << "\nskipped ";
    for (ProblemType col : kAllProblemTypes) out << std::setw(10) << r.skipped[std::size_t(problem_order(col) - 1)];
    out << "\nunsolved";
    for (ProblemType col : kAllProblemTypes) out << std::setw(10) << r.skipped_unsolved[std::size_t(problem_order(col) - 1)];
    out << "\n(- : no pass for that type yet; skipped: trials with problems of an earlier type left when the\n"
           "pass ran — their pass is not built or refused them — or with a repair kept provisionally (unsolved):\n"
           "states the paper's claim does not cover)\n";
    for (const auto& f : r.counterexamples)
      out << "COUNTEREXAMPLE: " << problem_name(f.recipe.pass) << " created " << problem_name(f.created) << ": "
          << f.recipe.to_json().dump() << "\n";
    for (const auto& f : r.threshold_flips)
      out << "threshold flip: " << problem_name(f.recipe.pass) << " brought a " << problem_name(f.created)
          << " just below the tolerance: " << f.recipe.to_json().dump() << "\n";
    for (const auto& f : r.disagreements)
      out << "disagreement with the paper: " << problem_name(f.recipe.pass) << " created " << problem_name(f.created)
          << ": " << f.recipe.to_json().dump() << "\n";
  }
  if (!r.counterexamples.empty()) return kExitInvalid;
  return saved ? kExitOk : kExitBadInput;
}

}  // namespace kintsugi::cli
