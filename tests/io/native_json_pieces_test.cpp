// The native reader in pieces (io/native_json_parse.h, "Pieces"): a document cut between
// elements into pieces of any size reads as the same elements, in the same order and with
// the same indices, and the same top level, as the text read in one piece; the sink is
// told each array's count once, before its elements; a cut that is no place between two
// elements sends the text back to be read whole.
#include "io/native_json.h"
#include "io/native_json_parse.h"
#include "zoo/zoo.h"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace kintsugi::io {
namespace {

struct Recording : ElementSink {
  std::vector<std::pair<int, std::string>> elements;  // kind, the element's JSON
  std::array<std::size_t, kElementKinds> seen{}, told{};
  int expects_after_elements = 0, repeated_expects = 0;
  void element(ElementKind kind, std::size_t index, JsonView value) override {
    EXPECT_EQ(index, seen[kind]) << kElementKeys[kind];
    ++seen[kind];
    elements.emplace_back(int(kind), value.dump());
  }
  void expect(ElementKind kind, std::size_t count, std::size_t) override {
    if (seen[kind]) ++expects_after_elements;
    if (told[kind]) ++repeated_expects;
    told[kind] += count;
  }
};

struct Parsed {
  FastParse result;
  Recording sink;
  std::string root;
};

Parsed parse(const std::string& text, std::size_t piece_bytes) {
  std::string padded = text;
  padded.append(simdjson_padding(), ' ');
  Parsed p;
  JsonTree root;
  p.result = parse_native_simdjson(padded.data(), text.size(), padded.size(), &p.sink, &root, piece_bytes);
  if (p.result == FastParse::kDone) p.root = JsonView(&root, 0).dump();
  return p;
}

// Both read, and the same document.
void expect_same_document(const std::optional<NativeDocument>& fast, const std::string& error,
                          const std::optional<NativeDocument>& reference, const std::string& reference_error) {
  ASSERT_TRUE(fast) << error;
  ASSERT_TRUE(reference) << reference_error;
  std::string why;
  EXPECT_TRUE(fast->body.equals(reference->body, &why)) << why;
  EXPECT_EQ(fast->meta, reference->meta);
}

TEST(NativeReaderPieces, EveryPieceSizeReadsWhatOnePieceReads) {
  zoo::ZooModel m = zoo::family(120, 0.3, 4);
  nlohmann::json meta = m.meta();
  meta["note"] = "after the arrays";
  const std::string text = write_native(m.body, meta, "mm");
  const Parsed whole = parse(text, text.size());
  ASSERT_EQ(whole.result, FastParse::kDone);
  ASSERT_GT(whole.sink.elements.size(), 500u);
  for (std::size_t piece : {std::size_t(1), std::size_t(9), std::size_t(100), std::size_t(777), std::size_t(4096),
                            text.size() / 3}) {
    SCOPED_TRACE("pieces of " + std::to_string(piece) + " bytes");
    const Parsed p = parse(text, piece);
    ASSERT_EQ(p.result, FastParse::kDone);
    EXPECT_EQ(p.sink.elements, whole.sink.elements);
    EXPECT_EQ(p.root, whole.root);
    // Told once per array, the exact count, before its first element.
    EXPECT_EQ(p.sink.told, p.sink.seen);
    EXPECT_EQ(p.sink.expects_after_elements, 0);
    EXPECT_EQ(p.sink.repeated_expects, 0);
  }
}

TEST(NativeReaderPieces, ACutOutsideTheElementArraysReadsTheTextWhole) {
  zoo::ZooModel m = zoo::family(60, 0.3, 2);
  // A long list in meta of objects on lines of their own that look like edges: cuts are
  // guessed inside it, and the piece before says otherwise.
  nlohmann::json meta = m.meta();
  meta["notes"] = nlohmann::json::array();
  for (int i = 0; i < 3000; ++i) meta["notes"].push_back({{"he", i}});
  const std::string text = write_native(m.body, meta, "mm");
  EXPECT_EQ(parse(text, 1024).result, FastParse::kUseReference);
  EXPECT_EQ(parse(text, text.size()).result, FastParse::kDone);
  // The reader reads it all the same, as the reference does.
  std::string error, reference_error;
  auto fast = read_native(text, &error, NativeParser::kSimdjsonFirst);
  auto reference = read_native(text, &reference_error, NativeParser::kReferenceOnly);
  expect_same_document(fast, error, reference, reference_error);
}

TEST(NativeReaderPieces, ADuplicateKeyInTwoPiecesIsRefused) {
  zoo::ZooModel m = zoo::family(60, 0.3, 2);
  std::string text = write_native(m.body, m.meta(), "mm");
  // "units" again at the end, far from the first: a piece of its own has it.
  text.insert(text.rfind("\n}"), ",\n  \"units\": \"mm\"");
  EXPECT_EQ(parse(text, text.size()).result, FastParse::kUseReference);
  EXPECT_EQ(parse(text, 64).result, FastParse::kUseReference);
}

// The text in memory, as a file would give it: a window at a time, never whole.
struct Windowed final : TextSource {
  const std::string& text;
  explicit Windowed(const std::string& t) : text(t) {}
  std::size_t size() const override { return text.size(); }
  bool read(std::size_t begin, std::size_t n, char* out) const override {
    if (begin > text.size() || n > text.size() - begin) return false;
    text.copy(out, n, begin);
    return true;
  }
};

TEST(NativeReaderPieces, CutsFoundAWindowAtATimeAreTheCutsOfTheWholeText) {
  zoo::ZooModel m = zoo::family(300, 0.3, 6);
  const std::string text = write_native(m.body, m.meta(), "mm");
  const MemorySource memory(text.data(), text.size(), text.size());
  const Windowed windowed(text);
  int found = 0;
  for (std::size_t from = 0; from < text.size(); from += 97) {
    Cut a, b;
    const bool in_memory = find_cut_in(memory, from, text.size(), &a);
    ASSERT_EQ(find_cut_in(windowed, from, text.size(), &b), in_memory) << from;
    if (!in_memory) continue;
    ++found;
    EXPECT_EQ(a.comma, b.comma) << from;
    EXPECT_EQ(a.next, b.next) << from;
    EXPECT_EQ(a.kind, b.kind) << from;
  }
  EXPECT_GT(found, 1000);
}

TEST(NativeReaderPieces, ALargeFileIsReadAPieceAtATimeAsTheReferenceReadsIt) {
  // About 10 MB: read from the file a piece at a time (past 8 MB), in two halves.
  zoo::ZooModel m = zoo::family(12000, 0.1, 3);
  const std::string text = write_native(m.body, m.meta(), "mm");
  ASSERT_GT(text.size(), std::size_t(8) << 20);
  const std::string path = (std::filesystem::temp_directory_path() / "kintsugi_pieces_test.json").string();
  auto read_file_as = [&](const std::string& t, NativeParser which, std::string* error) {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    EXPECT_TRUE(f);
    std::fwrite(t.data(), 1, t.size(), f);
    std::fclose(f);
    return read_native_file(path, error, which);
  };
  std::string error, reference_error;
  auto fast = read_file_as(text, NativeParser::kSimdjsonFirst, &error);
  {
    // The file itself, a piece at a time: what the text in memory gives in one piece.
    const int fd = ::open(path.c_str(), O_RDONLY);
    ASSERT_GE(fd, 0);
    Parsed from_file;
    JsonTree root;
    from_file.result = parse_native_simdjson(FileSource(fd, text.size()), &from_file.sink, &root);
    ::close(fd);
    ASSERT_EQ(from_file.result, FastParse::kDone);
    const Parsed whole = parse(text, text.size());
    EXPECT_EQ(from_file.sink.elements, whole.sink.elements);
    EXPECT_EQ(JsonView(&root, 0).dump(), whole.root);
  }
  auto reference = read_native(text, &reference_error, NativeParser::kReferenceOnly);
  expect_same_document(fast, error, reference, reference_error);
  // A bad element in the second half, and broken JSON: refused in the whole text's words.
  std::string bad_element = text;
  const std::size_t last_face = text.rfind("{\"id\": ", text.find("\"shells\""));
  bad_element.replace(last_face, 7, "{\"id\": -4, \"x\": ");
  std::string broken = text;
  broken.insert(text.size() * 3 / 4, "\"");
  for (const std::string& t : {bad_element, broken}) {
    std::string fast_error, whole_error;
    EXPECT_FALSE(read_file_as(t, NativeParser::kSimdjsonFirst, &fast_error));
    EXPECT_FALSE(read_file_as(t, NativeParser::kReferenceOnly, &whole_error));
    EXPECT_EQ(fast_error, whole_error);
    EXPECT_FALSE(fast_error.empty());
  }
  std::remove(path.c_str());
}

}  // namespace
}  // namespace kintsugi::io
