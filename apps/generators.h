// The models `kintsugi generate` can write, with their options. Each generator reads
// its options from parsed arguments and returns a model (body + meta) or throws
// std::invalid_argument naming the bad option.
#pragma once

#include "apps/args.h"
#include "apps/model_files.h"

#include <functional>
#include <set>
#include <string>
#include <vector>

namespace kintsugi::cli {

struct Generator {
  std::string name;
  std::string options_help;         // one line per option, for --list and --help
  std::set<std::string> options;    // accepted options taking a value
  std::set<std::string> flags;      // accepted switches
  std::function<Model(const Args&)> make;
};

const std::vector<Generator>& generators();

}  // namespace kintsugi::cli
