// assemble(): a body from a reader's description (kernel/assemble.h), checked whole.
#pragma once

#include "kernel/assemble.h"

#include <optional>

namespace kintsugi {

// Builds the body — ids and references checked by the kernel, then check_topology —
// or says what is wrong, naming the element. The journal of the result is empty. The
// body takes the description's geometry: pass it with std::move where it is not needed again.
std::optional<Body> assemble(BodyDescription d, AssembleError* error);

}  // namespace kintsugi
