// The native JSON reader on arbitrary bytes: it must refuse or accept without crashing,
// hanging, or undefined behaviour; and whatever it accepts must survive write → read as
// an equal body, written identically the second time. A violation aborts (the fuzzer
// reports it).
#include "fuzz/die.h"
#include "io/native_json.h"

#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

using namespace kintsugi;

using fuzz::die;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string error;
  auto doc = io::read_native(std::string_view(reinterpret_cast<const char*>(data), size), &error);
  if (!doc) {
    if (error.empty()) die("refused without a message");
    return 0;
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
