#include "apps/args.h"
#include "apps/commands.h"
#include "apps/model_files.h"
#include "apps/report_page.h"
#include "apps/tolerance_choice.h"
#include "repair/detect.h"
#include "view/tessellate.h"

#include <filesystem>
#include <ostream>

namespace kintsugi::cli {

namespace {
const char* kHelp =
    "usage: kintsugi view MODEL [--tol T] [--chordal C] [-o PAGE.html] [--png PICTURE.png]\n\n"
    "Writes a page that shows MODEL in 3D with the problems detect finds marked (faces\n"
    "tinted, edges thick, vertices as dots, gaps outlined, one colour per type) and\n"
    "listed (type, where, size against the tolerance). At least one of -o and --png.\n\n"
    "  --tol T        the length tolerance of detect (else meta.tolerance, else 1e-3 x\n"
    "                 model size, said on stderr)\n"
    "  --chordal C    how far the drawn faces and edges may stray from the curved\n"
    "                 surfaces (default 1e-3 x model size)\n"
    "  -o PAGE.html   the page\n"
    "  --png FILE     a still picture of the page (needs Chromium installed, see below)\n\n";
const char* kHelpEnd = "\nExit: 0 written; 2 bad input or usage, or no picture could be taken.\n";
}  // namespace

int cmd_view(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err) {
  Args args;
  std::string error;
  if (!args.parse(argv, {"--tol", "--chordal", "-o", "--png"}, {"--help"}, &error)) {
    err << "kintsugi view: " << error << "\n" << kHelp << kPageHelp << kHelpEnd;
    return kExitBadInput;
  }
  if (args.has("--help")) {
    out << kHelp << kPageHelp << kHelpEnd;
    return kExitOk;
  }
  if (args.positional().size() != 1 || (!args.has("-o") && !args.has("--png"))) {
    err << "kintsugi view: expected MODEL and -o PAGE.html or --png FILE\n" << kHelp << kPageHelp << kHelpEnd;
    return kExitBadInput;
  }
  auto given = args.number("--tol", 0, &error);
  if (!given || (args.has("--tol") && *given <= 0)) {
    err << "kintsugi view: " << (error.empty() ? "--tol must be a positive number" : error) << "\n";
    return kExitBadInput;
  }
  auto chordal = args.number("--chordal", 0, &error);
  if (!chordal || (args.has("--chordal") && *chordal <= 0)) {
    err << "kintsugi view: " << (error.empty() ? "--chordal must be a positive number" : error) << "\n";
    return kExitBadInput;
  }
  if (auto bad = args.bad_output({"-o", "--png"}, args.positional()[0])) {
    err << "kintsugi view: " << *bad << "\n";
    return kExitBadInput;
  }
  const std::string in = args.positional()[0];
  auto model = load_model(in, &error);
  if (!model) {
    err << "kintsugi view: " << error << "\n";
    return kExitBadInput;
  }
  auto choice = choose_tolerance(*model, args.has("--tol") ? given : std::nullopt, &error);
  if (!choice) {
    err << "kintsugi view: " << error << "\n";
    return kExitBadInput;
  }
  if (choice->source != "--tol")
    err << "kintsugi view: tolerance " << choice->tol.length << " " << model->units << " from " << choice->source << "\n";
  const Detection d = detect(model->body, choice->tol);
  view::PageInput page =
      page_from_detection(model->body, std::filesystem::path(in).filename().string(), model->units, choice->tol, d);
  page.chordal = *chordal;
  if (!write_report_page(page, {args.value("-o"), args.value("--png")}, in, &error)) {
    err << "kintsugi view: " << error << "\n";
    return kExitBadInput;
  }
  out << "tolerance " << choice->tol.length << " " << model->units << ": " << d.problems.size() << " problem(s) shown";
  if (args.has("-o")) out << " in " << *args.value("-o");
  if (args.has("--png")) out << (args.has("-o") ? " and " : " in ") << *args.value("--png");
  out << "\n";
  return kExitOk;
}

}  // namespace kintsugi::cli
