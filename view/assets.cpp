// Files embedded with the assembler's .incbin (paths from view/CMakeLists.txt): no
// generated sources, and an 850 kB script costs nothing to compile.
#include "view/assets.h"

#include <string>

// Defines name[] .. name_end[] holding the file's bytes (not NUL-terminated).
#define KINTSUGI_EMBED(name, path)                                                           \
  asm(".pushsection .rodata\n.balign 16\n.globl " #name "\n.hidden " #name "\n" #name        \
      ":\n.incbin \"" path "\"\n.globl " #name "_end\n.hidden " #name "_end\n" #name "_end:\n" \
      ".byte 0\n.popsection\n");                                                             \
  extern "C" __attribute__((visibility("hidden"))) const char name[], name##_end[];

KINTSUGI_EMBED(kintsugi_asset_three, KINTSUGI_THREE_DIR "/three.min.js")
KINTSUGI_EMBED(kintsugi_asset_orbit, KINTSUGI_THREE_DIR "/examples/js/controls/OrbitControls.js")
KINTSUGI_EMBED(kintsugi_asset_lsg, KINTSUGI_THREE_DIR "/examples/js/lines/LineSegmentsGeometry.js")
KINTSUGI_EMBED(kintsugi_asset_lm, KINTSUGI_THREE_DIR "/examples/js/lines/LineMaterial.js")
KINTSUGI_EMBED(kintsugi_asset_ls2, KINTSUGI_THREE_DIR "/examples/js/lines/LineSegments2.js")
KINTSUGI_EMBED(kintsugi_asset_hooks, KINTSUGI_PAGE_DIR "/hooks.js")
KINTSUGI_EMBED(kintsugi_asset_viewer, KINTSUGI_PAGE_DIR "/viewer.js")
KINTSUGI_EMBED(kintsugi_asset_style, KINTSUGI_PAGE_DIR "/viewer.css")

namespace kintsugi::view {

namespace {
std::string_view span(const char* begin, const char* end) { return {begin, std::size_t(end - begin)}; }
}  // namespace

const PageAssets& page_assets() {
  // The three fat-line files depend on each other in this order.
  static const std::string fat_lines = std::string(span(kintsugi_asset_lsg, kintsugi_asset_lsg_end)) + "\n" +
                                       std::string(span(kintsugi_asset_lm, kintsugi_asset_lm_end)) + "\n" +
                                       std::string(span(kintsugi_asset_ls2, kintsugi_asset_ls2_end));
  static const PageAssets assets = {
      span(kintsugi_asset_three, kintsugi_asset_three_end),
      span(kintsugi_asset_orbit, kintsugi_asset_orbit_end),
      fat_lines,
      span(kintsugi_asset_hooks, kintsugi_asset_hooks_end),
      span(kintsugi_asset_viewer, kintsugi_asset_viewer_end),
      span(kintsugi_asset_style, kintsugi_asset_style_end),
  };
  return assets;
}

}  // namespace kintsugi::view
