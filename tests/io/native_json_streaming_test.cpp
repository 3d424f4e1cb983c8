// The streamed writer (io/native_json_writer.cpp) against the DOM writer it replaced
// (tests/io/reference_writer.cpp), over random bodies with tombstones and border cycles,
// every surface and curve type with awkward doubles, zoo models, meta present or absent:
//   * the same bytes as the reference except how numbers are spelled, and every number
//     the same double, spelled no longer than the reference spelled it;
//   * write → read gives an equal body and the same meta and units;
//   * writing again, or writing what was read, gives the same bytes;
//   * the sink and file variants give the same bytes as write_native.
// No timing here: speed and memory are measured by `kintsugi-bench io` (docs/benchmarks.md).
#include "io/native_json.h"
#include "kernel/builders.h"
#include "tests/io/reference_writer.h"
#include "tests/io/sample_bodies.h"
#include "tests/support/random_ops.h"
#include "zoo/zoo.h"

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <sstream>
#include <thread>

#include <sys/stat.h>
#include <unistd.h>

namespace kintsugi::io {
namespace {

// ---- comparing with the reference writer ---------------------------------------------

// `text` cut into the number tokens outside strings and everything else.
struct Tokens {
  std::string skeleton;              // the text with every number replaced by '#'
  std::vector<std::string> numbers;  // the numbers, in order
};
Tokens tokens(const std::string& text) {
  Tokens t;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size();) {
    char c = text[i];
    if (in_string) {
      t.skeleton += c;
      if (c == '\\' && i + 1 < text.size()) t.skeleton += text[++i];
      else if (c == '"') in_string = false;
      ++i;
    } else if (c == '"') {
      in_string = true;
      t.skeleton += c;
      ++i;
    } else if (c == '-' || (c >= '0' && c <= '9')) {
      std::size_t j = i + 1;
      while (j < text.size() && std::strchr("0123456789.eE+-", text[j])) ++j;
      t.numbers.push_back(text.substr(i, j - i));
      t.skeleton += '#';
      i = j;
    } else {
      t.skeleton += c;
      ++i;
    }
  }
  return t;
}

// Empty when `streamed` is `reference` up to the spelling of numbers; else what differs.
std::string difference(const std::string& streamed, const std::string& reference) {
  Tokens s = tokens(streamed), r = tokens(reference);
  if (s.skeleton != r.skeleton) {
    std::size_t at = 0;
    while (at < s.skeleton.size() && at < r.skeleton.size() && s.skeleton[at] == r.skeleton[at]) ++at;
    return "layout differs at skeleton offset " + std::to_string(at) + ": streamed \"" + s.skeleton.substr(at, 80) +
           "\" vs reference \"" + r.skeleton.substr(at, 80) + "\"";
  }
  if (s.numbers.size() != r.numbers.size()) return "different number counts";
  for (std::size_t i = 0; i < s.numbers.size(); ++i) {
    const std::string &a = s.numbers[i], &b = r.numbers[i];
    if (a == b) continue;
    // Integers (ids, meta) are never respelled; doubles must denote the same bits.
    double x = std::strtod(a.c_str(), nullptr), y = std::strtod(b.c_str(), nullptr);
    if (std::memcmp(&x, &y, sizeof x) != 0) return "number " + std::to_string(i) + ": " + a + " vs reference " + b;
    if (a.size() > b.size()) return "number " + std::to_string(i) + ": " + a + " is longer than the reference " + b;
    const bool a_float = a.find_first_of(".eE") != std::string::npos, b_float = b.find_first_of(".eE") != std::string::npos;
    if (a_float != b_float) return "number " + std::to_string(i) + ": " + a + " vs reference " + b + " (int/float)";
  }
  return "";
}

// Everything the file's header promises, for one body: "" when it all holds, else the
// first thing that does not.
std::string problems(const Body& b, const nlohmann::json& meta, const std::string& units) {
  const std::string text = write_native(b, meta, units);
  if (std::string diff = difference(text, reference::write_native(b, meta, units)); !diff.empty())
    return "differs from the reference writer: " + diff;
  std::string error;
  auto doc = read_native(text, &error);
  if (!doc) return "refused its own output: " + error;
  std::string why;
  if (!doc->body.equals(b, &why)) return "read back a different body: " + why;
  if (doc->meta != meta) return "read back a different meta: " + doc->meta.dump();
  if (doc->units != units) return "read back units " + doc->units;
  if (write_native(b, meta, units) != text) return "writing twice gave different bytes";
  if (write_native(doc->body, doc->meta, doc->units) != text) return "write(read(write)) differs";
  std::string pieces;
  std::size_t calls = 0;
  const bool ok = write_native_to(b, meta, units, [&](std::string_view s) {
    pieces.append(s);
    ++calls;
    return true;
  });
  if (!ok || pieces != text) return "the sink got different bytes (" + std::to_string(calls) + " pieces)";
  return "";
}

// ---- random bodies --------------------------------------------------------------------

// An integer in [lo, hi), uniform whatever rapidcheck's current size (its inRange
// narrows the range for small sizes, which would starve the later choices).
int choose(int lo, int hi) { return *rc::gen::resize(100, rc::gen::inRange(lo, hi)); }

// A finite double: any bit pattern, an untidy fraction, or one of the awkward ones.
double awkward_double() {
  switch (choose(0, 4)) {
    case 0: {
      double x;
      do {
        const auto bits = *rc::gen::arbitrary<std::uint64_t>();
        std::memcpy(&x, &bits, sizeof x);
      } while (!std::isfinite(x));
      return x;
    }
    case 1: return double(choose(-100000, 100000)) / 97.0;
    case 2: {
      const double special[] = {0.0, -0.0, 1.0, -1.0, 1e-5, 1e-4, 1e15, 1e16, 123456789012345.0,
                                5e-324, 2.2250738585072014e-308, std::numeric_limits<double>::max(),
                                std::numeric_limits<double>::lowest(), 0.1, 1.0 / 3, 9007199254740993.0};
      return *rc::gen::elementOf(std::vector<double>(std::begin(special), std::end(special)));
    }
    default: return std::ldexp(double(choose(1, 1 << 20)), choose(-60, 60));
  }
}
double positive_double() {
  double x = std::abs(awkward_double());
  return x > 0 && x < 1e300 ? x : 0.5;
}
geo::Vec3 awkward_vec3() { return {awkward_double(), awkward_double(), awkward_double()}; }

// A frame the reader accepts (unit x and z within 1e-9, perpendicular within 1e-9).
geo::Frame random_frame() {
  geo::Frame f;
  f.origin = awkward_vec3();
  auto direction = [] {
    geo::Vec3 v(choose(-1000, 1001), choose(-1000, 1001), choose(-1000, 1001));
    return v.norm() > 0 ? geo::Vec3(v.normalized()) : geo::Vec3(-0.0, 0.0, -1.0);
  };
  f.z = direction();
  geo::Vec3 x = direction();
  x -= x.dot(f.z) * f.z;
  f.x = x.norm() > 1e-3 ? geo::Vec3(x.normalized()) : geo::Vec3(f.z.unitOrthogonal());
  return f;
}

geo::Surface random_surface() {
  switch (choose(0, 6)) {
    case 0: return std::monostate{};
    case 1: return geo::Plane{random_frame()};
    case 2: return geo::Cylinder{random_frame(), positive_double()};
    case 3: {
      double angle = std::ldexp(double(choose(1, 1 << 20)), -20) * 1.5;  // (0, 1.5]
      return geo::Cone{random_frame(), choose(0, 2) ? positive_double() : 0.0,
                       choose(0, 2) ? angle : -angle};
    }
    case 4: return geo::Sphere{random_frame(), positive_double()};
    default: {
      double minor = positive_double();
      return geo::Torus{random_frame(), minor * 2 + positive_double(), minor};
    }
  }
}

geo::Curve random_curve() {
  switch (choose(0, 5)) {
    case 0: return std::monostate{};
    case 1: return geo::Line{awkward_vec3(), random_frame().x};
    case 2: return geo::Circle{random_frame(), positive_double()};
    case 3: {
      double minor = positive_double();
      return geo::Ellipse{random_frame(), choose(0, 2) ? minor : minor * 3, minor};
    }
    default: {
      geo::Polyline p;
      const int n = choose(2, 6);
      for (int i = 0; i < n; ++i) p.points.push_back(awkward_vec3());
      p.chordal_error = choose(0, 2) ? positive_double() : 0.0;
      return p;
    }
  }
}

Body random_solid() {
  auto size = [] { return double(choose(1, 5000)) / 97.0; };
  switch (choose(0, 9)) {
    case 0: return build::box(size(), size(), size());
    case 1: return build::prism(build::regular_polygon(choose(3, 9), 1.5), 0.7);
    case 2: return build::pyramid(build::regular_polygon(choose(3, 9), 1), 2);
    case 3: return build::cylinder(1, 2);
    case 4: return build::cone(1.25, 3);
    case 5: return build::sphere(0.3);
    case 6: return build::torus(3, 1);
    case 7: return build::grid_box(std::size_t(choose(6, 100)));
    default: return Body{};
  }
}

// A solid after random Euler operators (tombstones: kill operators leave dead slots;
// border cycles: kfmb), then random geometry on some elements and random points.
Body random_body() {
  Body b = random_solid();
  testing::Numbers n(*rc::gen::container<std::vector<std::uint32_t>>(choose(0, 150),
                                                                     rc::gen::arbitrary<std::uint32_t>()));
  for (int steps = 0; !n.empty() && steps < 50; ++steps) (void)testing::apply_random_op(b, n);
  for (EdgeH e : b.edges())
    if (choose(0, 3) == 0) b.set_curve(e, random_curve());
  for (FaceH f : b.faces())
    if (choose(0, 3) == 0) b.set_surface(f, random_surface(), choose(0, 2) == 1);
  for (VertexH v : b.vertices())
    if (choose(0, 4) == 0) b.set_point(v, awkward_vec3());
  bool polyline = false, torus = false;
  for (EdgeH e : b.edges()) polyline = polyline || std::holds_alternative<geo::Polyline>(b.curve(e));
  for (FaceH f : b.faces()) torus = torus || std::holds_alternative<geo::Torus>(b.surface(f));
  RC_CLASSIFY(polyline && torus, "polyline and torus");
  RC_CLASSIFY(b.edges().size() < b.edge_slots() || b.faces().size() < b.face_slots(), "tombstones");
  RC_CLASSIFY(b.counts().border_cycles > 0, "border cycle");
  return b;
}

nlohmann::json random_meta() {
  switch (choose(0, 2)) {
    case 0: return nlohmann::json::object();
    default: {
      nlohmann::json m = {{"tolerance", positive_double()},
                          {"source", *rc::gen::arbitrary<std::string>()},
                          {"numbers", *rc::gen::arbitrary<std::vector<int>>()},
                          {"x", awkward_double()},
                          {"nested", {{"a", {1, -2, {{"b", nullptr}}}}, {"big", 18446744073709551615u}}}};
      // The writer replaces what is not UTF-8; compare with what it reads back instead.
      auto doc = read_native(write_native(Body{}, m), nullptr);
      return doc ? doc->meta : nlohmann::json::object();
    }
  }
}

RC_GTEST_PROP(NativeJsonStreaming, RandomBodiesMatchTheReferenceAndRoundTrip, ()) {
  const Body b = random_body();
  const nlohmann::json meta = random_meta();
  RC_CLASSIFY(meta.empty(), "empty meta");
  const std::string units = *rc::gen::elementOf(std::vector<std::string>{"nm", "um", "mm", "cm", "m", "in", "ft"});
  if (std::string p = problems(b, meta, units); !p.empty()) RC_FAIL(p);
}

RC_GTEST_PROP(NativeJsonStreaming, EveryFiniteDoubleIsSpelledLikeNlohmannOrShorter, ()) {
  const double x = awkward_double();
  Body b;
  (void)euler::mvfs(b, geo::Vec3(x, -x, x / 3));
  if (std::string diff = difference(write_native(b), reference::write_native(b)); !diff.empty()) RC_FAIL(diff);
}

// ---- fixed cases ------------------------------------------------------------------------

TEST(NativeJsonStreaming, NumbersAreSpelledAsNlohmannSpellsThem) {
  const std::pair<double, const char*> cases[] = {
      {0.0, "0.0"},
      {-0.0, "-0.0"},
      {1.0, "1.0"},
      {-2.5, "-2.5"},
      {0.1, "0.1"},
      {1e-4, "0.0001"},
      {1e-5, "1e-05"},
      {1.2e-5, "1.2e-05"},
      {0.00012, "0.00012"},
      {12345.678, "12345.678"},
      {123456789012345.0, "123456789012345.0"},
      {1e15, "1e+15"},
      {1.5e16, "1.5e+16"},
      {1e100, "1e+100"},
      {1.5e300, "1.5e+300"},
      {5e-324, "5e-324"},
      {std::numeric_limits<double>::max(), "1.7976931348623157e+308"},
      {-std::numeric_limits<double>::min(), "-2.2250738585072014e-308"},
  };
  for (auto [x, expected] : cases) {
    Body b;
    ASSERT_TRUE(euler::mvfs(b, geo::Vec3(x, 0, 0)));
    const std::string text = write_native(b);
    const std::string line = std::string("{\"id\": 0, \"point\": [") + expected + ", 0.0, 0.0]}";
    EXPECT_NE(text.find(line), std::string::npos) << expected << " not found in\n" << text;
    EXPECT_EQ(nlohmann::json(x).dump(), expected) << "nlohmann spells it differently";
  }
}

TEST(NativeJsonStreaming, BuilderSolidsWithEveryGeometryType) {
  Body b = test::every_geometry_type_body();
  EXPECT_EQ(problems(b, nlohmann::json::object(), "mm"), "") << "every type";
  EXPECT_EQ(problems(b, {{"tolerance", 1e-6}, {"note", "caf\xc3\xa9 \"quoted\" \\ / \n"}}, "in"), "") << "every type, meta";
  EXPECT_EQ(problems(Body{}, nlohmann::json::object(), "mm"), "") << "empty body";
  Body lone;
  ASSERT_TRUE(euler::mvfs(lone, geo::Vec3(1, 2, 3)));
  EXPECT_EQ(problems(lone, nlohmann::json::object(), "m"), "") << "lone vertex";
  EXPECT_EQ(problems(build::torus(3, 1), {{"tolerance", 0.5}}, "mm"), "") << "torus";
}

TEST(NativeJsonStreaming, ZooModelsMatchTheReference) {
  // Families large enough that write_native_to hands over several 1 MiB pieces.
  for (auto [faces, rate, seed] : {std::tuple{10, 0.0, 1}, std::tuple{500, 0.5, 2}, std::tuple{2500, 0.2, 3}}) {
    zoo::ZooModel m = zoo::family(std::size_t(faces), rate, std::uint64_t(seed));
    EXPECT_EQ(problems(m.body, m.meta(), "mm"), "") << m.source;
  }
  for (int n = 1; n <= 10; ++n) {
    for (bool clean : {false, true}) {
      zoo::ZooModel m;
      try {
        m = zoo::paper_object(n, clean);
      } catch (const std::exception&) {
        continue;  // not built (docs/paper-objects.md)
      }
      EXPECT_EQ(problems(m.body, m.meta(), "mm"), "") << "paper object " + std::to_string(n) + (clean ? " clean" : "");
    }
  }
}

TEST(NativeJsonStreaming, MetaNullIsWrittenAndRefused) {
  // write_native writes whatever meta it is given; null is not an object, so the reader
  // refuses it at /meta, as the reference writer's output was refused.
  const std::string text = write_native(build::box(), nullptr);
  EXPECT_EQ(difference(text, reference::write_native(build::box(), nullptr)), "");
  std::string error;
  EXPECT_FALSE(read_native(text, &error));
  EXPECT_EQ(error.rfind("/meta: ", 0), 0u) << error;
}

TEST(NativeJsonStreaming, ASinkThatFailsStopsTheWriter) {
  zoo::ZooModel m = zoo::family(2500, 0.1, 4);
  const std::string whole = write_native(m.body, m.meta(), "mm");
  ASSERT_GT(whole.size(), std::size_t(3) << 19);  // more than one piece of 1 MiB
  std::size_t calls = 0, bytes = 0;
  EXPECT_FALSE(write_native_to(m.body, m.meta(), "mm", [&](std::string_view s) {
    ++calls;
    bytes += s.size();
    return false;
  }));
  EXPECT_EQ(calls, 1u);
  EXPECT_LT(bytes, whole.size());
}

class NativeJsonFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("kintsugi_io_stream_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  static std::string contents(const std::string& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  std::size_t file_count() const {
    return std::size_t(std::distance(std::filesystem::directory_iterator(dir_), std::filesystem::directory_iterator()));
  }
  std::filesystem::path dir_;
};

