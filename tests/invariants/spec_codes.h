// The violation codes listed in a table of spec/invariants.md: rows that start with
// "| `code` |", between the heading `from` (or the start) and the heading `to` (or the
// end). The tests check that every listed code has a case that breaks it alone.
#pragma once

#include <fstream>
#include <regex>
#include <set>
#include <string>

namespace kintsugi::test {

inline std::set<std::string> spec_codes(const std::string& path, const std::string& from, const std::string& to) {
  std::ifstream in(path);
  std::set<std::string> out;
  bool inside = from.empty();
  const std::regex row(R"(^\|\s*`([a-z_]+)`\s*\|)");
  for (std::string line; std::getline(in, line);) {
    if (!from.empty() && line.rfind(from, 0) == 0) inside = true;
    else if (!to.empty() && line.rfind(to, 0) == 0) inside = false;
    std::smatch m;
    if (inside && std::regex_search(line, m, row)) out.insert(m[1]);
  }
  return out;
}

}  // namespace kintsugi::test
