// Report pages (HTML) and pictures (PNG) for `kintsugi view` and `kintsugi beautify
// --html/--png` (view/ draws them): what detect and beautify found, turned into what
// the page lists, and the files written.
#pragma once

#include "apps/model_files.h"
#include "geometry/tolerance.h"
#include "repair/beautify.h"
#include "repair/detect.h"
#include "view/scene.h"

#include <optional>
#include <string>

namespace kintsugi::cli {

// The page of a model and the problems detect found in it.
view::PageInput page_from_detection(const Body& body, const std::string& title, const std::string& units,
                                    const geo::Tolerances& tol, const Detection& d);

// The page of a beautify run: `before` and `after` side by side, one entry per problem
// handled, with its outcome and operators. The only code that reads BeautifyReport for
// the page.
view::PageInput page_from_beautify(const Body& before, const Body& after, const std::string& title,
                                   const std::string& units, const geo::Tolerances& tol, const BeautifyReport& r);

struct PageFiles {
  std::optional<std::string> html, png;  // where to write each (either may be absent)
};

// Writes the page and/or its picture, atomically and never over `input`. The picture
// needs Chromium (view/screenshot.h); without it, false and *error says so.
bool write_report_page(const view::PageInput& in, const PageFiles& files, const std::string& input, std::string* error);

// The --help lines shared by the verbs that write pages.
extern const char* const kPageHelp;

}  // namespace kintsugi::cli