TEST_F(NativeJsonFile, WriteNativeFileGivesWriteNativesBytes) {
  zoo::ZooModel m = zoo::family(2500, 0.3, 5);
  std::string error;
  ASSERT_TRUE(write_native_file(path("f.json"), m.body, m.meta(), "cm", &error)) << error;
  EXPECT_EQ(contents(path("f.json")), write_native(m.body, m.meta(), "cm"));
  auto doc = read_native_file(path("f.json"), &error);
  ASSERT_TRUE(doc) << error;
  std::string why;
  EXPECT_TRUE(doc->body.equals(m.body, &why)) << why;
  EXPECT_EQ(file_count(), 1u);
  // Never over the input, and nothing left behind.
  EXPECT_FALSE(write_native_file(path("f.json"), build::box(), {}, "mm", &error, path("f.json")));
  EXPECT_NE(error.find("refusing to overwrite the input file"), std::string::npos) << error;
  EXPECT_EQ(contents(path("f.json")), write_native(m.body, m.meta(), "cm"));
  EXPECT_FALSE(write_native_file(path("no/such/dir/f.json"), build::box(), {}, "mm", &error));
  EXPECT_EQ(file_count(), 1u);
}

TEST_F(NativeJsonFile, AProducerThatFailsOrThrowsLeavesTheOldFile) {
  std::string error;
  ASSERT_TRUE(write_file_atomically(path("out"), "old", &error)) << error;
  EXPECT_FALSE(write_file_atomically_streamed(
      path("out"), [](const ChunkSink& sink) { return sink("partial") && false; }, &error));
  EXPECT_NE(error.find("could not be produced"), std::string::npos) << error;
  EXPECT_FALSE(write_file_atomically_streamed(
      path("out"),
      [](const ChunkSink& sink) -> bool {
        (void)sink("partial");
        throw std::runtime_error("boom");
      },
      &error));
  EXPECT_NE(error.find("boom"), std::string::npos) << error;
  EXPECT_EQ(contents(path("out")), "old");
  EXPECT_EQ(file_count(), 1u);
  ASSERT_TRUE(write_file_atomically_streamed(
      path("out"), [](const ChunkSink& sink) { return sink("new ") && sink("") && sink("contents"); }, &error))
      << error;
  EXPECT_EQ(contents(path("out")), "new contents");
}

