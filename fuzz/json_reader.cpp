// The native JSON reader on arbitrary bytes: it must refuse or accept without crashing,
// hanging, or undefined behaviour; its parsers (simdjson first, whole and in two halves;
// nlohmann's alone) must give the same verdict, message and body; and whatever it accepts must survive
// write → read as an equal body, written identically the second time. A violation aborts
// (the fuzzer reports it).
#include "fuzz/die.h"
#include "io/native_json.h"

#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

using namespace kintsugi;

using fuzz::die;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  std::string error, reference_error;
  auto doc = io::read_native(input, &error);
  auto reference = io::read_native(input, &reference_error, io::NativeParser::kReferenceOnly);
  if (bool(doc) != bool(reference))
    die(doc ? "simdjson accepted what the reference refused: " + reference_error
            : "simdjson refused what the reference accepted: " + error);
  if (!doc) {
    if (error.empty()) die("refused without a message");
    if (error != reference_error) die("the parsers word a refusal differently:\n" + error + "\n" + reference_error);
    std::string halves_error;
    if (io::read_native(input, &halves_error, io::NativeParser::kSimdjsonHalves))
      die("simdjson in halves accepted what the others refused: " + reference_error);
    if (halves_error != reference_error)
      die("read in halves, a refusal worded differently:\n" + halves_error + "\n" + reference_error);
    return 0;
  }
  std::string differs;
  if (!reference->body.equals(doc->body, &differs)) die("the parsers read different bodies: " + differs);
  if (reference->meta != doc->meta || reference->units != doc->units) die("the parsers read different meta or units");
  {
    std::string halves_error;
    auto halves = io::read_native(input, &halves_error, io::NativeParser::kSimdjsonHalves);
    if (!halves) die("simdjson in halves refused what the others accepted: " + halves_error);
    if (!reference->body.equals(halves->body, &differs)) die("read in halves, a different body: " + differs);
    if (reference->meta != halves->meta || reference->units != halves->units) die("read in halves, different meta or units");
  }
  const std::string text = io::write_native(doc->body, doc->meta, doc->units);
  auto again = io::read_native(text, &error);
  if (!again) die("refused its own output: " + error + "\n" + text);
  std::string why;
  if (!again->body.equals(doc->body, &why)) die("write -> read changed the body: " + why);
  if (again->meta != doc->meta || again->units != doc->units) die("write -> read changed meta or units");
  if (io::write_native(again->body, again->meta, again->units) != text) die("second write differs");
  return 0;
}
