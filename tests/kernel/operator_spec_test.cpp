// spec/operators.md and the kernel agree: every operator the kernel exports
// (kernel/operator_list.h) has its row in the spec's table with the same Δ, every row
// names an exported operator, and each operator's file holds its query and its action.
#include "kernel/operator_list.h"

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace kintsugi {
namespace {

std::string read(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> out;
  std::string cur;
  for (std::size_t i = 1; i < line.size(); ++i) {
    if (line[i] == '|') {
      std::size_t a = cur.find_first_not_of(' '), b = cur.find_last_not_of(' ');
      out.push_back(a == std::string::npos ? "" : cur.substr(a, b - a + 1));
      cur.clear();
    } else {
      cur += line[i];
    }
  }
  return out;
}

// "+1", "−1" (U+2212), "-1" or "" (no change).
int count_change(const std::string& c) {
  if (c.empty()) return 0;
  std::string s = c;
  const std::string minus = "\u2212";
  if (s.rfind(minus, 0) == 0) s = "-" + s.substr(minus.size());
  return std::stoi(s);
}

struct Row {
  int line;
  CountDelta delta;
};

// The operator table: rows whose first cell is `name(...)` or `name` followed by words.
std::multimap<std::string, Row> spec_rows(const std::string& text) {
  std::multimap<std::string, Row> rows;
  std::istringstream in(text);
  std::string line;
  std::vector<std::string> header;
  int n = 0;
  while (std::getline(in, line)) {
    ++n;
    if (line.rfind("|", 0) != 0) {
      header.clear();
      continue;
    }
    auto c = cells(line);
    if (header.empty()) {
      header = c;
      continue;
    }
    if (c.empty() || c[0].rfind("---", 0) == 0 || c[0].size() < 3 || c[0][0] != '`') continue;
    std::size_t end = c[0].find_first_of("(`", 1);
    std::string name = c[0].substr(1, end - 1);
    std::map<std::string, int> by_column;
    for (std::size_t i = 1; i < c.size() && i < header.size(); ++i)
      if (header[i].rfind("Δ", 0) == 0) by_column[header[i]] = count_change(c[i]);
    CountDelta d{by_column["ΔV"], by_column["ΔE"], by_column["ΔF"], by_column["ΔL"],
                 by_column["ΔS"], by_column["ΔB"], by_column["ΔR"], by_column["ΔH"]};
    rows.insert({name, {n, d}});
  }
  return rows;
}

TEST(OperatorSpec, EveryExportedOperatorHasItsRowWithItsDelta) {
  std::string text = read(std::string(KINTSUGI_SOURCE_DIR) + "/spec/operators.md");
  ASSERT_FALSE(text.empty()) << "spec/operators.md not found";
  auto rows = spec_rows(text);
  ASSERT_GT(rows.size(), 10u) << "the operator table was not found";
  for (const auto& op : kOperators) {
    std::string name(op.name);
    auto [first, last] = rows.equal_range(name);
    EXPECT_NE(first, last) << "spec/operators.md has no row for " << name;
    for (auto it = first; it != last; ++it) {
      const CountDelta& d = it->second.delta;
      EXPECT_TRUE(d == op.delta || (op.has_variant && d == op.variant))
          << "spec/operators.md line " << it->second.line << ": the row for " << name
          << " has another Δ than kernel/operator_list.h";
    }
  }
  for (const auto& [name, row] : rows)
    EXPECT_NE(find_operator(name), nullptr) << "spec/operators.md line " << row.line << " names " << name
                                            << ", which the kernel does not export (kernel/operator_list.h)";
}

TEST(OperatorSpec, EachOperatorFileHoldsItsQueryAndItsAction) {
  for (const auto& op : kOperators) {
    std::string text = read(std::string(KINTSUGI_SOURCE_DIR) + "/" + std::string(op.file));
    ASSERT_FALSE(text.empty()) << op.file << " not found";
    std::string name(op.name);
    EXPECT_NE(text.find("euler::can_" + name + "("), std::string::npos) << op.file << " lacks can_" << name;
    EXPECT_NE(text.find("> euler::" + name + "("), std::string::npos) << op.file << " lacks " << name;
  }
}

}  // namespace
}  // namespace kintsugi
