#include "apps/args.h"
#include "apps/commands.h"
#include "invariants/element_geometry.h"
#include "repair/beautify.h"
#include "zoo/zoo.h"

#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <iomanip>
#include <ostream>
#include <sstream>

namespace kintsugi::cli {

namespace {
const char* kHelp =
    "usage: kintsugi demo\n\n"
    "Runs beautify on the paper's test objects that the zoo can build (docs/paper-objects.md)\n"
    "and prints, per object, faces/edges before and after next to the counts of its clean\n"
    "model. Objects with problems of a type no pass repairs yet (kintsugi --help lists\n"
    "the passes) are marked as not fully repaired, naming those types.\n";
}

void demo_object(int n, std::ostream& out);

int cmd_demo(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err) {
  Args args;
  std::string error;
  if (!args.parse(argv, {}, {"--help"}, &error) || !args.positional().empty()) {
    err << "kintsugi demo: " << (error.empty() ? "no arguments expected" : error) << "\n" << kHelp;
    return kExitBadInput;
  }
  if (args.has("--help")) {
    out << kHelp;
    return kExitOk;
  }
  out << "object  faces before -> after (expected)  edges before -> after (expected)  seconds  note\n";
  for (int n = 1; n <= 10; ++n) {
    // Each object runs in a child process, so a crash in one (a bug elsewhere) is
    // reported for that object and the demo goes on.
    int fds[2];
    if (pipe(fds) != 0) {
      err << "kintsugi demo: pipe failed\n";
      return kExitBadInput;
    }
    out.flush();
    pid_t pid = fork();
    if (pid == 0) {
      close(fds[0]);
      std::ostringstream line;
      demo_object(n, line);
      std::string s = line.str();
      ssize_t w = write(fds[1], s.data(), s.size());
      (void)w;
      _exit(0);
    }
    close(fds[1]);
    std::string text;
    char buf[512];
    for (ssize_t k; (k = read(fds[0], buf, sizeof buf)) > 0;) text.append(buf, std::size_t(k));
    close(fds[0]);
    int status = 0;
    if (pid > 0) waitpid(pid, &status, 0);
    if (pid < 0 || !WIFEXITED(status))
      out << std::setw(6) << n << "  crashed" << (pid > 0 && WIFSIGNALED(status) ? " (signal " + std::to_string(WTERMSIG(status)) + ")" : "")
          << ": not a beautify result; a bug to report\n";
    else
      out << text;
  }
  return kExitOk;
}

void demo_object(int n, std::ostream& out) {
  {
    zoo::ZooModel m, clean;
    try {
      m = zoo::paper_object(n, false);
      clean = zoo::paper_object(n, true);
    } catch (const std::exception& e) {
      out << std::setw(6) << n << "  could not be built (" << e.what() << ")\n";
      return;
    }
    geo::Tolerances tol = geo::Tolerances::for_model(m.tolerance, model_size(m.body));
    auto start = std::chrono::steady_clock::now();
    BeautifyReport r = beautify(m.body, tol);
    double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    // The types this object has but no registered pass repairs.
    std::string missing;
    for (ProblemType t : kAllProblemTypes)
      if (!pass_implemented(t) && r.problems_before[std::size_t(problem_order(t) - 1)] > 0)
        missing += (missing.empty() ? "" : ", ") + std::string(problem_name(t));
    const bool needs_early = !missing.empty();
    const Counts want = clean.body.counts();
    const bool match = r.counts_after.faces == want.faces && r.counts_after.edges == want.edges;
    out << std::setw(6) << n << "  " << std::setw(5) << r.counts_before.faces << " -> " << std::setw(3)
        << r.counts_after.faces << " (" << std::setw(3) << want.faces << ")            " << std::setw(5)
        << r.counts_before.edges << " -> " << std::setw(3) << r.counts_after.edges << " (" << std::setw(3)
        << want.edges << ")            " << std::fixed << std::setprecision(3) << s << std::defaultfloat << "    "
        << (match ? "as expected" : needs_early ? "not fully repaired yet: no pass for " + missing : std::string("DIFFERS")) << "\n";
  }
}

}  // namespace kintsugi::cli
