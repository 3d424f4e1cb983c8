#include "zoo/zoo.h"

namespace kintsugi::zoo {

nlohmann::json defect_json(const KnownDefect& d) {
  return {{"type", problem_name(d.type)}, {"elements", d.elements}, {"size", d.size}};
}

nlohmann::json ZooModel::meta() const {
  nlohmann::json j;
  j["tolerance"] = tolerance;
  j["defects"] = nlohmann::json::array();
  for (const KnownDefect& d : defects) j["defects"].push_back(defect_json(d));
  j["source"] = source;
  return j;
}

}  // namespace kintsugi::zoo
