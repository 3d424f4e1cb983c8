// The native reader's two parsers (internal to io/): both hand each element of the
// top-level element arrays ("vertices" ... "shells") to an ElementSink as a JsonTree as
// soon as it is complete, and build the rest of the document (the top level, `meta`) as
// one more tree, whose element arrays are there but empty.
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

#include <cstddef>

namespace kintsugi::io {

// The element arrays, in the order the reader checks them.
enum ElementKind { kVertices, kEdges, kLoops, kFaces, kShells, kElementKinds };
inline const char* const kElementKeys[kElementKinds] = {"vertices", "edges", "loops", "faces", "shells"};

class ElementSink {
 public:
  virtual ~ElementSink() = default;
  // Element `index` of the top-level array `kind`, complete.
  virtual void element(ElementKind kind, std::size_t index, JsonView value) = 0;
  // The array `kind` has `count` elements, in a document of `bytes` (when the parser knows
  // it before them).
  virtual void expect(ElementKind kind, std::size_t count, std::size_t bytes) = 0;
};

enum class FastParse { kDone, kUseReference };

// Parses data[0, size) — with at least 64 readable bytes past `size` (simdjson's padding;
// `capacity` is the whole buffer) — delivering elements to `sink` and building the rest
// in `root`. On kUseReference the sink may have seen some elements already: the caller
// starts again from scratch with the reference parser.
FastParse parse_native_simdjson(const char* data, std::size_t size, std::size_t capacity, ElementSink* sink,
                                JsonTree* root);

// The padding parse_native_simdjson needs past the end of the text.
std::size_t simdjson_padding();

// -- Two halves at once (io/native_json_halves.cpp) --
//
// A large document is parsed on two threads: cut between two elements of the element
// array that spans its middle, the first half read as `text[0, comma) + "]}"` and the
// second as `{"":[` + `text[next, size)`, where text[comma] is the comma between the two
// elements and text(comma, next) white space with a line break in it. The cut is a guess
// made from the bytes alone; the parses check it. When both halves are valid JSON, the
// first ends inside an element array of kind `cut` holding at least one element, and the
// second continues that kind with at least one more, then the whole text is valid JSON
// and its element arrays are the two halves' elements in order (the caller merges the
// two top levels and must refuse a key that both have). Anything else: kUseReference,
// and the caller parses the whole text as one (a refusal is then worded as always).

// The two halves, each as parse_native_simdjson. The first: its last member must be an
// element array (*cut, with *count elements). The second: its first member, "", is the
// rest of array `cut` (*count elements, delivered as indices from 0); it is not a member
// of `root`.
FastParse parse_native_simdjson_head(const char* data, std::size_t size, std::size_t capacity, ElementSink* sink,
                                     JsonTree* root, ElementKind* cut, std::size_t* count);
FastParse parse_native_simdjson_tail(const char* data, std::size_t size, std::size_t capacity, ElementKind cut,
                                     ElementSink* sink, JsonTree* root, std::size_t* count);

// Parses `text` in two halves as above, elements of the first half to `head` (with
// `head_root` the top level), of the second to `tail` (their indices counted from 0 in
// the cut array). Writes two bytes at the cut while the first half is parsed and puts
// them back before returning. *cut: the array cut; *head_count: its elements in the
// first half.
FastParse parse_native_simdjson_halves(char* text, std::size_t size, std::size_t capacity, ElementSink* head,
                                       JsonTree* head_root, ElementSink* tail, JsonTree* tail_root, ElementKind* cut,
                                       std::size_t* head_count);

// Where the text can be cut (above), searching forward from its middle for at most
// `reach` bytes: false when there is no such place.
struct Cut {
  std::size_t comma = 0, next = 0;
  ElementKind kind = kVertices;  // guessed from the keys of the element at `next`
};
bool find_cut(const char* text, std::size_t size, std::size_t reach, Cut* cut);

}  // namespace kintsugi::io
