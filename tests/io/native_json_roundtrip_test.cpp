// Write → read gives an equal body: every builder solid, open shells, tombstones, genus,
// every geometry type, and the document's meta and units.
#include "io/native_json.h"
#include "kernel/builders.h"
#include "kernel/euler.h"
#include "tests/io/sample_bodies.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace kintsugi::io {
namespace {

// Reads back what write_native wrote and checks the body is equal.
void expect_round_trip(const Body& b, const std::string& label) {
  std::string text = write_native(b);
  std::string error;
  auto doc = read_native(text, &error);
  ASSERT_TRUE(doc) << label << ": " << error << "\n" << text;
  std::string why;
  EXPECT_TRUE(doc->body.equals(b, &why)) << label << ": " << why;
  EXPECT_EQ(write_native(doc->body), text) << label << ": second write differs";
}

TEST(NativeJsonRoundTrip, EveryBuilderSolid) {
  expect_round_trip(build::box(), "box");
  expect_round_trip(build::box(2.5, 0.1, 1e-3), "thin box");
  expect_round_trip(build::prism(build::regular_polygon(6, 1.5), 0.7), "prism");
  expect_round_trip(build::pyramid(build::regular_polygon(5, 1), 2), "pyramid");
  expect_round_trip(build::cylinder(1, 2), "cylinder");
  expect_round_trip(build::cone(1.25, 3), "cone");
  expect_round_trip(build::sphere(0.3), "sphere");
  expect_round_trip(build::torus(3, 1), "torus");
  expect_round_trip(build::grid_box(60), "grid box");
}

TEST(NativeJsonRoundTrip, BodyWithABorderCycle) {
  Body b = build::box();
  auto gap = euler::kfmb(b, b.faces()[2]);
  ASSERT_TRUE(gap);
  ASSERT_EQ(b.counts().border_cycles, 1u);
  expect_round_trip(b, "box with a gap");
  auto doc = read_native(write_native(b), nullptr);
  ASSERT_TRUE(doc);
  EXPECT_EQ(doc->body.counts().border_cycles, 1u);
  EXPECT_TRUE(doc->body.is_border(gap->border));
}

TEST(NativeJsonRoundTrip, TombstonesKeepTheirHandles) {
  Body b = build::pyramid(build::regular_polygon(4, 1), 1);
  // Collapse one side edge: its edge and end vertex die, leaving holes in the id ranges.
  HalfedgeH h = b.halfedges()[0];
  ASSERT_TRUE(euler::kev(b, h));
  ASSERT_LT(b.edges().size(), b.edge_slots());
  expect_round_trip(b, "pyramid after kev");
  auto doc = read_native(write_native(b), nullptr);
  ASSERT_TRUE(doc);
  EXPECT_FALSE(doc->body.alive(edge_of(h)));
  EXPECT_EQ(doc->body.edges(), b.edges());
}

TEST(NativeJsonRoundTrip, TorusKeepsItsGenus) {
  Body b = build::torus(2, 0.5);
  auto doc = read_native(write_native(b), nullptr);
  ASSERT_TRUE(doc);
  EXPECT_EQ(doc->body.shell_genus(doc->body.shells()[0]), 1u);
}

TEST(NativeJsonRoundTrip, LoneVertexShell) {
  Body b;
  ASSERT_TRUE(euler::mvfs(b, geo::Vec3(1, 2, 3)));
  expect_round_trip(b, "mvfs");
  expect_round_trip(Body{}, "empty body");
}

TEST(NativeJsonRoundTrip, EveryCurveAndSurfaceType) {
  Body b = test::every_geometry_type_body();
  expect_round_trip(b, "every type");
}

TEST(NativeJsonRoundTrip, DoublesSurviveExactly) {
  // Values whose shortest decimal forms are long or unusual.
  const double hard[] = {0.1,
                         1.0 / 3,
                         -2.0 / 7,
                         1e-320,  // subnormal
                         std::numeric_limits<double>::min(),
                         std::numeric_limits<double>::max(),
                         std::nextafter(1.0, 2.0),
                         -0.0,
                         123456789012345678.0,
                         5e-324};
  Body b;
  for (double x : hard) ASSERT_TRUE(euler::mvfs(b, geo::Vec3(x, -x, x * 0.5)));
  expect_round_trip(b, "hard doubles");
  auto doc = read_native(write_native(b), nullptr);
  ASSERT_TRUE(doc);
  EXPECT_TRUE(std::signbit(doc->body.point(VertexH(7)).x()));  // -0.0 stays negative
}

TEST(NativeJsonRoundTrip, MetaAndUnitsArePreserved) {
  nlohmann::json meta = {{"tolerance", 1e-6},
                         {"source", "scan 7"},
                         {"defects", {{{"type", "face_gap"}, {"elements", {"l9", "e3"}}, {"size", 0.25}}}},
                         {"nested", {{"a", {1, 2, {{"b", nullptr}}}}, {"big", 18446744073709551615u}, {"neg", -4}}}};
  std::string text = write_native(build::cylinder(1, 1), meta, "in");
  std::string error;
  auto doc = read_native(text, &error);
  ASSERT_TRUE(doc) << error;
  EXPECT_EQ(doc->meta, meta);
  EXPECT_EQ(doc->units, "in");
  EXPECT_EQ(write_native(doc->body, doc->meta, doc->units), text);
}

TEST(NativeJsonRoundTrip, MissingMetaReadsAsAnEmptyObject) {
  std::string text = write_native(build::box());
  auto cut = text.find(",\n  \"meta\"");
  ASSERT_NE(cut, std::string::npos);
  std::string error;
  auto doc = read_native(text.substr(0, cut) + "\n}\n", &error);
  ASSERT_TRUE(doc) << error;
  EXPECT_EQ(doc->meta, nlohmann::json::object());
}

}  // namespace
}  // namespace kintsugi::io
