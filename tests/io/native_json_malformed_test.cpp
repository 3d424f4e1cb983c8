// Malformed documents: each is refused, and the message starts with the JSON pointer of
// the offending place.
#include "io/native_json.h"
#include "kernel/builders.h"
#include "kernel/euler.h"

#include <gtest/gtest.h>

#include <functional>

namespace kintsugi::io {
namespace {

using ojson = nlohmann::ordered_json;

std::string error_of(const std::string& text) {
  std::string error;
  auto doc = read_native(text, &error);
  EXPECT_FALSE(doc) << "accepted:\n" << text.substr(0, 2000);
  EXPECT_FALSE(error.empty());
  return error;
}

// The error for `base` (a written body) after `edit` changes its document.
std::string error_after(const Body& base, const std::function<void(ojson&)>& edit) {
  ojson j = ojson::parse(write_native(base));
  edit(j);
  return error_of(j.dump(2));
}

// The message starts with "<pointer>: " and mentions `words`.
#define EXPECT_ERROR_AT(message, pointer, words)                                     \
  do {                                                                                \
    const std::string m_ = (message);                                                 \
    EXPECT_EQ(m_.rfind(std::string(pointer) + ": ", 0), 0u) << "message: " << m_;     \
    EXPECT_NE(m_.find(words), std::string::npos) << "message: " << m_;                \
  } while (0)

const Body& box() {
  static const Body b = build::box();
  return b;
}

TEST(NativeJsonMalformed, NotJsonAtAll) {
  std::string m = error_of("hello");
  EXPECT_NE(m.find("not valid JSON"), std::string::npos) << m;
  EXPECT_NE(m.find("line 1, column 1"), std::string::npos) << m;
  m = error_of("");
  EXPECT_NE(m.find("not valid JSON"), std::string::npos) << m;
  m = error_of(write_native(box()) + " trailing");
  EXPECT_NE(m.find("not valid JSON"), std::string::npos) << m;
}

TEST(NativeJsonMalformed, TruncatedFileNamesWhereItStopped) {
  std::string text = write_native(box());
  std::size_t cut = text.find("\"next\"", text.find("\"id\": 3, \"he\""));
  ASSERT_NE(cut, std::string::npos);
  std::string m = error_of(text.substr(0, cut + 8));
  EXPECT_ERROR_AT(m, "/edges/3/he/0/next", "not valid JSON");
  EXPECT_NE(m.find("unexpected end of input"), std::string::npos) << m;
  // Every prefix is refused, none crashes.
  for (std::size_t n = 0; n < text.size(); n += 7) EXPECT_FALSE(read_native(text.substr(0, n), nullptr)) << n;
}

TEST(NativeJsonMalformed, TopLevelMustBeAKintsugiDocument) {
  EXPECT_NE(error_of("[1, 2]").find("expected a kintsugi-brep document"), std::string::npos);
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["format"] = "stl"; }), "/format", "kintsugi-brep");
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["version"] = 2; }), "/version", "unsupported version 2");
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["version"] = "1"; }), "/version", "found the string \"1\"");
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["units"] = "furlong"; }), "/units", "\"furlong\"");
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["faces"] = ojson::object(); }), "/faces", "expected an array");
}

TEST(NativeJsonMalformed, UnknownKeysAreNamed) {
  std::string m = error_after(box(), [](ojson& j) {
    j["colour"] = "red";
    j["weight"] = 3;
  });
  EXPECT_ERROR_AT(m, "/colour", "unknown keys \"colour\", \"weight\"");
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["faces"][2]["same_sens"] = true; }), "/faces/2/same_sens",
                  "unknown key \"same_sens\" in a face");
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["edges"][1]["curve"]["radius"] = 1; }), "/edges/1/curve/radius",
                  "a line curve");
  // Inside meta anything goes.
  ojson j = ojson::parse(write_native(box()));
  j["meta"]["colour"] = {{"r", 1}, {"anything", {1, "two", nullptr}}};
  std::string error;
  auto doc = read_native(j.dump(), &error);
  ASSERT_TRUE(doc) << error;
  EXPECT_EQ(doc->meta["colour"]["anything"][1], "two");
}

