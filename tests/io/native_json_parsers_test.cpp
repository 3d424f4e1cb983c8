// The native reader's two parsers agree (io/native_json_parse.h): simdjson first, falling
// back on nlohmann's, whole or in two halves on two threads, against nlohmann's alone —
// the same verdict, the same message, the same body, meta and units — on hand-picked JSON
// corner cases and on random documents damaged the ways files get damaged. And the fast
// parser is really the one that reads ordinary documents (else the agreement would be the
// reference agreeing with itself); native_json_halves_test.cpp checks the same of halves.
#include "io/native_json.h"
#include "io/native_json_parse.h"
#include "kernel/builders.h"
#include "zoo/zoo.h"

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <string>
#include <vector>

namespace kintsugi::io {
namespace {

// "" when the fast parser (whole, then in halves) says the same of `text` as the
// reference, else what differs.
std::string disagreement(const std::string& text) {
  std::string reference_error;
  auto reference = read_native(text, &reference_error, NativeParser::kReferenceOnly);
  for (NativeParser parser : {NativeParser::kSimdjsonFirst, NativeParser::kSimdjsonHalves}) {
    const std::string who = parser == NativeParser::kSimdjsonFirst ? "simdjson" : "simdjson in halves";
    std::string fast_error;
    auto fast = read_native(text, &fast_error, parser);
    if (bool(fast) != bool(reference))
      return fast ? who + " accepted, the reference refused: " + reference_error
                  : "the reference accepted, " + who + " refused: " + fast_error;
    if (!fast) {
      if (fast_error != reference_error) return who + ": messages differ:\n  " + fast_error + "\n  " + reference_error;
      continue;
    }
    std::string why;
    if (!fast->body.equals(reference->body, &why)) return who + ": bodies differ: " + why;
    if (fast->meta != reference->meta) return who + ": meta differs: " + fast->meta.dump() + " vs " + reference->meta.dump();
    if (fast->units != reference->units) return who + ": units differ";
  }
  return "";
}

// Does the simdjson parser read `text` itself, without falling back?
bool simdjson_reads(const std::string& text) {
  struct Count : ElementSink {
    std::size_t n = 0;
    void element(ElementKind, std::size_t, JsonView) override { ++n; }
    void expect(ElementKind, std::size_t, std::size_t) override {}
  } sink;
  std::string padded = text + std::string(simdjson_padding(), ' ');
  JsonTree root;
  return parse_native_simdjson(padded.data(), text.size(), padded.size(), &sink, &root) == FastParse::kDone;
}

const std::string& box_text() {
  static const std::string t = write_native(build::box(), {{"tolerance", 0.01}, {"seed", 7}});
  return t;
}

// `text` with the first occurrence of `from` replaced by `to`.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

TEST(NativeReaderParsers, SimdjsonReadsOrdinaryDocumentsItself) {
  EXPECT_TRUE(simdjson_reads(box_text()));
  zoo::ZooModel m = zoo::family(500, 0.5, 2);
  EXPECT_TRUE(simdjson_reads(write_native(m.body, m.meta(), "mm")));
  // Keys with escapes, other spacing, members in another order: still its own.
  EXPECT_TRUE(simdjson_reads(replaced(box_text(), "\"format\"", "\"form\\u0061t\"")));
  EXPECT_TRUE(simdjson_reads(nlohmann::json::parse(box_text()).dump()));
}

// How many elements the fast parser read typed (io/native_json_typed.h), how many as trees.
struct TypedCount {
  std::size_t typed = 0, trees = 0;
};
TypedCount typed_count(const std::string& text) {
  struct Sink : ElementSink {
    BodyDescription d;
    TypedCount n;
    void element(ElementKind, std::size_t, JsonView) override { ++n.trees; }
    void expect(ElementKind, std::size_t, std::size_t) override {}
    BodyDescription* direct(ElementKind) override { return &d; }
    void appended(ElementKind, std::size_t) override { ++n.typed; }
  } sink;
  std::string padded = text + std::string(simdjson_padding(), ' ');
  JsonTree root;
  EXPECT_EQ(parse_native_simdjson(padded.data(), text.size(), padded.size(), &sink, &root), FastParse::kDone);
  return sink.n;
}

TEST(NativeReaderParsers, TypedReadingTakesTheCommonElements) {
  // Every element of the analytic solids and of the scalable family is read typed (else the
  // agreement above would be the tree path agreeing with itself) ...
  zoo::ZooModel m = zoo::family(300, 0.5, 3);
  for (const std::string& t : {box_text(), write_native(build::cone(1, 2)), write_native(build::sphere(1)),
                               write_native(build::torus(3, 1)), write_native(m.body, m.meta(), "mm")}) {
    const TypedCount n = typed_count(t);
    EXPECT_EQ(n.trees, 0u);
    EXPECT_GE(n.typed, 5u);
  }
  // ... and an element it cannot read exactly as the tree path would goes that way, alone.
  const TypedCount n = typed_count(replaced(box_text(), "\"type\": \"line\"", "\"type\": \"lin\\u0065\""));
  EXPECT_EQ(n.trees, 1u);
  EXPECT_EQ(n.typed + n.trees, typed_count(box_text()).typed);
}

TEST(NativeReaderParsers, SimdjsonLeavesTheOutOfTheOrdinaryToTheReference) {
  // Each of these the reference must read (or word the refusal of) itself.
  EXPECT_FALSE(simdjson_reads(box_text() + " x"));
  EXPECT_FALSE(simdjson_reads(replaced(box_text(), "\"units\"", "\"format\": \"kintsugi-brep\", \"units\"")));
  EXPECT_FALSE(simdjson_reads(replaced(box_text(), "\"seed\": 7", "\"seed\": 1e999")));
  EXPECT_FALSE(simdjson_reads(replaced(box_text(), "\"seed\": 7", "\"seed\": 18446744073709551616")));
  EXPECT_FALSE(simdjson_reads(replaced(box_text(), "\"seed\": 7", "\"seed\": " + std::string(64, '[') + std::string(64, ']'))));
  EXPECT_FALSE(simdjson_reads(""));
}

TEST(NativeReaderParsers, AgreeOnJsonCornerCases) {
  const std::string& t = box_text();
  auto deep = [](int n) { return std::string(std::size_t(n), '[') + std::string(std::size_t(n), ']'); };
  std::vector<std::string> cases = {
      "", " ", "{}", "[]", "null", "\xef\xbb\xbf" + t, t + "\n\t ", t + " x", t + "{}",
      // Numbers, as ids and in meta: signs, fractions, exponents, 64-bit edges.
      replaced(t, "\"id\": 0", "\"id\": -0"), replaced(t, "\"id\": 0", "\"id\": 0.0"),
      replaced(t, "\"id\": 0", "\"id\": 0e0"), replaced(t, "\"id\": 0", "\"id\": -1"),
      replaced(t, "\"id\": 0", "\"id\": 01"), replaced(t, "\"id\": 0", "\"id\": +0"),
      replaced(t, "\"id\": 0", "\"id\": 4294967295"), replaced(t, "\"id\": 0", "\"id\": 9223372036854775808"),
      replaced(t, "\"seed\": 7", "\"seed\": 18446744073709551615"),
      replaced(t, "\"seed\": 7", "\"seed\": 18446744073709551616"),
      replaced(t, "\"seed\": 7", "\"seed\": -9223372036854775808"),
      replaced(t, "\"seed\": 7", "\"seed\": -9223372036854775809"), replaced(t, "\"seed\": 7", "\"seed\": 1e308"),
      replaced(t, "\"seed\": 7", "\"seed\": 1e309"), replaced(t, "\"seed\": 7", "\"seed\": 1e-400"),
      replaced(t, "\"seed\": 7", "\"seed\": -0.0"), replaced(t, "\"seed\": 7", "\"seed\": .5"),
      replaced(t, "\"seed\": 7", "\"seed\": 1."), replaced(t, "\"seed\": 7", "\"seed\": NaN"),
      replaced(t, "\"seed\": 7", "\"seed\": 4.9e-324"), replaced(t, "\"seed\": 7", "\"seed\": 0.1e1"),
      replaced(t, "\"tolerance\": 0.01", "\"tolerance\": 1E-2"),
      // More digits than a 64-bit mantissa holds (simdjson 3.0's get_number() reads them as 0).
      replaced(t, "\"seed\": 7", "\"seed\": 11000.2400000000009212"),
      replaced(t, "\"point\": [0.0", "\"point\": [1.00000000000000000000001"),
      // ... and far more (simdjson 3.0's portable kernel read this one as 1.4e-88).
      replaced(t, "\"seed\": 7", "\"seed\": 0." + std::string(108, '4') + "0"),
      replaced(t, "\"seed\": 7", "\"seed\": " + std::string(300, '9') + ".5"),
      replaced(t, "\"seed\": 7", "\"seed\": 1." + std::string(400, '0') + "1e-5"),
      // Literals and strings.
      replaced(t, "\"seed\": 7", "\"seed\": nul"), replaced(t, "\"seed\": 7", "\"seed\": truee"),
      replaced(t, "\"seed\": 7", "\"seed\": \"a\\u0000b\""), replaced(t, "\"seed\": 7", "\"seed\": \"\\ud800\""),
      replaced(t, "\"seed\": 7", "\"seed\": \"\\ud83d\\ude00\""), replaced(t, "\"seed\": 7", "\"seed\": \"\x01\""),
      replaced(t, "\"seed\": 7", "\"seed\": \"\xff\""), replaced(t, "\"seed\": 7", "\"seed\": 'x'"),
      replaced(t, "\"seed\": 7", "\"seed\": \"\\x\""), replaced(t, "\"seed\": 7", "\"seed\": 7 // note"),
      replaced(t, "\"units\": \"mm\"", "\"units\": \"m\\u006d\""), replaced(t, "\"units\": \"mm\"", "\"units\": \"in\""),
      // Keys: escaped, duplicated (in the top level, an element, meta), unknown.
      replaced(t, "\"format\"", "\"form\\u0061t\""), replaced(t, "\"format\"", "\"form\\/at\""),
      replaced(t, "\"units\"", "\"format\": \"kintsugi-brep\", \"units\""),
      replaced(t, "\"point\"", "\"id\": 0, \"point\""), replaced(t, "\"seed\": 7", "\"seed\": 7, \"seed\": 8"),
      replaced(t, "\"point\"", "\"colour\": 1, \"point\""), replaced(t, "\"point\"", "\"po\\u0000int\""),
      // Structure: the element arrays missing, not arrays, in another order; nesting at the limit.
      replaced(t, "\"vertices\"", "\"vertices_\""), replaced(t, "\"shells\": [", "\"shells\": {\"a\": [") + "}",
      replaced(t, "\"seed\": 7", "\"seed\": " + deep(62)), replaced(t, "\"seed\": 7", "\"seed\": " + deep(63)),
      replaced(t, "\"seed\": 7", "\"seed\": " + deep(64)), replaced(t, "\"seed\": 7", "\"seed\": [1,]"),
      replaced(t, "\"seed\": 7", "\"seed\": {\"a\": 1,}"), replaced(t, "\"seed\": 7", "\"seed\": {1: 2}"),
      t.substr(0, t.size() / 2), t.substr(0, t.size() - 1), t.substr(1),
  };
  // A meta object with many keys (the builder's hash set), once with a repeat.
  std::string many = "{";
  for (int k = 0; k < 40; ++k) many += (k ? ", \"k" : "\"k") + std::to_string(k) + "\": " + std::to_string(k);
  cases.push_back(replaced(t, "\"seed\": 7", "\"seed\": " + many + "}"));
  cases.push_back(replaced(t, "\"seed\": 7", "\"seed\": " + many + ", \"k17\": 0}"));
  for (std::size_t i = 0; i < cases.size(); ++i) EXPECT_EQ(disagreement(cases[i]), "") << "case " << i << ":\n" << cases[i].substr(0, 300);
}

// Each check the reader makes of an element, one at a time, on documents of every kind of
// analytic geometry: the fast parser reads most elements typed, without a tree
// (io/native_json_typed.h), and must leave every one of these to the tree path, which
// accepts or words the refusal as the reference does.
TEST(NativeReaderParsers, AgreeOnEveryElementCheck) {
  const std::string box = box_text(), cylinder = write_native(build::cylinder(1, 2)),
                    cone = write_native(build::cone(1, 2)), sphere = write_native(build::sphere(1)),
                    torus = write_native(build::torus(3, 1));
  struct Edit {
    const std::string* text;
    std::string from, to;
  };
  const std::string unit = "[1.0, 0.0, 0.0]";
  const std::vector<Edit> edits = {
      // Vertices: ids, points, keys.
      {&box, "{\"id\": 0, \"point\"", "{\"id\": 0.0, \"point\""},
      {&box, "{\"id\": 0, \"point\"", "{\"id\": -1, \"point\""},
      {&box, "{\"id\": 0, \"point\"", "{\"id\": 4294967295, \"point\""},
      {&box, "{\"id\": 0, \"point\"", "{\"id\": 4294967294, \"point\""},
      {&box, "{\"id\": 0, \"point\"", "{\"id\": \"0\", \"point\""},
      {&box, "{\"id\": 0, \"point\"", "{\"point\""},
      {&box, "{\"id\": 0, \"point\"", "{\"id\": 0, \"id\": 0, \"point\""},
      {&box, "{\"id\": 0, \"point\"", "{\"id\": 0, \"colour\": 1, \"point\""},
      {&box, "{\"id\": 0, \"point\"", "{\"id\": 0, \"po\\u0069nt\""},
      {&box, "\"point\": [0.0, 0.0, 0.0]", "\"point\": [0.0, 0.0]"},
      {&box, "\"point\": [0.0, 0.0, 0.0]", "\"point\": [0.0, 0.0, 0.0, 0.0]"},
      {&box, "\"point\": [0.0, 0.0, 0.0]", "\"point\": [0.0, null, 0.0]"},
      {&box, "\"point\": [0.0, 0.0, 0.0]", "\"point\": [0, 0, -0]"},
      {&box, "\"point\": [0.0, 0.0, 0.0]", "\"point\": [1e400, 0.0, 0.0]"},
      {&box, "\"point\": [0.0, 0.0, 0.0]", "\"point\": {\"x\": 0}"},
      // Edges: ids, half-edges, curves.
      {&box, "{\"id\": 0, \"he\"", "{\"id\": 2147483647, \"he\""},
      {&box, "{\"id\": 0, \"he\"", "{\"he\""},
      {&box, "{\"id\": 0, \"he\"", "{\"id\": 2147483646, \"he\""},
      {&box, "{\"id\": 0, \"he\": [", "{\"id\": 0, \"he\": [{\"origin\": 0, \"next\": 0, \"loop\": 0}, "},
      {&box, "\"next\": ", "\"next\": 1, \"next\": "},
      {&box, "\"next\": ", "\"nxt\": "},
      {&box, ", \"loop\": ", ", \"lo\\u006fp\": "},
      {&box, "\"curve\": {\"type\": \"line\"", "\"curve\": null, \"x\": {\"type\": \"line\""},
      {&box, "\"curve\": {\"type\": \"line\"", "\"curve\": {\"type\": \"lin\\u0065\""},
      {&box, "\"curve\": {\"type\": \"line\"", "\"curve\": {\"type\": \"spline\""},
      {&box, "\"curve\": {\"type\": \"line\"", "\"curve\": {\"type\": \"line\\\"\""},
      {&box, "\"curve\": {\"type\": \"line\"", "\"curve\": {\"type\": \"line\", \"radius\": 1"},
      {&box, "\"curve\": {\"type\": \"line\"", "\"curve\": {\"type\": \"line\", \"type\": \"line\""},
      {&box, "\"curve\": {\"type\": \"line\"", "\"curve\": {\"type\": 1"},
      {&box, "\"direction\": " + unit, "\"direction\": [1.000000001, 0.0, 0.0]"},
      {&box, "\"direction\": " + unit, "\"direction\": [1.0000000011, 0.0, 0.0]"},
      {&box, "\"direction\": " + unit, "\"direction\": [1, 0, 0]"},
      {&box, ", \"direction\": " + unit, ""},
      {&cylinder, "\"curve\": {\"type\": \"circle\"", "\"curve\": {\"type\": \"ellipse\""},
      {&cylinder, "\"radius\": 1.0}}", "\"radius\": 0}}"},
      {&cylinder, "\"radius\": 1.0}}", "\"radius\": -1.0}}"},
      {&cylinder, "\"radius\": 1.0}}", "\"radius\": true}}"},
      {&cylinder, "\"radius\": 1.0}}", "\"radius\": 1.0, \"radius\": 2.0}}"},
      {&cylinder, "\"radius\": 1.0}}", "}}"},
      {&cylinder, "\"x\": " + unit, "\"x\": [1.0, 0.0, 0.000000002]"},
      {&cylinder, "\"x\": " + unit, "\"x\": [1.0, 0.0, 0.0000000005]"},
      {&cylinder, "\"x\": " + unit, "\"y\": " + unit},
      {&cylinder, "\"x\": " + unit + ", ", ""},
      {&cylinder, "\"x\": " + unit, "\"x\": " + unit + ", \"x\": " + unit},
      {&cylinder, "\"frame\": {\"origin\": [0.0, 0.0, 0.0]", "\"frame\": {\"origin\": [0.0, 0.0, 0.0], \"w\": 1"},
      // Loops: the face, the cycle or the lone vertex.
      {&box, "{\"id\": 0, \"face\": 0,", "{\"id\": 0, \"face\": null,"},
      {&box, "{\"id\": 0, \"face\": 0,", "{\"id\": 0,"},
      {&box, "{\"id\": 0, \"face\": 0,", "{\"face\": 0,"},
      {&box, "{\"id\": 0, \"face\": 0, \"first\": ", "{\"id\": 0, \"face\": 0, \"lone\": 0, \"first\": "},
      {&box, "{\"id\": 0, \"face\": 0, \"first\": ", "{\"id\": 0, \"face\": 0, \"lone\": null, \"first\": "},
      {&box, "{\"id\": 0, \"face\": 0, \"first\": ", "{\"id\": 0, \"face\": 0, \"first\": null, \"x\": "},
      {&box, "{\"id\": 0, \"face\": 0, \"first\": ", "{\"id\": 0, \"face\": 0, \"first\": 1, \"first\": "},
      // Faces: shells, loops, sense, surfaces.
      {&box, "\"shell\": 0, \"loops\": [0]", "\"shell\": 0, \"loops\": []"},
      {&box, "\"shell\": 0, \"loops\": [0]", "\"shell\": 0, \"loops\": [0.5]"},
      {&box, "\"shell\": 0, \"loops\": [0]", "\"shell\": -0, \"loops\": [0]"},
      {&box, "\"shell\": 0, \"loops\": [0]", "\"loops\": [0]"},
      {&box, "\"same_sense\": true", "\"same_sense\": 1"},
      {&box, ", \"same_sense\": true", ""},
      {&box, "\"loops\": [0], ", ""},
      {&box, "\"same_sense\": true", "\"same_sense\": false"},
      {&box, "\"same_sense\": true", "\"same_sense\": true, \"same_sense\": true"},
      {&box, "\"surface\": {\"type\": \"plane\"", "\"surface\": null, \"s\": {\"type\": \"plane\""},
      {&box, "\"surface\": {\"type\": \"plane\"", "\"surface\": {\"type\": \"plane\", \"radius\": 1.0"},
      {&box, "\"surface\": {\"type\": \"plane\"", "\"surface\": {\"type\": \"pl\\u0061ne\""},
      {&box, "\"surface\": {\"type\": \"plane\"", "\"surface\": {\"type\": \"sphere\""},
      {&cylinder, "\"type\": \"cylinder\"", "\"type\": \"sphere\""},
      {&cylinder, "\"type\": \"cylinder\"", "\"type\": \"cone\""},
      {&cone, "\"half_angle\": ", "\"half_angle\": 0, \"x\": "},
      {&cone, "\"half_angle\": -0.4636476090008061", "\"half_angle\": 0"},
      {&cone, "\"half_angle\": -0.4636476090008061", "\"half_angle\": -0.0"},
      {&cone, "\"half_angle\": -0.4636476090008061", "\"half_angle\": 1.5707963267948966"},
      {&cone, "\"half_angle\": -0.4636476090008061", "\"half_angle\": 1.5707963267948963"},
      {&cone, "\"type\": \"cone\", \"frame\"", "\"type\": \"cone\", \"radius\": 0, \"frame\""},
      {&cone, "\"radius\": 1.0, \"half_angle\"", "\"radius\": 0, \"half_angle\""},
      {&cone, "\"radius\": 1.0, \"half_angle\"", "\"radius\": -0.5, \"half_angle\""},
      {&cone, "\"radius\": 1.0, \"half_angle\"", "\"half_angle\""},
      {&sphere, "\"type\": \"sphere\"", "\"type\": \"cylinder\""},
      {&sphere, "\"radius\": 1.0}", "\"radius\": 0.0}"},
      {&torus, "\"minor_radius\": 1.0", "\"minor_radius\": 3.0"},
      {&torus, "\"minor_radius\": 1.0", "\"minor_radius\": 2.9999999999999996"},
      {&torus, "\"minor_radius\": 1.0", "\"minor_radius\": 0"},
      {&torus, "\"major_radius\": 3.0", "\"major_radius\": -3.0"},
      {&torus, "\"major_radius\": 3.0, ", ""},
      {&torus, "\"type\": \"torus\"", "\"type\": \"cone\""},
      // Shells.
      {&box, "{\"id\": 0, \"genus\": 0}", "{\"id\": 0, \"genus\": -1}"},
      {&box, "{\"id\": 0, \"genus\": 0}", "{\"id\": 0, \"genus\": 0, \"genus\": 0}"},
      {&box, "{\"id\": 0, \"genus\": 0}", "{\"id\": 0}"},
      {&box, "{\"id\": 0, \"genus\": 0}", "{\"id\": 0, \"genus\": 0, \"g\": 0}"},
      {&box, "{\"id\": 0, \"genus\": 0}", "[0, 0]"},
  };
  std::size_t refused = 0;
  for (std::size_t i = 0; i < edits.size(); ++i) {
    const std::string t = replaced(*edits[i].text, edits[i].from, edits[i].to);
    EXPECT_EQ(disagreement(t), "") << "edit " << i << ": " << edits[i].from << " -> " << edits[i].to;
    refused += !read_native(t, nullptr, NativeParser::kReferenceOnly).has_value();
  }
  // Most are refusals: a check the typed reader skipped would accept them.
  EXPECT_GE(refused, edits.size() * 3 / 4);
  // An edge without its half-edges.
  {
    std::string t = box;
    const std::size_t from = t.find("\"he\": ["), to = t.find("}], ", from);
    ASSERT_NE(to, std::string::npos);
    t.erase(from, to + 4 - from);
    EXPECT_EQ(disagreement(t), "");
    EXPECT_FALSE(read_native(t, nullptr, NativeParser::kReferenceOnly).has_value());
  }
  // No curve, no surface (null): read, as the reference reads them.
  for (const auto& [key, end] : {std::pair<std::string, std::string>{"\"curve\": {", "]}"}, {"\"surface\": {", "]}}"}}) {
    std::string t = box;
    const std::size_t from = t.find(key), to = t.find(end, from);
    ASSERT_NE(to, std::string::npos);
    t.replace(from, to + end.size() - from, key.substr(0, key.size() - 1) + "null");
    EXPECT_EQ(disagreement(t), "") << key;
    EXPECT_TRUE(read_native(t, nullptr, NativeParser::kReferenceOnly).has_value()) << key;
    EXPECT_EQ(typed_count(t).trees, 0u) << key;
  }
  // The unchanged documents read the same too.
  for (const std::string* t : {&box, &cylinder, &cone, &sphere, &torus}) EXPECT_EQ(disagreement(*t), "");
}

// A written document with one small damage, as a truncated copy, a bad disk sector or a
// careless hand edit makes: a byte replaced, removed, inserted or a span repeated.
std::string damaged(const std::string& text) {
  static const std::string bytes = "{}[],:\"\\ 0123456789-+.eEtrufalsn/\x01\xff\xc3";
  std::string t = text;
  const int edits = *rc::gen::inRange(1, 4);
  for (int e = 0; e < edits && !t.empty(); ++e) {
    const std::size_t at = *rc::gen::inRange<std::size_t>(0, t.size());
    const char c = bytes[*rc::gen::inRange<std::size_t>(0, bytes.size())];
    switch (*rc::gen::inRange(0, 4)) {
      case 0: t[at] = c; break;
      case 1: t.erase(at, 1); break;
      case 2: t.insert(t.begin() + std::ptrdiff_t(at), c); break;
      default: {
        const std::size_t n = *rc::gen::inRange<std::size_t>(1, 40);
        t.insert(at, t.substr(at, n));
      }
    }
  }
  return t;
}

RC_GTEST_PROP(NativeReaderParsers, AgreeOnDamagedDocuments, ()) {
  const int which = *rc::gen::inRange(0, 4);
  std::string text;
  switch (which) {
    case 0: text = box_text(); break;
    case 1: text = write_native(build::cylinder(1.5, 2.0)); break;
    case 2: text = nlohmann::json::parse(box_text()).dump(); break;
    default: {
      zoo::ZooModel m = zoo::family(std::size_t(*rc::gen::inRange(10, 60)), 0.5, *rc::gen::inRange<std::uint64_t>(1, 1000));
      text = write_native(m.body, m.meta(), "mm");
    }
  }
  const std::string t = damaged(text);
  std::string error;
  RC_CLASSIFY(read_native(t, &error).has_value(), "still accepted");
  RC_CLASSIFY(simdjson_reads(t), "simdjson read it itself");
  const std::string d = disagreement(t);
  RC_ASSERT(d == "");
}

}  // namespace
}  // namespace kintsugi::io
