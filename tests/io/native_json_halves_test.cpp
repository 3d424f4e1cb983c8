// The native reader in two halves (io/native_json_parse.h, io/native_json_halves.cpp):
// the text is cut between two elements of the array that spans its middle, whichever
// array that is, and read on two threads into the same document the whole text gives;
// where the middle is elsewhere, or the cut's guess is wrong, the text is read whole.
// (native_json_parsers_test.cpp holds the halves to the reference's verdict and wording
// on corner cases and damaged documents.)
#include "io/native_json.h"
#include "io/native_json_parse.h"
#include "zoo/zoo.h"

#include <gtest/gtest.h>

#include <array>
#include <set>
#include <string>

namespace kintsugi::io {
namespace {

struct Counting : ElementSink {
  std::array<std::size_t, kElementKinds> seen{};
  void element(ElementKind kind, std::size_t index, JsonView) override {
    // Indices arrive in order from 0 in each half.
    EXPECT_EQ(index, seen[kind]);
    ++seen[kind];
  }
  void expect(ElementKind, std::size_t, std::size_t) override {}
};

struct HalvesResult {
  bool done = false;
  ElementKind cut = kVertices;
  std::size_t head_count = 0;
  Counting head, tail;
};

HalvesResult parse_in_halves(std::string text) {
  HalvesResult r;
  const std::size_t size = text.size();
  const std::string before = text;
  text.append(simdjson_padding(), ' ');
  JsonTree head_root, tail_root;
  r.done = parse_native_simdjson_halves(text.data(), size, text.size(), &r.head, &head_root, &r.tail, &tail_root, &r.cut,
                                        &r.head_count) == FastParse::kDone;
  // The text is read, never written.
  EXPECT_EQ(text.substr(0, size), before);
  return r;
}

// The element array whose elements span text position `at`, or -1.
int array_at(const std::string& text, std::size_t at) {
  for (int k = 0; k < kElementKinds; ++k) {
    const std::size_t open = text.find("\"" + std::string(kElementKeys[k]) + "\": [");
    if (open == std::string::npos) continue;
    const std::size_t close = text.find("\n  ]", open);
    if (open < at && at < close) return k;
  }
  return -1;
}

// `text` with its meta moved in front of the element arrays.
std::string meta_first(const std::string& text) {
  const std::size_t meta = text.find(",\n  \"meta\": ");
  const std::size_t end = text.rfind("\n}");
  std::string member = text.substr(meta + 2, end - meta - 2);
  std::string t = text.substr(0, meta) + text.substr(end);
  const std::size_t units = t.find("\"units\": \"mm\",\n");
  return t.insert(units + 15, member + ",\n");
}

TEST(NativeReaderHalves, CutsWhicheverArraySpansTheMiddle) {
  zoo::ZooModel m = zoo::family(400, 0.3, 5);
  const std::size_t plain = write_native(m.body, m.meta(), "mm").size();
  std::set<int> cut;
  int whole = 0;
  // A pad in meta, after the arrays or before them, moves the middle through every array.
  for (bool front : {false, true})
    for (std::size_t pad = 0; pad <= plain; pad += plain / 24) {
      nlohmann::json meta = m.meta();
      meta["pad"] = std::string(pad, 'x');
      std::string text = write_native(m.body, meta, "mm");
      if (front) text = meta_first(text);
      SCOPED_TRACE((front ? "meta first, pad " : "meta last, pad ") + std::to_string(pad));
      HalvesResult r = parse_in_halves(text);
      // The first element boundary from the middle on: in an element array with two
      // elements or more, or nowhere (the rest is meta or the one-element shell array).
      Cut c;
      const int expected = find_cut(text.data(), text.size(), std::size_t(4) << 20, &c) ? array_at(text, c.comma) : -1;
      if (expected >= 0) {
        EXPECT_GT(c.next, text.size() / 2);
      }
      const nlohmann::json whole_text = nlohmann::json::parse(text);
      std::array<std::size_t, kElementKinds> sizes{};
      for (int k = 0; k < kElementKinds; ++k) sizes[k] = whole_text[kElementKeys[k]].size();
      if (expected < 0) {
        EXPECT_FALSE(r.done);
        ++whole;
      } else {
        ASSERT_TRUE(r.done);
        EXPECT_EQ(int(r.cut), expected);
        cut.insert(int(r.cut));
        // Every element once: the cut array's split between the halves, the others whole
        // in one half.
        EXPECT_EQ(r.head_count, r.head.seen[r.cut]);
        for (int k = 0; k < kElementKinds; ++k) EXPECT_EQ(r.head.seen[k] + r.tail.seen[k], sizes[k]) << kElementKeys[k];
        EXPECT_GT(r.head.seen[r.cut], 0u);
        EXPECT_GT(r.tail.seen[r.cut], 0u);
      }
      // And the document read is the one the text holds, either way.
      std::string error, reference_error;
      auto halves = read_native(text, &error, NativeParser::kSimdjsonHalves);
      auto reference = read_native(text, &reference_error, NativeParser::kReferenceOnly);
      ASSERT_TRUE(halves) << error;
      ASSERT_TRUE(reference) << reference_error;
      std::string why;
      EXPECT_TRUE(halves->body.equals(reference->body, &why)) << why;
      EXPECT_EQ(halves->meta, reference->meta);
    }
  EXPECT_EQ(cut, (std::set<int>{kVertices, kEdges, kLoops, kFaces}));
  EXPECT_GT(whole, 0);
}

TEST(NativeReaderHalves, WholeTextRefusalsAreWordedForTheWholeText) {
  zoo::ZooModel m = zoo::family(200, 0.3, 9);
  const std::string text = write_native(m.body, m.meta(), "mm");
  ASSERT_TRUE(parse_in_halves(text).done);
  // Damage in the second half: the message names the element's place in the whole text
  // (the second half counts its elements from 0), as reading it whole does.
  const std::size_t last_face = text.rfind("{\"id\": ", text.find("\"shells\""));
  std::string bad_element = text;
  bad_element.replace(last_face, 7, "{\"id\": -4, \"x\": ");
  // A top-level key in both halves; an element array in both.
  std::string twice = text;
  twice.insert(twice.rfind("\n}"), ",\n  \"units\": \"mm\"");
  std::string arrays_twice = text;
  arrays_twice.insert(arrays_twice.rfind("\n}"), ",\n  \"vertices\": []");
  // Not JSON after the cut, and trailing bytes.
  std::string broken = text;
  broken.insert(text.size() * 3 / 4, "\"");
  for (const std::string& t : {bad_element, twice, arrays_twice, broken, text + "x"}) {
    std::string halves_error, reference_error;
    EXPECT_FALSE(read_native(t, &halves_error, NativeParser::kSimdjsonHalves));
    EXPECT_FALSE(read_native(t, &reference_error, NativeParser::kReferenceOnly));
    EXPECT_EQ(halves_error, reference_error);
    EXPECT_FALSE(halves_error.empty());
  }
}

TEST(NativeReaderHalves, AWrongGuessReadsTheTextWhole) {
  zoo::ZooModel m = zoo::family(200, 0.3, 9);
  // A long list in meta of objects that look like edges (their key "he"): the middle is
  // in it, the cut is guessed to be in the edges, and the first half says otherwise.
  nlohmann::json meta = m.meta();
  meta["notes"] = nlohmann::json::array();
  for (int i = 0; i < 20000; ++i) meta["notes"].push_back({{"he", i}});
  const std::string text = write_native(m.body, meta, "mm");
  Cut c;
  ASSERT_TRUE(find_cut(text.data(), text.size(), std::size_t(1) << 20, &c));
  EXPECT_EQ(c.kind, kEdges);
  EXPECT_LT(text.find("\"notes\""), c.comma);
  EXPECT_FALSE(parse_in_halves(text).done);
  // An element array that spans the middle with all its elements on one line: no line
  // break between two elements, nowhere to cut.
  const std::string one_line = nlohmann::json::parse(write_native(m.body, m.meta(), "mm")).dump();
  EXPECT_FALSE(find_cut(one_line.data(), one_line.size(), std::size_t(1) << 20, &c));
  EXPECT_FALSE(parse_in_halves(one_line).done);
  // Both read whole, as the reference reads them.
  for (const std::string& t : {text, one_line}) {
    std::string error, reference_error;
    auto halves = read_native(t, &error, NativeParser::kSimdjsonHalves);
    auto reference = read_native(t, &reference_error, NativeParser::kReferenceOnly);
    ASSERT_TRUE(halves) << error;
    ASSERT_TRUE(reference) << reference_error;
    std::string why;
    EXPECT_TRUE(halves->body.equals(reference->body, &why)) << why;
    EXPECT_EQ(halves->meta, reference->meta);
  }
}

}  // namespace
}  // namespace kintsugi::io
