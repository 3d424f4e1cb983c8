#include "invariants/assemble.h"

#include "invariants/topology_check.h"

namespace kintsugi {

std::optional<Body> assemble(BodyDescription d, AssembleError* error) {
  std::optional<Body> b = assemble_references(std::move(d), error);
  if (!b) return std::nullopt;
  std::vector<Violation> bad = check_topology(*b);
  if (!bad.empty()) {
    if (error) *error = {bad.front().elements.empty() ? "" : bad.front().elements.front(), to_string(bad.front())};
    return std::nullopt;
  }
  return b;
}

}  // namespace kintsugi