TEST_F(NativeJsonFile, ReadingAFileInChunksSaysWhatReadingItsTextSays) {
  // read_native_file parses 64 KiB at a time; its verdicts and messages (line and column
  // included) are those of read_native on the whole text, wherever the chunks break.
  zoo::ZooModel m = zoo::family(2500, 0.3, 6);
  const std::string text = write_native(m.body, m.meta(), "mm");
  for (std::size_t cut : {text.size(), text.size() - 3, text.size() / 2 + 1, std::size_t(1) << 16, std::size_t(70000)}) {
    std::string part = text.substr(0, cut);
    if (cut == std::size_t(70000)) part.back() = '@';
    ASSERT_TRUE(write_file_atomically(path("t.json"), part, nullptr));
    std::string from_file, from_text;
    const bool file_ok = read_native_file(path("t.json"), &from_file).has_value();
    const bool text_ok = read_native(part, &from_text).has_value();
    EXPECT_EQ(file_ok, text_ok) << cut;
    if (!text_ok) {
      EXPECT_EQ(from_file, path("t.json") + ": " + from_text) << cut;
    }
  }
}

TEST_F(NativeJsonFile, ReadsFromAPipe) {
  // Not a regular file: no size from stat, the cap is checked as it reads.
  ASSERT_EQ(::mkfifo(path("p.json").c_str(), 0600), 0);
  const std::string text = write_native(build::torus(3, 1), {{"tolerance", 0.5}});
  std::thread writer([&] { std::ofstream(path("p.json"), std::ios::binary) << text; });
  std::string error;
  auto doc = read_native_file(path("p.json"), &error);
  writer.join();
  ASSERT_TRUE(doc) << error;
  EXPECT_TRUE(doc->body.equals(build::torus(3, 1)));
}

}  // namespace
}  // namespace kintsugi::io
