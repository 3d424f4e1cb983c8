// The registry: the passes the build found (repair/passes.inc, generated from the
// repair/pass_*.cpp files) and Table 1 from spec/table1.json (embedded at build time).
#include "repair/pass.h"

#include "repair/detect.h"

#include <algorithm>
#include <array>
#include <nlohmann/json.hpp>
#include <stdexcept>

#define KINTSUGI_PASS_ENTRY(name) extern const ::kintsugi::Pass name;
namespace kintsugi::registered_passes {
#include "passes.inc"
}
#undef KINTSUGI_PASS_ENTRY

namespace kintsugi {

extern const char* const kTable1Json;  // table1_json.cpp, generated from spec/table1.json

const std::vector<const Pass*>& passes() {
  static const std::vector<const Pass*> all = [] {
#define KINTSUGI_PASS_ENTRY(name) &registered_passes::name,
    std::vector<const Pass*> v = {
#include "passes.inc"
    };
#undef KINTSUGI_PASS_ENTRY
    std::stable_sort(v.begin(), v.end(),
                     [](const Pass* a, const Pass* b) { return problem_order(a->type) < problem_order(b->type); });
    for (std::size_t i = 1; i < v.size(); ++i)
      if (v[i]->type == v[i - 1]->type)
        throw std::logic_error(std::string("two passes repair ") + problem_name(v[i]->type));
    return v;
  }();
  return all;
}

const Pass* find_pass(ProblemType t) {
  for (const Pass* p : passes())
    if (p->type == t) return p;
  return nullptr;
}

const std::vector<ProblemType>& may_create(ProblemType t) {
  static const std::array<std::vector<ProblemType>, 11> table = [] {
    std::array<std::vector<ProblemType>, 11> out;
    const nlohmann::json j = nlohmann::json::parse(kTable1Json);
    for (ProblemType col : kAllProblemTypes)
      for (const auto& row : j.at("can_cause").at(problem_name(col))) {
        auto r = problem_from_name(row.get<std::string>());
        if (!r) throw std::logic_error("spec/table1.json names an unknown problem type: " + row.get<std::string>());
        out[std::size_t(problem_order(col) - 1)].push_back(*r);
      }
    return out;
  }();
  return table[std::size_t(problem_order(t) - 1)];
}

namespace {
std::vector<Problem> only(std::vector<Problem> all, ProblemType t) {
  std::vector<Problem> mine;
  for (Problem& p : all)
    if (p.type == t) mine.push_back(std::move(p));
  return mine;
}
}  // namespace

std::vector<Problem> detect_for(const Pass& p, const Body& b, const geo::Tolerances& tol) {
  if (p.detect_all) return p.detect_all(b, tol);
  return only(detect(b, tol).problems, p.type);
}

std::vector<Problem> detect_near_for(const Pass& p, const Body& b, const geo::Tolerances& tol, const Neighbourhood& n) {
  if (p.detect_near) return p.detect_near(b, tol, n);
  return detect_near_of_type(b, tol, n, p.type);
}

}  // namespace kintsugi
