#include "view/html_page.h"

#include "view/assets.h"

namespace kintsugi::view {

namespace {

// The scene's JSON inside a <script> element: '<' only occurs inside JSON strings, where
// \u003c means the same, and without it no "</script>" can end the element early.
std::string inline_json(const nlohmann::json& j) {
  const std::string s = j.dump();
  std::string out;
  out.reserve(s.size());
  for (char c : s) {
    if (c == '<') out += "\\u003c";
    else out += c;
  }
  return out;
}

std::string html_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '&': out += "&amp;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

}  // namespace

std::string html_page(const nlohmann::json& scene) {
  const PageAssets& a = page_assets();
  const std::string title = scene.value("title", std::string("model"));
  std::string page;
  page.reserve(a.three.size() + 200000);
  page += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  page += "<meta name=\"generator\" content=\"kintsugi\">\n";
  page += "<title>" + html_escape(title) + " - kintsugi</title>\n<style>\n";
  page += a.style;
  page += "</style>\n<script>\n";
  page += a.hooks;  // first: errors of every later script land in the DOM
  page += "</script>\n</head>\n<body>\n";
  page += "<div id=\"main\"><div id=\"views\"><canvas id=\"canvas\"></canvas></div>"
          "<aside id=\"side\"></aside></div>\n<pre id=\"errors\" hidden></pre>\n";
  page += "<script type=\"application/json\" id=\"scene\">";
  page += inline_json(scene);
  page += "</script>\n";
  page += "<script>\n/* three.js r111 (Debian libjs-three 111+dfsg1-3), MIT licence: Copyright (c) 2010-2017 three.js "
          "authors; see view/third_party/three-LICENSE in kintsugi's sources. */\n";
  page += a.three;
  page += "\n</script>\n<script>\n";
  page += a.orbit_controls;
  page += "\n</script>\n<script>\n";
  page += a.fat_lines;
  page += "\n</script>\n<script>\n";
  page += a.viewer;
  page += "\n</script>\n</body>\n</html>\n";
  return page;
}

}  // namespace kintsugi::view
