// Still pictures of a page (view/html_page.h) through headless Chromium: the page's
// ?still=1&size=WxH mode (no list, a legend) rendered with software WebGL (SwiftShader) and
// captured with Chromium's --screenshot. Needs Chromium installed (Debian: chromium);
// KINTSUGI_CHROMIUM may name the binary, otherwise chromium, chromium-browser,
// google-chrome and google-chrome-stable are looked up on PATH.
#pragma once

#include <optional>
#include <string>

namespace kintsugi::view {

// The browser to use, or nullopt when none is installed.
std::optional<std::string> find_chromium();

struct ScreenshotOptions {
  int width = 1600, height = 800;  // CSS pixels (device scale 1)
  int timeout_seconds = 180;
};

// The PNG bytes of the page at `html_path` in still mode, or nullopt with *error saying
// why (no browser, the browser failed or timed out, no picture written).
std::optional<std::string> screenshot(const std::string& html_path, const ScreenshotOptions& options,
                                      std::string* error);

}  // namespace kintsugi::view
