#include "apps/report_json.h"

namespace kintsugi::cli {

nlohmann::json counts_json(const Counts& c) {
  return {{"vertices", c.vertices}, {"edges", c.edges},   {"faces", c.faces},
          {"loops", c.loops},       {"shells", c.shells}, {"border_cycles", c.border_cycles}};
}

nlohmann::json violation_json(const Violation& v) {
  nlohmann::json j = {{"invariant", v.invariant}, {"elements", v.elements}, {"detail", v.detail}};
  if (v.distance != 0.0) j["distance"] = v.distance;
  return j;
}

}  // namespace kintsugi::cli
