// Bad input files are refused with a message naming the file and the problem; never a
// crash.
#include "io/occt/exchange.h"
#include "kernel/builders.h"
#include "tests/occt/compare.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

namespace kintsugi {
namespace {

using io::CadFormat;

// Imports `path`, expects a refusal whose message names the file and contains `what`.
void expect_refused(const std::string& path, CadFormat f, const std::string& what) {
  std::string err;
  std::optional<io::CadImport> in = io::import_cad(path, f, &err);
  EXPECT_FALSE(in) << path;
  EXPECT_NE(err.find(path), std::string::npos) << err;
  EXPECT_NE(err.find(what), std::string::npos) << "expected '" << what << "' in: " << err;
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string exported_box() {
  std::string path = test::temp_path("box.step");
  std::string err;
  EXPECT_TRUE(io::export_cad(build::box(), path, CadFormat::step, &err)) << err;
  return slurp(path);
}

std::string exported(CadFormat f, const std::string& name) {
  std::string path = test::temp_path(name);
  std::string err;
  EXPECT_TRUE(io::export_cad(build::cylinder(1, 2), path, f, &err)) << err;
  return slurp(path);
}

// A box exported to STEP, with the text after the first `marker` up to the next `end`
// replaced by `with` ("" when the marker is missing: the test then fails on it).
std::string box_step_with(const std::string& marker, char end, const std::string& with) {
  std::string text = exported_box();
  const std::size_t at = text.find(marker);
  EXPECT_NE(at, std::string::npos) << marker;
  if (at == std::string::npos) return "";
  const std::size_t from = at + marker.size();
  return text.replace(from, text.find(end, from) - from, with);
}

TEST(BadFiles, Missing) {
  expect_refused(test::temp_path("does_not_exist.step"), CadFormat::step, "no such file");
  expect_refused(test::temp_path("does_not_exist.brep"), CadFormat::brep, "no such file");
}

TEST(BadFiles, Directory) { expect_refused(test::temp_path(""), CadFormat::step, "directory"); }

TEST(BadFiles, Empty) {
  expect_refused(test::temp_file("empty.step", ""), CadFormat::step, "empty");
  expect_refused(test::temp_file("empty.brep", ""), CadFormat::brep, "empty");
  expect_refused(test::temp_file("blank.step", "  \n\t\n"), CadFormat::step, "empty");
}

TEST(BadFiles, Garbage) {
  std::string junk = "this is not a CAD file\n\x01\x02\x03 }{ ;;; \n";
  expect_refused(test::temp_file("garbage.step", junk), CadFormat::step, "not a STEP file");
  expect_refused(test::temp_file("garbage.brep", junk), CadFormat::brep, "not an OpenCASCADE BREP file");
}

TEST(BadFiles, GarbageBetweenAValidHeaderAndTrailer) {
  std::string text = "ISO-10303-21;\nHEADER;\n%%%% garbage ((( \nDATA;\n#1 = ;;; ))) \nENDSEC;\nEND-ISO-10303-21;\n";
  std::string path = test::temp_file("garbled.step", text);
  std::string err;
  EXPECT_FALSE(io::import_cad(path, CadFormat::step, &err));
  EXPECT_NE(err.find(path), std::string::npos) << err;
}

TEST(BadFiles, TruncatedStep) {
  std::string full = exported(CadFormat::step, "whole.step");
  ASSERT_GT(full.size(), 200u);
  for (double frac : {0.1, 0.5, 0.9, 0.99})
    expect_refused(test::temp_file("truncated.step", full.substr(0, std::size_t(double(full.size()) * frac))),
                   CadFormat::step, "truncated");
}

TEST(BadFiles, TruncatedBrep) {
  std::string full = exported(CadFormat::brep, "whole.brep");
  ASSERT_GT(full.size(), 200u);
  for (double frac : {0.1, 0.3, 0.5, 0.7, 0.9, 0.99}) {
    std::string path = test::temp_file("truncated.brep", full.substr(0, std::size_t(double(full.size()) * frac)));
    std::string err;
    EXPECT_FALSE(io::import_cad(path, CadFormat::brep, &err)) << frac;
    EXPECT_NE(err.find(path), std::string::npos) << err;
    EXPECT_NE(err.find("truncated"), std::string::npos) << err;
  }
}

TEST(BadFiles, StepWithoutAShape) {
  std::string text =
      "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('no shape'),'2;1');\n"
      "FILE_NAME('p.step','2024-01-01T00:00:00',(''),(''),'','','');\n"
      "FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));\nENDSEC;\n"
      "DATA;\n#1 = CARTESIAN_POINT('',(0.,0.,0.));\nENDSEC;\nEND-ISO-10303-21;\n";
  expect_refused(test::temp_file("no_shape.step", text), CadFormat::step, "no shape");
}

// OpenCASCADE drops an entity whose reference does not resolve: here a face of the box's
// shell would vanish and leave a hole. Refused instead, naming both entities.
TEST(BadFiles, StepWithADanglingReference) {
  const std::string text = box_step_with("CLOSED_SHELL('',(#", ',', "99999");
  ASSERT_FALSE(text.empty());
  expect_refused(test::temp_file("dangling.step", text), CadFormat::step, "refers to #99999, which the file does not define");
  // A reference inside a string or a comment is not one.
  std::string err;
  std::string quoted = exported_box();
  quoted.insert(quoted.find("DATA;") + 5, "\n/* #99999 */");
  quoted.replace(quoted.find("CLOSED_SHELL('"), 14, "CLOSED_SHELL('#99999");
  std::string ok = test::temp_file("quoted.step", quoted);
  EXPECT_TRUE(io::import_cad(ok, CadFormat::step, &err)) << err;
}

TEST(BadFiles, StepWithOverflowingNumbers) {
  const std::string text = box_step_with("CARTESIAN_POINT('',(", ')', "1.E999,-1.E999,1.E400");
  ASSERT_FALSE(text.empty());
  std::string err;
  std::string bad = test::temp_file("overflow.step", text);
  EXPECT_FALSE(io::import_cad(bad, CadFormat::step, &err));
  EXPECT_NE(err.find(bad), std::string::npos) << err;
}

TEST(BadFiles, StepReadAsBrepAndBrepReadAsStep) {
  std::string step = test::temp_file("really_step.brep", exported(CadFormat::step, "s.step"));
  expect_refused(step, CadFormat::brep, "not an OpenCASCADE BREP file");
  std::string brep = test::temp_file("really_brep.step", exported(CadFormat::brep, "b.brep"));
  expect_refused(brep, CadFormat::step, "not a STEP file");
}

}  // namespace
}  // namespace kintsugi
