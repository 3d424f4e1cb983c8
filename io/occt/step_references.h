// A check of a STEP file's entity references before OpenCASCADE reads it: OpenCASCADE
// drops an entity that refers to one the file does not define, so a face whose bound is
// missing would silently vanish and leave a hole in the model.
#pragma once

#include <string>
#include <string_view>

namespace kintsugi::io {

// Scans the DATA sections of a STEP file (ISO 10303-21 text: strings, comments and
// multi-line instances allowed) for a reference #n to an entity that is not defined.
// Returns "" when every reference resolves, else a message naming the first one:
// "entity #16 refers to #9999, which the file does not define".
std::string step_dangling_reference(std::string_view text);

}  // namespace kintsugi::io
