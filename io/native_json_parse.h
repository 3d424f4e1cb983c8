// The native reader's two parsers (internal to io/): both hand each element of the
// top-level element arrays ("vertices" ... "shells") to an ElementSink as a JsonTree as
// soon as it is complete, and build the rest of the document (the top level, `meta`) as
// one more tree, whose element arrays are there but empty. The fast one reads the common
// elements straight into the sink's descriptions instead, where the sink lets it
// (ElementSink::direct, io/native_json_typed.h).
//
// simdjson's On-Demand parser (native_json_parse_simdjson.cpp) reads a document several
// times faster than nlohmann's; it gives up (kUseReference) on anything out of the
// ordinary — a syntax error, a duplicate key, nesting deeper than kMaxNativeDepth, a number
// outside 64 bits or a double — and the reader then parses the text again with nlohmann's
// SAX parser (native_json_reader.cpp), whose messages name the line and column. So every
// refusal has one wording, whichever parser met the document first, and the two accept
// the same documents as the same trees (`NativeReader.SimdjsonAndReferenceAgree...`, and the
// json_reader fuzz target compares them on every input).
#pragma once

#include "io/json_tree.h"
#include "io/text_source.h"
#include "kernel/assemble.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>

namespace kintsugi::io {

// The reader's bounds and tolerances (spec/file-format.md).
inline constexpr std::uint64_t kMaxId = 0xFFFFFFFEu;      // 0xFFFFFFFF is the invalid handle
inline constexpr std::uint64_t kMaxEdgeId = 0x7FFFFFFEu;  // its half-edges must be ids too
inline constexpr double kUnitTolerance = 1e-9;            // unit length and perpendicularity

// The element arrays, in the order the reader checks them.
enum ElementKind { kVertices, kEdges, kLoops, kFaces, kShells, kElementKinds };
inline const char* const kElementKeys[kElementKinds] = {"vertices", "edges", "loops", "faces", "shells"};

class ElementSink {
 public:
  virtual ~ElementSink() = default;
  // Element `index` of the top-level array `kind`, complete.
  virtual void element(ElementKind kind, std::size_t index, JsonView value) = 0;
  // `count` more elements of array `kind` follow, in a piece of `bytes` of the document
  // (when the parser knows it before them).
  virtual void expect(ElementKind kind, std::size_t count, std::size_t bytes) = 0;

  // Typed reading (io/native_json_typed.h): the descriptions the parser may append the
  // next element of `kind` to itself, when it has read and checked it exactly as element()
  // would have; null (the default): every element comes through element().
  virtual BodyDescription* direct(ElementKind) { return nullptr; }
  // Element `index` of `kind` was appended to direct(kind).
  virtual void appended(ElementKind, std::size_t) {}
};

enum class FastParse { kDone, kUseReference };

// The padding the fast parser needs past the end of the text.
std::size_t simdjson_padding();

// -- Pieces --
//
// simdjson indexes a whole document before it is read: four bytes per token, written to
// fresh memory and read back, 1.6 times the text of a native file. So a large document
// is read in pieces of about a megabyte, each copied into one reused buffer and parsed by
// one reused parser: cut between two elements of an element array, a piece is read as
// `{"":[` + its text + `]}` (without the first at the document's start, the second at its
// end), where the text of the document has the comma between the two elements and then
// white space with a line break in it. The cut is a guess made from the bytes alone; the
// parses check it. When every piece is valid JSON, each but the last ends inside an
// element array of the kind guessed for the next with at least one element, and each but
// the first continues that array in its first member "", then the whole text is valid
// JSON and its element arrays are the pieces' elements in order (the top levels are joined
// refusing a key that two pieces have). Anything else: kUseReference.
//
// A run is text[begin, end): begin is 0 or where an element starts after a cut (`continued`:
// the kind of its array, else -1), end is the text's size or a cut's comma.
using ElementCounts = std::array<std::size_t, kElementKinds>;
struct Run {
  std::size_t begin = 0, end = 0;
  int continued = -1;
  std::size_t piece_bytes = std::size_t(1) << 20;  // each piece ends at the first cut past this
  // A run of several pieces counts its elements first, so that the sink makes room for them
  // once (a description grown as it is filled is copied, and on a virtual machine fresh
  // memory is most of the cost of reading): this says how many to tell the sink of, given
  // the run's counts (none: the counts). The halves make room in the first half's
  // descriptions for the second's.
  std::function<ElementCounts(const ElementCounts&)> room;
};
struct RunEnds {
  std::size_t first_count = 0;  // elements of the continued array in the run
  int last_kind = -1;           // the run's last member, if an element array: its kind
  std::size_t last_count = 0;   // ... and its elements in the run
};
// Parses a run of `text` (io/text_source.h), delivering elements to `sink` (the continued
// array's from index 0, each array's in order) and building the rest of the run's top
// level in `root` (element arrays there but empty). On kUseReference the sink may have seen
// some elements already: the caller starts again from scratch.
FastParse parse_native_simdjson_run(const TextSource& text, const Run& run, ElementSink* sink, JsonTree* root,
                                    RunEnds* ends);

// A whole document, as one run of pieces of `piece_bytes`.
FastParse parse_native_simdjson(const TextSource& text, ElementSink* sink, JsonTree* root,
                                std::size_t piece_bytes = Run{}.piece_bytes);
// The same of text[0, size) in memory, with simdjson_padding() readable bytes past `size`
// up to `capacity`.
FastParse parse_native_simdjson(const char* text, std::size_t size, std::size_t capacity, ElementSink* sink,
                                JsonTree* root, std::size_t piece_bytes = Run{}.piece_bytes);

// -- Two halves at once (io/native_json_halves.cpp) --
//
// A large document is parsed on two threads, each a run: cut between two elements of the
// element array that spans its middle, the first half is text[0, comma), the second
// text[next, size), read as above.

// Parses `text` in two halves, elements of the first half to `head` (with `head_root` the
// top level), of the second to `tail` (their indices counted from 0 in the cut array; the
// caller merges the two top levels and must refuse a key that both have). *cut: the array
// cut; *head_count: its elements in the first half.
FastParse parse_native_simdjson_halves(const TextSource& text, ElementSink* head, JsonTree* head_root, ElementSink* tail,
                                       JsonTree* tail_root, ElementKind* cut, std::size_t* head_count,
                                       std::size_t piece_bytes = Run{}.piece_bytes);
FastParse parse_native_simdjson_halves(const char* text, std::size_t size, std::size_t capacity, ElementSink* head,
                                       JsonTree* head_root, ElementSink* tail, JsonTree* tail_root, ElementKind* cut,
                                       std::size_t* head_count, std::size_t piece_bytes = Run{}.piece_bytes);

// Where the text can be cut (above), searching forward from `from` for at most `reach`
// bytes: false when there is no such place. find_cut: from the middle.
struct Cut {
  std::size_t comma = 0, next = 0;
  ElementKind kind = kVertices;  // guessed from the keys of the element at `next`
};
bool find_cut_at(const char* text, std::size_t size, std::size_t from, std::size_t reach, Cut* cut);
bool find_cut(const char* text, std::size_t size, std::size_t reach, Cut* cut);
// The same in a source not in memory, read a window at a time (a line break with more white
// space around it than the window holds is passed over: the cut is a guess either way).
bool find_cut_in(const TextSource& text, std::size_t from, std::size_t reach, Cut* cut);

}  // namespace kintsugi::io