TEST(NativeJsonMalformed, MissingFields) {
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j.erase("vertices"); }), "/vertices", "is missing");
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["vertices"][4].erase("point"); }), "/vertices/4/point",
                  "is missing");
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["edges"][0]["he"][1].erase("loop"); }), "/edges/0/he/1/loop",
                  "is missing");
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["faces"][0]["surface"]["frame"].erase("z"); }),
                  "/faces/0/surface/frame/z", "is missing");
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["loops"][1].erase("first"); }), "/loops/1", "has neither");
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["loops"][1]["lone"] = 0; }), "/loops/1", "has both");
}

TEST(NativeJsonMalformed, WrongTypes) {
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["vertices"][2]["point"][1] = "1.0"; }), "/vertices/2/point/1",
                  "expected a number, found the string \"1.0\"");
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["vertices"][2]["point"] = {1, 2}; }), "/vertices/2/point",
                  "an array of 2");
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["vertices"][2]["id"] = 2.5; }), "/vertices/2/id",
                  "expected an integer, found 2.5");
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["vertices"][2]["id"] = -2; }), "/vertices/2/id",
                  "non-negative integer, found -2");
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["faces"][1]["same_sense"] = 1; }), "/faces/1/same_sense",
                  "expected true or false");
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["edges"][5]["he"] = ojson::array({1}); }), "/edges/5/he",
                  "an array of 1");
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["faces"][3]["loops"] = ojson::array(); }), "/faces/3/loops",
                  "an empty array");
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["faces"][3]["surface"] = "plane"; }), "/faces/3/surface",
                  "expected a surface");
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["faces"][3]["surface"]["type"] = "nurbs"; }),
                  "/faces/3/surface/type", "unknown surface type \"nurbs\"");
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["edges"][3]["curve"]["type"] = 7; }), "/edges/3/curve/type",
                  "expected a string");
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["vertices"][0] = nullptr; }), "/vertices/0",
                  "expected a vertex (an object), found null");
}

TEST(NativeJsonMalformed, DanglingReferences) {
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["edges"][3]["he"][1]["next"] = 99; }), "/edges/3/he/1/next",
                  "refers to half-edge 99, which does not exist");
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["edges"][3]["he"][0]["origin"] = 8; }),
                  "/edges/3/he/0/origin", "refers to vertex 8");
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["edges"][0]["he"][0]["loop"] = 6; }), "/edges/0/he/0/loop",
                  "refers to loop 6");
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["loops"][2]["face"] = 40; }), "/loops/2/face",
                  "refers to face 40");
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["loops"][2]["first"] = 24; }), "/loops/2/first",
                  "refers to half-edge 24");
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["faces"][2]["shell"] = 1; }), "/faces/2/shell",
                  "refers to shell 1");
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["faces"][2]["loops"].push_back(17); }), "/faces/2/loops/1",
                  "refers to loop 17");
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["faces"][2]["loops"][0] = 3; }), "/faces/2/loops/0",
                  "loop 3 belongs to face 3, not to face 2");
}

TEST(NativeJsonMalformed, BadIds) {
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["vertices"][6]["id"] = 4000000000u; }), "/vertices/6/id",
                  "too large for 8 vertices");
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["vertices"][6]["id"] = 18446744073709551615u; }),
                  "/vertices/6/id", "out of range");
  EXPECT_ERROR_AT(error_of([] {
                    std::string t = write_native(box());
                    auto p = t.find("\"id\": 6");
                    return t.replace(p, 7, "\"id\": 123456789012345678901234567890");
                  }()),
                  "/vertices/6/id", "expected an integer");
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["vertices"][6]["id"] = 2; }), "/vertices/6/id",
                  "vertex id 2 is used twice (also at /vertices/2)");
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["edges"][6]["id"] = 3000000000u; }), "/edges/6/id",
                  "out of range");
}

