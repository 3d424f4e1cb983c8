// Two of OpenCASCADE's sample parts (Debian's occt-misc) on which beautify once committed
// an invalid model or could not write its result (issue 22): Pump_Nut.brep came out with
// vertices 0.0003 off their curves and OpenCASCADE calling it unorientable; screw.step was
// merged into a model OpenCASCADE could not write. The validity gate must leave each
// either repaired and valid (by our check and OpenCASCADE's) or exactly as read. Skipped,
// visibly, without occt-misc; the whole sample corpus is tests/occt/corpus_test.cpp.
#include "invariants/element_geometry.h"
#include "invariants/geometry_check.h"
#include "invariants/region_validity.h"
#include "invariants/topology_check.h"
#include "io/occt/exchange.h"
#include "repair/beautify.h"
#include "tests/occt/compare.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

namespace kintsugi {
namespace {

// The report, after checking the output as above. `keeps_input_problems`: a part
// OpenCASCADE calls invalid as read may come out repaired with those problems (the gate
// lets a repair keep what a face had), but with nothing new.
BeautifyReport beautify_is_valid_or_unchanged(const std::string& path, io::CadFormat format,
                                              bool keeps_input_problems = false) {
  std::string err;
  std::optional<io::CadImport> in = io::import_cad(path, format, &err);
  EXPECT_TRUE(in) << err;
  if (!in) return {};
  Body b = std::move(in->body);
  const Body original = b;
  // The tolerance the issue reported them at: the size default.
  const double size = model_size(b);
  const geo::Tolerances tol = geo::Tolerances::for_model(1e-3 * size, size);
  // screw.step's exact curves lie up to 7e-5 off its surfaces (the file's tolerances,
  // which our bodies do not carry), so OpenCASCADE calls it invalid as we read it: then
  // beautify must leave it as read, or make it valid.
  const io::OcctVerdict before = io::occt_check(b, tol.precision);
  const bool occt_before = before.valid;
  io::register_occt_region_check(b, tol.precision);
  BeautifyReport r = beautify(b, tol);
  set_external_region_check(nullptr);

  EXPECT_TRUE(check_topology(b).empty());
  if (r.repaired() == 0) {
    std::string why;
    EXPECT_TRUE(b.equals(original, &why)) << "changed without a repair: " << why;
  }
  auto ours = region_violations(b, whole_body(b), tol, lies_on_limit(tol, check_geometry(original, tol.precision).max_deviation));
  EXPECT_TRUE(ours.empty()) << ours.front().invariant << ": " << ours.front().detail;
  if (!occt_before && keeps_input_problems && r.repaired() > 0) {
    // Elements a repair left alone keep their names.
    for (const std::string& p : io::occt_check(b, tol.precision).problems)
      EXPECT_NE(std::find(before.problems.begin(), before.problems.end(), p), before.problems.end()) << "new: " << p;
  } else if (occt_before || r.repaired() > 0) {
    io::OcctVerdict theirs = io::occt_check(b, tol.precision);
    EXPECT_TRUE(theirs.valid) << (theirs.problems.empty() ? "" : theirs.problems.front());
  }
  Body back = test::round_trip(b, format, "sample_" + std::filesystem::path(path).filename().string());
  EXPECT_EQ(back.counts(), b.counts());
  // The file holds what was checked: read back, its geometry is as consistent as the
  // input's (a marched polyline, 0.01 tol off its surfaces between its points, once passed
  // the gate on Pump_Nut.brep and came back 0.0011 off).
  const double input_deviation = check_geometry(original, tol.precision).max_deviation;
  EXPECT_LE(check_geometry(back, tol.precision).max_deviation, lies_on_limit(tol, input_deviation));
  return r;
}

#define SKIP_WITHOUT(path) \
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is not installed (Debian package occt-misc)"

TEST(SampleParts, PumpNutComesOutValidOrUnchanged) {
  const std::string path = "/usr/share/opencascade/data/occ/Pump_Nut.brep";
  SKIP_WITHOUT(path);
  beautify_is_valid_or_unchanged(path, io::CadFormat::brep);
}

TEST(SampleParts, ScrewComesOutUnchangedOrValidAndWritable) {
  const std::string path = "/usr/share/opencascade/data/step/screw.step";
  SKIP_WITHOUT(path);
  beautify_is_valid_or_unchanged(path, io::CadFormat::step);
}

// bottle.brep's fillets and neck are each split into faces of one surface (6e-14 apart),
// and each borders a face it is tangent to. Merging two of them keeps the surface, so the
// edges to the tangent neighbours keep their curves; intersecting the tangent surfaces
// again (a double root) found no curve and refused every merge (session 22).
TEST(SampleParts, FacesOfOneSurfaceBesideTangentFacesAreMerged) {
  const std::string path = "/usr/share/opencascade/data/occ/bottle.brep";
  SKIP_WITHOUT(path);
  const BeautifyReport r = beautify_is_valid_or_unchanged(path, io::CadFormat::brep, /*keeps_input_problems=*/true);
  int merged = 0;
  for (const RepairEntry& e : r.problems) {
    if (e.problem.type != ProblemType::same_geometry_faces) continue;
    EXPECT_TRUE(e.repaired()) << element_names(e.problem).front() << ": " << e.reason;
    merged += e.repaired();
  }
  EXPECT_GE(merged, 12);
}

}  // namespace
}  // namespace kintsugi
