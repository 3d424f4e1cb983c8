#include "problems/problem.h"

namespace kintsugi {

std::string element_name(const Element& e) {
  return std::visit([](auto h) { return h.str(); }, e);
}

const char* measure_name(Measure m) {
  switch (m) {
    case Measure::length: return "length";
    case Measure::area: return "area";
    case Measure::width: return "width";
    case Measure::distance: return "distance";
    case Measure::diameter: return "diameter";
  }
  return "?";
}

std::vector<std::string> element_names(const Problem& p) {
  std::vector<std::string> out;
  out.reserve(p.elements.size());
  for (const Element& e : p.elements) out.push_back(element_name(e));
  return out;
}

std::string subcase_name(const Problem& p) {
  switch (p.type) {
    case ProblemType::face_gap:
    case ProblemType::edge_gap:
    case ProblemType::multi_face_gap:
      return p.subcase.shares_vertex ? "shares a vertex with another gap" : "";
    case ProblemType::pinched_face: {
      const char* where = p.subcase.location == PinchLocation::necking   ? "necking"
                          : p.subcase.location == PinchLocation::spiking ? "spiking"
                                                                         : "bossing";
      return std::string(where) + (p.subcase.configuration == PinchConfiguration::straight ? "/straight" : "/complex");
    }
    default: return "";
  }
}

}  // namespace kintsugi