TEST(NativeJsonMalformed, NumbersOutOfRange) {
  std::string t = write_native(box());
  std::size_t p = t.find("[1.0, 1.0, 1.0]");
  ASSERT_NE(p, std::string::npos);
  std::string m = error_of(t.substr(0, p) + "[1.0, 1e999, 1.0]" + t.substr(p + 15));
  EXPECT_ERROR_AT(m, "/vertices/7/point/1", "number overflow parsing '1e999'");
  m = error_of(t.substr(0, p) + "[1.0, -1e400, 1.0]" + t.substr(p + 15));
  EXPECT_ERROR_AT(m, "/vertices/7/point/1", "overflow");
  m = error_of(t.substr(0, p) + "[1.0, NaN, 1.0]" + t.substr(p + 15));
  EXPECT_NE(m.find("not valid JSON"), std::string::npos) << m;
  // Overflow inside meta is refused too: it could not be written back.
  m = error_of(t.substr(0, t.rfind('}', t.rfind('}') - 1)) + "\"x\": 1e999}\n}");
  EXPECT_ERROR_AT(m, "/meta/x", "overflow");
}

TEST(NativeJsonMalformed, BadGeometry) {
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["faces"][0]["surface"]["frame"]["x"] = {1, 1, 0}; }),
                  "/faces/0/surface/frame/x", "not a unit vector");
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["faces"][0]["surface"]["frame"]["x"] = {0, 0.6, 0.8}; }),
                  "/faces/0/surface/frame", "not perpendicular (their dot product is 0.8)");
  EXPECT_ERROR_AT(error_after(box(),
                              [](ojson& j) {
                                j["faces"][0]["surface"]["frame"]["x"] = {0, 0, 1};
                                j["faces"][0]["surface"]["frame"]["z"] = {0, 0, 1};
                              }),
                  "/faces/0/surface/frame", "x and z are not perpendicular");
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["edges"][2]["curve"]["direction"] = {0, 0, 0}; }),
                  "/edges/2/curve/direction", "length is 0.0");
  Body cyl = build::cylinder(1, 1);
  EXPECT_ERROR_AT(error_after(cyl, [](ojson& j) { j["faces"][1]["surface"]["radius"] = 0; }),
                  "/faces/1/surface/radius", "must be positive, found 0.0");
  EXPECT_ERROR_AT(error_after(cyl, [](ojson& j) { j["edges"][0]["curve"]["radius"] = -1; }), "/edges/0/curve/radius",
                  "must be positive");
  Body cone = build::cone(1, 1);
  ASSERT_TRUE(std::holds_alternative<geo::Cone>(cone.surface(FaceH(0))));
  EXPECT_ERROR_AT(error_after(cone, [](ojson& j) { j["faces"][0]["surface"]["half_angle"] = 1.6; }),
                  "/faces/0/surface/half_angle", "(-pi/2, pi/2)");
  EXPECT_ERROR_AT(error_after(cone, [](ojson& j) { j["faces"][0]["surface"]["half_angle"] = 0.0; }),
                  "/faces/0/surface/half_angle", "not 0");
  EXPECT_ERROR_AT(error_after(cone, [](ojson& j) { j["faces"][0]["surface"]["radius"] = -0.5; }),
                  "/faces/0/surface/radius", "must not be negative");
  Body torus = build::torus(3, 1);
  EXPECT_ERROR_AT(error_after(torus, [](ojson& j) { j["faces"][0]["surface"]["minor_radius"] = 3; }),
                  "/faces/0/surface/minor_radius", "must be less than major_radius");
  EXPECT_ERROR_AT(error_after(box(),
                              [](ojson& j) {
                                j["edges"][0]["curve"] = {{"type", "polyline"}, {"points", {{0, 0, 0}}}, {"chordal_error", 0}};
                              }),
                  "/edges/0/curve/points", "at least 2 points");
  EXPECT_ERROR_AT(error_after(box(),
                              [](ojson& j) {
                                j["edges"][0]["curve"] = {
                                    {"type", "polyline"}, {"points", {{0, 0, 0}, {1, 0}}}, {"chordal_error", 0}};
                              }),
                  "/edges/0/curve/points/1", "an array of 2");
  EXPECT_ERROR_AT(error_after(box(),
                              [](ojson& j) {
                                j["edges"][0]["curve"] = {{"type", "ellipse"},
                                                          {"frame", j["faces"][0]["surface"]["frame"]},
                                                          {"major_radius", 1},
                                                          {"minor_radius", 2}};
                              }),
                  "/edges/0/curve/minor_radius", "must not exceed major_radius");
}

