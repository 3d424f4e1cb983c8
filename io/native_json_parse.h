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

}  // namespace kintsugi::io
