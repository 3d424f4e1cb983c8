#include "kernel/violation.h"

#include <sstream>

namespace kintsugi {

std::string to_string(const Violation& v) {
  std::ostringstream os;
  os << v.invariant;
  if (!v.elements.empty()) {
    os << " [";
    for (std::size_t i = 0; i < v.elements.size(); ++i) os << (i ? " " : "") << v.elements[i];
    os << "]";
  }
  if (!v.detail.empty()) os << ": " << v.detail;
  return os.str();
}

}  // namespace kintsugi
