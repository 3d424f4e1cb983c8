// The verbs of the `kintsugi` program. Each lives in apps/cmd_<verb>.cpp and prints its
// own --help. Exit codes: 0 success, 1 the model is invalid (check), 2 bad input or usage,
// 3 some files failed (batch).
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace kintsugi::cli {

constexpr int kExitOk = 0;
constexpr int kExitInvalid = 1;
constexpr int kExitBadInput = 2;
constexpr int kExitSomeFailed = 3;

struct Command {
  const char* name;
  const char* summary;
  int (*run)(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
  bool hidden = false;  // not listed by --help (batch-file: batch's child)
};

const std::vector<Command>& commands();

// The whole command line after the program name: finds the verb and runs it. Exceptions
// become a message on `err` and kExitBadInput (apps/dispatch.cpp).
int run_kintsugi(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

int cmd_generate(const std::vector<std::string>&, std::ostream&, std::ostream&);
int cmd_check(const std::vector<std::string>&, std::ostream&, std::ostream&);
int cmd_inject(const std::vector<std::string>&, std::ostream&, std::ostream&);
int cmd_measure(const std::vector<std::string>&, std::ostream&, std::ostream&);
int cmd_detect(const std::vector<std::string>&, std::ostream&, std::ostream&);
int cmd_convert(const std::vector<std::string>&, std::ostream&, std::ostream&);
int cmd_beautify(const std::vector<std::string>&, std::ostream&, std::ostream&);
int cmd_batch(const std::vector<std::string>&, std::ostream&, std::ostream&);
int cmd_batch_file(const std::vector<std::string>&, std::ostream&, std::ostream&);
int cmd_demo(const std::vector<std::string>&, std::ostream&, std::ostream&);
int cmd_audit(const std::vector<std::string>&, std::ostream&, std::ostream&);
int cmd_view(const std::vector<std::string>&, std::ostream&, std::ostream&);

}  // namespace kintsugi::cli
