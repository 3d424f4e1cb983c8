// The native file format: a body's topology and geometry as JSON (spec/file-format.md).
//
// Ids in the file are the body's handles, so element names ("e3", "f1") survive a
// write → read, and writing then reading gives a body that Body::equals the original.
//
// The reader trusts nothing: it checks types, ranges, references and the topology
// invariants (through kintsugi::assemble), and refuses malformed input with a message that
// starts with the JSON pointer (RFC 6901) of the offending place, e.g.
//   "/edges/3/he/1/next: refers to half-edge 99, which does not exist".
// Problems with the document as a whole (too large, empty) have no pointer prefix.
// It never crashes on input, never recurses deeper than a fixed nesting limit, and
// allocates in proportion to the input, which is itself capped at 1 GiB: a piece of the
// text at a time (a megabyte; the whole text only when it cannot be cut, or comes from
// memory), the parser's index of a piece, the descriptions of the elements (read straight
// from the parser, or through a small tree per element for anything out of the common:
// io/native_json_typed.h), and the body they describe.
#pragma once

#include "kernel/body.h"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

namespace kintsugi::io {

// Largest document the reader accepts, in bytes.
inline constexpr std::size_t kMaxNativeBytes = std::size_t(1) << 30;
// Deepest nesting of arrays and objects the reader accepts (the format itself needs 6;
// the rest is room for `meta`).
inline constexpr std::size_t kMaxNativeDepth = 64;

struct NativeDocument {
  Body body;
  nlohmann::json meta = nlohmann::json::object();  // free-form, preserved verbatim
  std::string units = "mm";
};

// Which parser reads the text. kSimdjsonFirst: simdjson, several times faster, falling
// back on nlohmann's for anything out of the ordinary (a syntax error, a duplicate key, deep
// nesting), so a refusal is worded the same either way (io/native_json_parse.h).
// A document of 8 MiB or more is parsed by simdjson in two halves on two threads, where
// two may be used (KINTSUGI_THREADS, else the machine's hardware threads) (io/native_json_parse.h: cut between two elements near the middle;
// anything out of the ordinary reads it whole again), which gives the same document.
// kSimdjsonHalves: in two halves whatever its size, for the tests and the fuzzer.
// kReferenceOnly: nlohmann's alone, the reference the tests and the fuzzer compare with.
enum class NativeParser { kSimdjsonFirst, kSimdjsonHalves, kReferenceOnly };

// Parses text; on failure returns nullopt and sets *error (if given) to a message that
// starts with the JSON pointer of the offending place.
std::optional<NativeDocument> read_native(std::string_view text, std::string* error,
                                          NativeParser parser = NativeParser::kSimdjsonFirst);

// The document for `b` (live elements only), streamed from the body without building a
// JSON document (io/native_json_writer.cpp). Strings in `meta` that are not UTF-8 are
// written with U+FFFD in their place, and a non-finite number (which no valid body has)
// is written as null, which the reader then refuses. Throws only std::bad_alloc.
std::string write_native(const Body& b, const nlohmann::json& meta = nlohmann::json::object(),
                         const std::string& units = "mm");

// Receives a document piece by piece, in order; returns false to stop (a failed write).
using ChunkSink = std::function<bool(std::string_view)>;

// The same bytes as write_native, handed to `sink` in pieces of about 1 MiB, so the
// whole document is never in memory. Returns false when the sink did (and stops there).
bool write_native_to(const Body& b, const nlohmann::json& meta, const std::string& units, const ChunkSink& sink);

// write_native(b, meta, units) written to `path` as write_file_atomically does, but
// streamed: memory stays at the 1 MiB buffer however large the body.
bool write_native_file(const std::string& path, const Body& b, const nlohmann::json& meta, const std::string& units,
                       std::string* error, const std::string& must_not_overwrite = "");

// Reads a whole file into memory and parses it. Refuses files over kMaxNativeBytes and
// paths that cannot be read; every message starts with the path ("model.json: /faces/2: ...").
std::optional<NativeDocument> read_native_file(const std::string& path, std::string* error,
                                               NativeParser parser = NativeParser::kSimdjsonFirst);

// Writes `contents` to `path` so that `path` holds either its old contents or all of the
// new ones, never a part: writes a temporary file in the same directory, fsyncs it, and
// renames it over `path`. Refuses (returns false, *error set) when `path` is the same file
// as `must_not_overwrite` (typically the input of a repair). On failure no temporary file
// is left behind.
bool write_file_atomically(const std::string& path, const std::string& contents, std::string* error,
                           const std::string& must_not_overwrite = "");

// write_file_atomically with the contents produced piece by piece (io/atomic_file.cpp):
// `produce` is called once with a sink that appends to the temporary file. When it
// returns false or throws, or a write fails, nothing is renamed and the temporary file
// is removed.
bool write_file_atomically_streamed(const std::string& path, const std::function<bool(const ChunkSink&)>& produce,
                                    std::string* error, const std::string& must_not_overwrite = "");

}  // namespace kintsugi::io
