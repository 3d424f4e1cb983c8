#include "apps/commands.h"
#include "apps/generators.h"

#include <ostream>

namespace kintsugi::cli {

namespace {
void help(std::ostream& os) {
  os << "usage: kintsugi generate NAME [options] -o FILE\n"
        "       kintsugi generate --list\n\n"
        "Writes a built-in model. Formats by extension: "
     << formats_supported() << ".\nModels and their options:\n";
  for (const Generator& g : generators()) os << "  " << g.name << "\n" << g.options_help << "\n";
}
}  // namespace

int cmd_generate(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err) {
  if (argv.empty()) {
    help(err);
    return kExitBadInput;
  }
  if (argv[0] == "--help" || argv[0] == "-h") {
    help(out);
    return kExitOk;
  }
  if (argv[0] == "--list") {
    for (const Generator& g : generators()) out << g.name << "\n" << g.options_help << "\n";
    return kExitOk;
  }
  const Generator* gen = nullptr;
  for (const Generator& g : generators())
    if (g.name == argv[0]) gen = &g;
  if (!gen) {
    err << "kintsugi generate: unknown model '" << argv[0] << "' (kintsugi generate --list shows them)\n";
    return kExitBadInput;
  }
  Args args;
  std::set<std::string> options = gen->options;
  options.insert("-o");
  std::string error;
  std::set<std::string> flags = gen->flags;
  flags.insert("--help");
  if (!args.parse({argv.begin() + 1, argv.end()}, options, flags, &error)) {
    err << "kintsugi generate " << gen->name << ": " << error << "\n";
    return kExitBadInput;
  }
  if (args.has("--help")) {
    out << "usage: kintsugi generate " << gen->name << " [options] -o FILE\n" << gen->options_help << "\n";
    return kExitOk;
  }
  if (!args.positional().empty()) {
    err << "kintsugi generate " << gen->name << ": unexpected argument '" << args.positional()[0] << "'\n";
    return kExitBadInput;
  }
  auto path = args.value("-o");
  if (!path) {
    err << "kintsugi generate " << gen->name << ": -o FILE is required\n";
    return kExitBadInput;
  }
  Model m;
  try {
    m = gen->make(args);
  } catch (const std::invalid_argument& e) {
    err << "kintsugi generate " << gen->name << ": " << e.what() << "\n";
    return kExitBadInput;
  }
  if (!save_model(m, *path, "", &error)) {
    err << "kintsugi generate: " << error << "\n";
    return kExitBadInput;
  }
  return kExitOk;
}

}  // namespace kintsugi::cli
