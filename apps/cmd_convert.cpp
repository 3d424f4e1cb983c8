#include "apps/args.h"
#include "apps/commands.h"
#include "apps/model_files.h"

#include <ostream>

namespace kintsugi::cli {

int cmd_convert(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err) {
  const std::string help = "usage: kintsugi convert IN OUT\n\n"
                           "Reads IN and writes OUT, each in the format its extension names: " +
                           formats_supported() +
                           ".\nThe model is checked on reading; OUT is written atomically and never over IN.\n"
                           "Exit: 0 converted, 2 unreadable input, unwritable output or bad usage.\n";
  Args args;
  std::string error;
  if (!args.parse(argv, {}, {"--help"}, &error)) {
    err << "kintsugi convert: " << error << "\n" << help;
    return kExitBadInput;
  }
  if (args.has("--help")) {
    out << help;
    return kExitOk;
  }
  if (args.positional().size() != 2) {
    err << "kintsugi convert: expected IN and OUT\n" << help;
    return kExitBadInput;
  }
  auto model = load_model(args.positional()[0], &error);
  if (!model) {
    err << "kintsugi convert: " << error << "\n";
    return kExitBadInput;
  }
  if (!save_model(*model, args.positional()[1], args.positional()[0], &error)) {
    err << "kintsugi convert: " << error << "\n";
    return kExitBadInput;
  }
  return kExitOk;
}

}  // namespace kintsugi::cli
