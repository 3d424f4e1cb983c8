// Typed reading of the native format's common elements (internal to io/): straight from
// simdjson's On-Demand values into the descriptions, without the small tree per element
// that DocumentReader checks (io/native_json_reader.cpp). That tree is most of the cost of
// reading a large file once simdjson has indexed it.
//
// It reads only what it can read exactly as the tree path would, and checks everything the
// tree path checks of it: vertices, edges with no curve, a line or a circle, loops, faces with
// no surface or an analytic one, shells, each with its keys unescaped, once each, and every
// value of the expected type and in range. Anything else — a key it does not know, a key
// twice, an id written 1.0, a direction not of unit length, a B-spline — it leaves alone
// (kNotTyped): the element is read again from its start by the tree path, which then
// decides and words any refusal. So an element is accepted by one path exactly when the
// other would accept it, as the same description (`NativeReaderParsers.AgreeOn*`, and the
// json_reader fuzz target, compare the fast reader with nlohmann's on every input).
#pragma once

#include "io/native_json_parse.h"

#include <simdjson.h>

#include <cstdint>

namespace kintsugi::io {

// A JSON number as the tree path types it (and nlohmann does): with a fraction or an
// exponent a double, else without a minus sign unsigned, with one signed ("-0" too).
struct JsonNumber {
  enum Type { kFloat, kSigned, kUnsigned } type = kUnsigned;
  double d = 0;
  std::int64_t i = 0;
  std::uint64_t u = 0;
  // The value as the reader's number() reads it (JsonView::as_double).
  double as_double() const { return type == kFloat ? d : type == kSigned ? double(i) : double(u); }
};
// Reads a number value; false on a simdjson error (a number outside 64 bits or a double,
// which the reference parser words).
bool read_json_number(simdjson::ondemand::value& v, JsonNumber* out);

enum class Typed {
  kRead,      // appended to the descriptions
  kNotTyped,  // nothing appended, nothing unescaped: reset the object and read it as a tree
  kError,     // simdjson failed on the text: the parse gives up (kUseReference)
};

// Element `kind` from its object `o` (just begun) into `d`.
Typed read_typed_element(simdjson::ondemand::object& o, ElementKind kind, BodyDescription* d);

}  // namespace kintsugi::io
