#include "geometry/freeform.h"

#include <stdexcept>

namespace kintsugi::geo {

namespace {
const FreeformBackend* g_backend = nullptr;
}

void set_freeform_backend(const FreeformBackend* b) { g_backend = b; }
const FreeformBackend* freeform_backend() { return g_backend; }

std::string freeform_unavailable() {
  return g_backend ? std::string()
                   : std::string("free-form geometry (B-spline, revolution, extrusion, offset) needs OpenCASCADE, "
                                 "which this build of kintsugi does not have");
}

const FreeformBackend& require_freeform() {
  if (!g_backend) throw std::runtime_error(freeform_unavailable());
  return *g_backend;
}

}  // namespace kintsugi::geo
