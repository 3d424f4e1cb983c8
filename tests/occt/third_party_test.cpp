// STEP files written by other systems (tests/data/step/README.md: sources and licences)
// import with the expected topology and survive a round trip.
#include "invariants/topology_check.h"
#include "io/occt/exchange.h"
#include "tests/occt/compare.h"

#include <gtest/gtest.h>

namespace kintsugi {
namespace {

using io::CadFormat;

const std::string kDir = std::string(KINTSUGI_TEST_DATA_DIR) + "/step/";

std::string problems(const io::OcctVerdict& v) {
  std::string s;
  for (const std::string& p : v.problems) s += "\n  " + p;
  return s;
}

TEST(ThirdParty, RedCubeBlueCylinder) {
  std::string err;
  std::optional<io::CadImport> in = io::import_cad(kDir + "red_cube_blue_cylinder.step", CadFormat::step, &err);
  ASSERT_TRUE(in) << err;
  EXPECT_EQ(in->units, "m");
  EXPECT_DOUBLE_EQ(in->unit_in_mm, 1000.0);
  const Body& b = in->body;
  for (const Violation& v : check_topology(b)) ADD_FAILURE() << to_string(v);
  // Cube: 8 V, 12 E, 6 F. The cylinder's side is seamless in the file (two circles, an
  // annulus), but OpenCASCADE's STEP reader runs ShapeFix, whose FixMissingSeam adds a
  // seam edge: 2 V, 3 E, 3 F, one loop per face, as OpenCASCADE's own cylinders.
  Counts c = b.counts();
  EXPECT_EQ(c.shells, 2u);
  EXPECT_EQ(c.vertices, 10u);
  EXPECT_EQ(c.edges, 15u);
  EXPECT_EQ(c.faces, 9u);
  EXPECT_EQ(c.loops, 9u);
  EXPECT_EQ(c.border_cycles, 0u);
  int cylinders = 0;
  for (FaceH f : b.faces())
    if (const auto* cyl = std::get_if<geo::Cylinder>(&b.surface(f))) {
      ++cylinders;
      EXPECT_NEAR(cyl->radius, 0.005, 1e-12) << "geometry stays in the file's unit (metres)";
      EXPECT_TRUE(b.same_sense(f));
    }
  EXPECT_EQ(cylinders, 1);
  io::OcctVerdict v = io::occt_check(b);
  EXPECT_TRUE(v.valid) << problems(v);

  for (CadFormat f : {CadFormat::step, CadFormat::brep}) {
    Body r = test::round_trip(b, f, "red_cube_blue_cylinder");
    EXPECT_EQ(test::compare_bodies(b, r), "");
    EXPECT_EQ(test::compare_bodies(r, b), "");
    EXPECT_TRUE(io::occt_check(r).valid);
  }
}

}  // namespace
}  // namespace kintsugi