TEST(NativeJsonMalformed, Meta) {
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["meta"] = ojson::array(); }), "/meta", "expected an object");
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["meta"]["tolerance"] = -1e-6; }), "/meta/tolerance",
                  "must be positive");
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["meta"]["tolerance"] = "tight"; }), "/meta/tolerance",
                  "expected a number");
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["meta"]["defects"] = {{{"type", "gap"}, {"elements", {}}}}; }),
                  "/meta/defects/0/size", "is missing");
  EXPECT_ERROR_AT(
      error_after(box(), [](ojson& j) { j["meta"]["defects"] = {{{"type", 3}, {"elements", {}}, {"size", 1}}}; }),
      "/meta/defects/0/type", "expected a string");
  EXPECT_ERROR_AT(
      error_after(box(), [](ojson& j) { j["meta"]["defects"] = {{{"type", "x"}, {"elements", 1}, {"size", 1}}}; }),
      "/meta/defects/0/elements", "expected an array");
}

TEST(NativeJsonMalformed, DeepNestingIsRefusedWithoutOverflow) {
  std::string deep(100000, '[');
  std::string m = error_of(deep + std::string(100000, ']'));
  EXPECT_NE(m.find("nesting is deeper than 64 levels"), std::string::npos) << m.substr(0, 300);
  EXPECT_EQ(m.rfind("/0/0/0/0", 0), 0u) << m.substr(0, 300);
  // Inside meta, at the place it happens.
  std::string t = write_native(box());
  std::string m2 = error_of(t.substr(0, t.rfind('}', t.rfind('}') - 1)) + "\"deep\": " + deep);
  EXPECT_EQ(m2.rfind("/meta/deep/0/0", 0), 0u) << m2.substr(0, 300);
  EXPECT_NE(m2.find("nesting is deeper"), std::string::npos) << m2.substr(0, 300);
  // 64 levels are allowed in meta (the document and meta take two).
  ojson j = ojson::parse(t);
  ojson inner = 1;
  for (int i = 0; i < 62; ++i) inner = ojson::array({inner});
  j["meta"]["ok"] = inner;
  std::string error;
  EXPECT_TRUE(read_native(j.dump(), &error)) << error;
  j["meta"]["ok"] = ojson::array({inner});
  EXPECT_FALSE(read_native(j.dump(), &error));
}

TEST(NativeJsonMalformed, DuplicateKeys) {
  std::string t = write_native(box());
  std::size_t p = t.find("\"id\": 5, \"point\"");
  ASSERT_NE(p, std::string::npos);
  std::string m = error_of(t.substr(0, p) + "\"id\": 5, \"id\": 6, " + t.substr(p + 9));
  EXPECT_ERROR_AT(m, "/vertices/5/id", "appears twice");
}

TEST(NativeJsonMalformed, InvalidTopologyIsRefusedByTheInvariantCheck) {
  // Swap the next pointers of two half-edges of one loop: every reference is in range,
  // but the cycles no longer close as the loops say.
  std::string m = error_after(box(), [](ojson& j) {
    std::swap(j["edges"][0]["he"][0]["next"], j["edges"][1]["he"][0]["next"]);
  });
  EXPECT_ERROR_AT(m, "/edges/0/he/0", "twin_next_prev");
  // A loop listed twice by its face.
  m = error_after(box(), [](ojson& j) { j["faces"][0]["loops"].push_back(j["faces"][0]["loops"][0]); });
  EXPECT_ERROR_AT(m, "/faces/0", "listed twice");
  // The wrong genus: Euler–Poincaré.
  m = error_after(box(), [](ojson& j) { j["shells"][0]["genus"] = 1; });
  EXPECT_ERROR_AT(m, "/shells/0", "euler_poincare");
  // A half-edge named as next twice.
  m = error_after(box(), [](ojson& j) { j["edges"][0]["he"][0]["next"] = j["edges"][1]["he"][0]["next"]; });
  EXPECT_ERROR_AT(m, "/edges/1/he/0", "already the next of another");
}

