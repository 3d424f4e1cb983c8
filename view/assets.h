// The scripts and style a page inlines, embedded into the program at build time
// (view/CMakeLists.txt): three.js r111 and the parts of its examples the page uses,
// from Debian's libjs-three, and the page's own code in view/page/.
#pragma once

#include <string_view>

namespace kintsugi::view {

struct PageAssets {
  std::string_view three;           // three.min.js
  std::string_view orbit_controls;  // examples/js/controls/OrbitControls.js
  std::string_view fat_lines;       // examples/js/lines/: LineSegmentsGeometry, LineMaterial, LineSegments2
  std::string_view hooks;           // page/hooks.js: errors into the DOM, before anything else runs
  std::string_view viewer;          // page/viewer.js
  std::string_view style;           // page/viewer.css
};

const PageAssets& page_assets();

}  // namespace kintsugi::view
