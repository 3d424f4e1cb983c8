#include "apps/report_page.h"

#include "io/native_json.h"
#include "view/html_page.h"
#include "view/screenshot.h"

#include <filesystem>
#include <unistd.h>

namespace kintsugi::cli {

const char* const kPageHelp =
    "  A page is one self-contained HTML file (three.js inlined; opens without network):\n"
    "  the model shaded, edges drawn, each problem type in its own colour, the list of\n"
    "  problems beside it; click an entry to frame it. --png photographs the page with\n"
    "  headless Chromium, which must be installed (Debian: chromium; or name the binary\n"
    "  in KINTSUGI_CHROMIUM).\n";

namespace {

view::ProblemEntry entry_of(const Problem& p) {
  view::ProblemEntry e;
  e.type = problem_name(p.type);
  e.elements = element_names(p);
  e.measure = p.measure;
  e.measure_name = measure_name(p.measure_kind);
  e.subcase = subcase_name(p);
  return e;
}

}  // namespace

view::PageInput page_from_detection(const Body& body, const std::string& title, const std::string& units,
                                    const geo::Tolerances& tol, const Detection& d) {
  view::PageInput in;
  in.title = title;
  in.units = units;
  in.tolerance = tol.length;
  in.models.push_back({"model", &body, true});
  for (const Problem& p : d.problems) in.problems.push_back(entry_of(p));
  return in;
}

view::PageInput page_from_beautify(const Body& before, const Body& after, const std::string& title,
                                   const std::string& units, const geo::Tolerances& tol, const BeautifyReport& r) {
  view::PageInput in;
  in.title = title;
  in.units = units;
  in.tolerance = tol.length;
  in.models.push_back({"before", &before, true});
  in.models.push_back({"after", &after, false});
  for (const RepairEntry& p : r.problems) {
    view::ProblemEntry e = entry_of(p.problem);
    e.action = outcome_name(p.outcome);
    e.resolved = !p.left();  // repaired, or removed by an earlier repair: not in the model after
    e.operators = p.operators;
    e.reason = p.reason;
    e.deviation = p.deviation;
    in.problems.push_back(std::move(e));
  }
  return in;
}

bool write_report_page(const view::PageInput& in, const PageFiles& files, const std::string& input, std::string* error) {
  const std::string page = view::html_page(view::scene_json(in));
  if (files.html && !io::write_file_atomically(*files.html, page, error, input)) return false;
  if (!files.png) return true;
  // Chromium opens a file: the page written above, or a temporary copy.
  std::string html_path;
  std::filesystem::path temp;
  if (files.html) {
    html_path = *files.html;
  } else {
    temp = std::filesystem::temp_directory_path() / ("kintsugi-page-" + std::to_string(::getpid()) + ".html");
    if (!io::write_file_atomically(temp.string(), page, error)) return false;
    html_path = temp.string();
  }
  view::ScreenshotOptions o;
  o.width = in.models.size() > 1 ? 1600 : 1000;
  o.height = 800;
  std::string why;
  auto png = view::screenshot(html_path, o, &why);
  if (!temp.empty()) {
    std::error_code ec;
    std::filesystem::remove(temp, ec);
  }
  if (!png) {
    if (error) *error = "cannot write " + *files.png + ": " + why;
    return false;
  }
  return io::write_file_atomically(*files.png, *png, error, input);
}

}  // namespace kintsugi::cli