// The reader checks each element as soon as it has parsed it (and then drops it), but
// reports in the order spec/file-format.md lists the checks, whatever the order of the
// text: syntax first, then the top level, then vertices, edges, loops, faces, shells,
// each in index order, ids included.
TEST(NativeJsonMalformed, ErrorsComeInTheSpecsOrderWhateverTheTextsOrder) {
  // Two broken arrays, the later kind first in the text: the earlier kind is reported.
  std::string m = error_after(box(), [](ojson& j) {
    ojson reordered = ojson::object();
    for (const char* key : {"format", "version", "units", "shells", "faces", "loops", "edges", "vertices", "meta"})
      reordered[key] = j[key];
    reordered["shells"][0]["genus"] = "one";
    reordered["edges"][2]["he"][0]["origin"] = -1;
    reordered["vertices"][5]["point"] = "here";
    j = reordered;
  });
  EXPECT_ERROR_AT(m, "/vertices/5/point", "expected [x, y, z]");
  // An element error, then a syntax error further on: the syntax error.
  std::string text = write_native(box());
  std::string broken = text;
  broken.replace(broken.find("\"origin\": 0"), 12, "\"origin\": \"a\"");
  m = error_of(broken.substr(0, broken.rfind("\"meta\"")) + "\"meta\": {");
  EXPECT_NE(m.find("not valid JSON"), std::string::npos) << m;
  // An element error, then an unknown key at the top level: the top level.
  m = error_after(box(), [](ojson& j) {
    j["edges"][0]["he"][0]["origin"] = "a";
    j["colour"] = "red";
  });
  EXPECT_ERROR_AT(m, "/colour", "unknown key");
  // A repeated id before a malformed element, and after one.
  m = error_after(box(), [](ojson& j) {
    j["vertices"][3]["id"] = 0;
    j["vertices"][5]["point"] = nullptr;
  });
  EXPECT_ERROR_AT(m, "/vertices/3/id", "used twice (also at /vertices/0)");
  m = error_after(box(), [](ojson& j) {
    j["vertices"][5]["id"] = 0;
    j["vertices"][3]["point"] = nullptr;
  });
  EXPECT_ERROR_AT(m, "/vertices/3/point", "expected [x, y, z]");
  // The id bound counts the whole array, elements after a malformed one included.
  m = error_after(box(), [](ojson& j) {
    j["shells"][0]["id"] = 1026;  // below 2·2 + 1024 only once the second shell counts
    j["shells"].push_back({{"id", 7}, {"genus", "none"}});
  });
  EXPECT_ERROR_AT(m, "/shells/1/genus", "expected a non-negative integer");
  m = error_after(box(), [](ojson& j) {
    j["shells"][0]["id"] = 1028;
    j["shells"].push_back({{"id", 7}, {"genus", "none"}});
  });
  EXPECT_ERROR_AT(m, "/shells/0/id", "too large for 2 shells");
}

TEST(NativeJsonMalformed, ElementArraysThatAreNotArraysOrNotAtTheTop) {
  EXPECT_ERROR_AT(error_after(box(), [](ojson& j) { j["edges"] = {{"id", 0}}; }), "/edges", "expected an array");
  // "vertices" inside meta is meta's business, not an element array.
  std::string text = write_native(box(), {{"vertices", {{{"id", "not a vertex"}}}}});
  std::string error;
  auto doc = read_native(text, &error);
  ASSERT_TRUE(doc) << error;
  EXPECT_EQ(doc->meta["vertices"][0]["id"], "not a vertex");
  // A document that is an array of element arrays is not a kintsugi document.
  EXPECT_NE(error_of("[{\"vertices\": [1]}]").find("expected a kintsugi-brep document"), std::string::npos);
}

TEST(NativeJsonMalformed, OversizedTextIsRefusedBeforeParsing) {
  // A view that claims more than the limit, over a small buffer: the reader must look at
  // its size only, and never at the bytes (AddressSanitizer would notice).
  std::string small = "{}";
  std::string_view huge(small.data(), kMaxNativeBytes + 1);
  std::string error;
  EXPECT_FALSE(read_native(huge, &error));
  EXPECT_NE(error.find("more than the limit"), std::string::npos) << error;
}

}  // namespace
}  // namespace kintsugi::io
