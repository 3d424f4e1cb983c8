// Files in tests/data/native/: valid ones read to the body they describe and survive a
// write → read; invalid ones are refused at the place named in the table below. The
// fuzz-found regressions live there too (regression_*.json).
#include "io/native_json.h"
#include "kernel/builders.h"
#include "kernel/euler.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace kintsugi::io {
namespace {

const std::string kDir = KINTSUGI_NATIVE_FIXTURES;

NativeDocument read_fixture(const std::string& name) {
  std::string error;
  auto doc = read_native_file(kDir + "/" + name, &error);
  EXPECT_TRUE(doc) << error;
  return doc ? std::move(*doc) : NativeDocument{};
}

void expect_equal(const Body& a, const Body& b, const std::string& label) {
  std::string why;
  EXPECT_TRUE(a.equals(b, &why)) << label << ": " << why;
}

TEST(NativeJsonFixtures, WrittenFilesReadToTheBuildersBodies) {
  expect_equal(read_fixture("box.json").body, build::box(), "box");
  expect_equal(read_fixture("cylinder.json").body, build::cylinder(1, 2), "cylinder");
  expect_equal(read_fixture("torus.json").body, build::torus(3, 1), "torus");
  Body gap = build::box();
  ASSERT_TRUE(euler::kfmb(gap, gap.faces()[5]));
  NativeDocument g = read_fixture("box_with_gap.json");
  expect_equal(g.body, gap, "box with gap");
  EXPECT_EQ(g.meta["defects"][0]["type"], "face_gap");
  Body p = build::pyramid(build::regular_polygon(4, 1), 1);
  ASSERT_TRUE(euler::kev(p, p.halfedges()[0]));
  expect_equal(read_fixture("pyramid_tombstones.json").body, p, "pyramid with tombstones");
}

TEST(NativeJsonFixtures, HandWrittenSheetWithABorderCycle) {
  NativeDocument d = read_fixture("triangle_sheet.json");
  EXPECT_EQ(d.units, "m");
  EXPECT_EQ(d.body.counts(), (Counts{3, 3, 1, 1, 1, 1}));  // Counts::loops: face loops only
  EXPECT_TRUE(d.body.is_border(LoopH(1)));
  EXPECT_TRUE(std::holds_alternative<std::monostate>(d.body.curve(EdgeH(2))));  // absent curve
  EXPECT_DOUBLE_EQ(d.meta["tolerance"].get<double>(), 0.001);
}

TEST(NativeJsonFixtures, EveryValidFileSurvivesWriteThenRead) {
  for (const auto& entry : std::filesystem::directory_iterator(kDir)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("invalid_", 0) == 0) continue;
    NativeDocument d = read_fixture(name);
    std::string text = write_native(d.body, d.meta, d.units);
    std::string error;
    auto again = read_native(text, &error);
    ASSERT_TRUE(again) << name << ": " << error;
    expect_equal(again->body, d.body, name);
    EXPECT_EQ(again->meta, d.meta) << name;
  }
}

TEST(NativeJsonFixtures, InvalidFilesAreRefusedAtTheNamedPlace) {
  struct Case {
    const char* file;
    const char* starts;  // after "<path>: "
    const char* mentions;
  };
  const Case cases[] = {
      {"invalid_dangling_next.json", "/edges/3/he/1/next: ", "refers to half-edge 99, which does not exist"},
      {"invalid_frame_not_perpendicular.json", "/faces/1/surface/frame: ", "not perpendicular"},
      {"invalid_swapped_next.json", "/edges/0/he/0: ", "twin_next_prev"},
      {"invalid_wrong_genus.json", "/shells/0: ", "euler_poincare"},
      {"invalid_unknown_key.json", "/color: ", "unknown key \"color\""},
      {"invalid_truncated.json", "/loops/", "unexpected end of input"},
      {"invalid_deep_nesting.json", "/meta/0/0/0/0", "nesting is deeper than 64 levels"},
      {"invalid_not_json.json", "not valid JSON", "line 1, column 2"},
  };
  std::size_t invalid_files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kDir))
    invalid_files += entry.path().filename().string().rfind("invalid_", 0) == 0;
  EXPECT_EQ(invalid_files, std::size(cases)) << "every invalid fixture needs a row here";
  for (const Case& c : cases) {
    const std::string path = kDir + "/" + c.file;
    std::string error;
    EXPECT_FALSE(read_native_file(path, &error)) << c.file;
    EXPECT_EQ(error.rfind(path + ": " + c.starts, 0), 0u) << error.substr(0, 300);
    EXPECT_NE(error.find(c.mentions), std::string::npos) << error.substr(0, 300);
  }
}

TEST(NativeJsonFixtures, UnreadablePathsAreNamed) {
  std::string error;
  EXPECT_FALSE(read_native_file(kDir + "/no_such_file.json", &error));
  EXPECT_EQ(error, kDir + "/no_such_file.json: cannot open: No such file or directory");
  EXPECT_FALSE(read_native_file(kDir, &error));
  EXPECT_EQ(error, kDir + ": is a directory, not a file");
}

}  // namespace
}  // namespace kintsugi::io
