// A small, strict command-line parser: positional arguments, `--name value` options and
// `--flag` switches declared up front. Anything undeclared is an error that names it.
#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace kintsugi::cli {

class Args {
 public:
  // `options` take a value; `flags` do not. Returns false with *error set on an unknown
  // option, a missing value, or a repeated option.
  bool parse(const std::vector<std::string>& argv, const std::set<std::string>& options,
             const std::set<std::string>& flags, std::string* error);

  const std::vector<std::string>& positional() const { return positional_; }
  bool has(const std::string& name) const { return values_.count(name) || flags_.count(name); }
  std::optional<std::string> value(const std::string& name) const;

  // Typed values; on a malformed value they set *error naming the option and return nullopt.
  std::optional<double> number(const std::string& name, double fallback, std::string* error) const;
  std::optional<long long> integer(const std::string& name, long long fallback, long long lo, long long hi,
                                   std::string* error) const;

  // Of the given output options, the first whose value is not a file name in an existing
  // folder (empty, ends in '/', names a folder, or its folder is missing), names the
  // input file `input`, or names the same file as another of them — with the reason;
  // nullopt when all are fine. Commands with several outputs check them all before writing
  // any: one found bad after another was written would leave that one behind with exit 2.
  std::optional<std::string> bad_output(const std::vector<std::string>& options, const std::string& input) const;

 private:
  std::vector<std::string> positional_;
  std::map<std::string, std::string> values_;
  std::set<std::string> flags_;
};

// Parses a whole string as a finite double.
std::optional<double> parse_double(const std::string& s);

}  // namespace kintsugi::cli
