#include "apps/args.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>

namespace kintsugi::cli {

std::optional<double> parse_double(const std::string& s) {
  if (s.empty()) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  double v = std::strtod(s.c_str(), &end);
  if (end != s.c_str() + s.size() || errno == ERANGE || !std::isfinite(v)) return std::nullopt;
  return v;
}

bool Args::parse(const std::vector<std::string>& argv, const std::set<std::string>& options,
                 const std::set<std::string>& flags, std::string* error) {
  for (std::size_t i = 0; i < argv.size(); ++i) {
    const std::string& a = argv[i];
    if (a.size() > 1 && a[0] == '-' && !parse_double(a)) {
      if (flags.count(a)) {
        flags_.insert(a);
      } else if (options.count(a)) {
        if (i + 1 >= argv.size()) {
          *error = "option " + a + " needs a value";
          return false;
        }
        if (values_.count(a)) {
          *error = "option " + a + " is given twice";
          return false;
        }
        values_[a] = argv[++i];
      } else {
        *error = "unknown option " + a;
        return false;
      }
    } else {
      positional_.push_back(a);
    }
  }
  return true;
}

std::optional<std::string> Args::value(const std::string& name) const {
  auto it = values_.find(name);
  if (it == values_.end()) return std::nullopt;
  return it->second;
}

std::optional<double> Args::number(const std::string& name, double fallback, std::string* error) const {
  auto v = value(name);
  if (!v) return fallback;
  auto d = parse_double(*v);
  if (!d) *error = "option " + name + " needs a finite number, not '" + *v + "'";
  return d;
}

std::optional<long long> Args::integer(const std::string& name, long long fallback, long long lo, long long hi,
                                       std::string* error) const {
  auto v = value(name);
  if (!v) return fallback;
  char* end = nullptr;
  errno = 0;
  long long x = std::strtoll(v->c_str(), &end, 10);
  if (v->empty() || end != v->c_str() + v->size() || errno == ERANGE || x < lo || x > hi) {
    *error = "option " + name + " needs a whole number from " + std::to_string(lo) + " to " + std::to_string(hi) +
             ", not '" + *v + "'";
    return std::nullopt;
  }
  return x;
}

std::optional<std::string> Args::bad_output(const std::vector<std::string>& options, const std::string& input) const {
  namespace fs = std::filesystem;
  // The same file: one path, or two names of one existing file.
  auto same = [](const fs::path& a, const fs::path& b) {
    std::error_code ec;
    if (a.lexically_normal() == b.lexically_normal()) return true;
    return fs::exists(a, ec) && fs::exists(b, ec) && fs::equivalent(a, b, ec);
  };
  std::vector<std::pair<std::string, fs::path>> seen;
  for (const std::string& option : options) {
    if (!has(option)) continue;
    const fs::path p(*value(option));
    const fs::path folder = p.has_parent_path() ? p.parent_path() : fs::path(".");
    std::error_code ec;
    if (p.empty() || !p.has_filename() || !fs::is_directory(folder, ec) || fs::is_directory(p, ec))
      return option + " '" + p.string() + "' is not a file name in an existing folder";
    if (!input.empty() && same(p, input)) return option + " '" + p.string() + "' would overwrite the input file";
    for (const auto& [other, q] : seen)
      if (same(p, q)) return option + " and " + other + " name the same file '" + p.string() + "'";
    seen.push_back({option, p});
  }
  return std::nullopt;
}

}  // namespace kintsugi::cli
