// The verb table and the dispatch of `kintsugi VERB ...` (apps/commands.h), in the
// library so that a fuzz target (fuzz/cli_args.cpp) can run the whole command line
// in-process; apps/main.cpp only passes argv on.
#include "apps/commands.h"
#include "repair/pass.h"
#ifdef KINTSUGI_HAVE_OCCT
#include "geometry/occt/freeform_occt.h"
#endif

#include <exception>
#include <iostream>
#include <new>

namespace kintsugi::cli {

const std::vector<Command>& commands() {
  static const std::vector<Command> table = {
      {"generate", "write a built-in model", cmd_generate},
      {"check", "check a model's topology and geometry", cmd_check},
      {"inject", "insert a known defect into a model (for testing repairs)", cmd_inject},
      {"detect", "find the eleven kinds of topological problem", cmd_detect},
      {"beautify", "repair the topology with the passes listed below", cmd_beautify},
      {"batch", "beautify every model in a folder, each in its own process", cmd_batch},
      {"batch-file", "one file of a batch (run by batch)", cmd_batch_file, true},
      {"demo", "beautify the paper's test objects and compare with the expected counts", cmd_demo},
      {"audit", "check the paper's Table 1 (the order of the passes) on random defective models", cmd_audit},
      {"convert", "convert between .json, .step/.stp and .brep", cmd_convert},
      {"measure", "areas, lengths and bounding boxes of faces and edges", cmd_measure},
      {"view", "write a page (HTML, PNG) showing a model and its problems", cmd_view},
  };
  return table;
}

namespace {
void usage(std::ostream& os) {
  os << "usage: kintsugi VERB [options]   (kintsugi VERB --help for each verb)\n\nverbs:\n";
  for (const Command& c : commands())
    if (!c.hidden) os << "  " << c.name << std::string(12 - std::string(c.name).size(), ' ') << c.summary << "\n";
  os << "\nrepair passes, in the order beautify runs them (the paper's Table 1):\n";
  for (kintsugi::ProblemType t : kintsugi::kAllProblemTypes) {
    const kintsugi::Pass* p = kintsugi::find_pass(t);
    os << "  " << (kintsugi::problem_order(t) < 10 ? " " : "") << kintsugi::problem_order(t) << " "
       << kintsugi::problem_name(t) << std::string(21 - std::string(kintsugi::problem_name(t)).size(), ' ')
       << (p ? p->summary : "(no pass yet: found and reported, not repaired)") << "\n";
  }
  os << "\nExit codes: 0 success, 1 invalid model (check), 2 bad input or usage, 3 some files failed (batch).\n";
}
}  // namespace

int run_kintsugi(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
#ifdef KINTSUGI_HAVE_OCCT
  // Free-form faces are evaluated by OpenCASCADE (geometry/freeform.h); registered here,
  // not in main, so that the in-process users of the command line (fuzz/cli_args.cpp)
  // read the same models the program does.
  kintsugi::geo::occt::register_freeform_backend();
#endif
  if (args.empty()) {
    usage(err);
    return kExitBadInput;
  }
  if (args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    usage(out);
    return kExitOk;
  }
  for (const Command& c : commands()) {
    if (args[0] != c.name) continue;
    try {
      return c.run({args.begin() + 1, args.end()}, out, err);
    } catch (const std::bad_alloc&) {
      err << "kintsugi " << c.name << ": out of memory\n";
      return kExitBadInput;
    } catch (const std::exception& e) {
      // Builders and readers report bad parameters by exception; anything else is a bug,
      // still reported rather than crashing.
      err << "kintsugi " << c.name << ": " << e.what() << "\n";
      return kExitBadInput;
    }
  }
  err << "kintsugi: unknown verb '" << args[0] << "'\n\n";
  usage(err);
  return kExitBadInput;
}

}  // namespace kintsugi::cli
