// One self-contained HTML page (no network needed to open it): the scene
// (view/scene.h) inlined as JSON, three.js and the viewer inlined as scripts.
//
// The page shows the models side by side with one linked camera (rotate: left drag,
// zoom: wheel, pan: right drag), edges drawn, each problem type in its own colour, and
// a list of the problems; clicking an entry frames the problem. For tests and pictures
// it reads URL parameters: ?click=N clicks entry N after loading, ?still=1 hides the
// list and shows a legend (what --png photographs), ?size=WxH lays the page out at that
// size whatever the window. It writes into the DOM what a
// headless browser can read back: body[data-ready], body[data-errors] (console errors
// and exceptions, also listed in #errors), body[data-camera], body[data-render-ms] (first
// frame done, ms since navigation) and body[data-timing] (its steps), and
// on each list entry data-screen="model:x,y ..." (where the problem projects, in page
// pixels).
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace kintsugi::view {

// The same scene gives the same bytes.
std::string html_page(const nlohmann::json& scene);

}  // namespace kintsugi::view
