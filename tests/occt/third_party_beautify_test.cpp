// Beautify on STEP parts written by other systems (tests/data/step/README.md): whatever
// it repairs or leaves, the output is a valid body and the report's "left" list is
// exactly what detect() finds on it (issue 12: the local re-detection between passes
// misses nothing and invents nothing, also on models none of our generators made).
#include "invariants/element_geometry.h"
#include "invariants/topology_check.h"
#include "io/occt/exchange.h"
#include "repair/beautify.h"
#include "tests/support/left_mismatch.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

namespace kintsugi {
namespace {

std::vector<std::string> step_parts() {
  std::vector<std::string> out;
  for (const auto& e : std::filesystem::directory_iterator(std::string(KINTSUGI_TEST_DATA_DIR) + "/step")) {
    std::string ext = e.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
    if (ext == ".step" || ext == ".stp") out.push_back(e.path().string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

TEST(ThirdPartyBeautify, LeftIsWhatDetectFindsOnTheOutput) {
  const auto parts = step_parts();
  ASSERT_GE(parts.size(), 5u);
  int repaired_somewhere = 0;
  for (const std::string& path : parts) {
    std::string err;
    std::optional<io::CadImport> in = io::import_cad(path, io::CadFormat::step, &err);
    ASSERT_TRUE(in.has_value()) << path << ": " << err;
    // From "nothing is a defect" to a tolerance that calls real features defects: the
    // larger ones make the passes work on these parts, which is the point here.
    for (double rel : {1e-3, 1e-2, 3e-2, 6e-2}) {
      Body b = in->body.clone();
      const geo::Tolerances tol = geo::Tolerances::for_model(rel * model_size(b), model_size(b));
      const BeautifyReport r = beautify(b, tol);
      const std::string where = path + " at tolerance " + std::to_string(rel) + " x size";
      EXPECT_TRUE(check_topology(b).empty()) << where;
      EXPECT_EQ(test::left_mismatch(b, tol, r), "") << where;
      repaired_somewhere += r.repaired();
    }
  }
  // Otherwise the property above would hold of a pipeline that does nothing.
  EXPECT_GT(repaired_somewhere, 0);
}

}  // namespace
}  // namespace kintsugi
