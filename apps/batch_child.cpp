// One file of a batch in its own process (apps/batch.h): the parent's side (spawn, wait,
// kill, map the way the child ended to a manifest status) and the child's verb.
#include "apps/api.h"
#include "apps/args.h"
#include "apps/batch.h"
#include "apps/commands.h"

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <memory>
#include <new>
#include <poll.h>
#include <sstream>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

namespace kintsugi::cli::batch {

namespace {

using clock = std::chrono::steady_clock;

std::string last_line_of(const fs::path& p) {
  std::ifstream f(p);
  std::string line, last;
  while (std::getline(f, line))
    if (!line.empty()) last = line;
  if (last.size() > 300) last = last.substr(0, 300) + "...";
  return last;
}

std::string signal_name(int sig) {
  const char* d = sigdescr_np(sig);
  const char* a = sigabbrev_np(sig);
  std::string s = "signal " + std::to_string(sig);
  if (a) s += std::string(" (SIG") + a + (d ? std::string(", ") + d : std::string()) + ")";
  return s;
}

std::string seconds_text(double s) {
  std::ostringstream o;
  o << s;
  return o.str();
}

nlohmann::json entry_for(const Child& c, const std::string& status, const std::string& error, double seconds) {
  return {{"input", c.job.input},
          {"output", nullptr},
          {"status", status},
          {"problems_before", nullptr},
          {"problems_after", nullptr},
          {"tolerance", nullptr},
          {"seconds", seconds},
          {"error", error.empty() ? nlohmann::json(nullptr) : nlohmann::json(error)}};
}

// The test-only switches (tests/batch/, python/tests/), read only here in the child: a
// child whose input file is named (file name only) by KINTSUGI_TEST_HANG hangs; by
// KINTSUGI_TEST_CRASH aborts; by KINTSUGI_TEST_ALLOCATE reserves address space until it
// is refused (never touching it, so even without a limit it costs no memory).
bool test_switch_names(const char* var, const std::string& input) {
  const char* v = std::getenv(var);
  return v && *v && fs::path(input).filename() == v;
}

[[noreturn]] void test_hang() {
  for (;;) ::pause();
}

void test_allocate() {
  std::vector<std::unique_ptr<char[]>> blocks;
  for (int i = 0; i < 16384; ++i) blocks.push_back(std::make_unique_for_overwrite<char[]>(std::size_t(64) << 20));
  throw std::runtime_error("test allocation of 1 TiB was not refused (no --max-memory?)");
}

}  // namespace

std::string self_exe() {
  std::error_code ec;
  fs::path p = fs::read_symlink("/proc/self/exe", ec);
  return ec ? std::string() : p.string();
}

Child spawn_child(const std::string& exe, const Job& job, const Limits& limits, const fs::path& scratch, long serial) {
  Child c;
  c.job = job;
  c.result = scratch / (std::to_string(serial) + ".json");
  c.log = scratch / (std::to_string(serial) + ".log");
  const fs::path in = job.in_dir / job.input, out = job.out_dir / job.input;
  std::error_code ec;
  fs::create_directories(out.parent_path(), ec);  // the child reports it if this failed
  std::vector<std::string> args = {exe, "batch-file", in.string(), out.string(), c.result.string()};
  if (job.tol) {
    std::ostringstream t;
    t.precision(17);
    t << *job.tol;
    args.insert(args.end(), {"--tol", t.str()});
  }
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  // Everything the child needs is prepared before fork: between fork and exec it only
  // makes async-signal-safe calls (the parent may be a threaded Python worker).
  const int log_fd = ::open(c.log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  const int null_fd = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
  const pid_t parent = ::getpid();
  struct rlimit as_limit = {rlim_t(limits.max_memory), rlim_t(limits.max_memory)};
  struct rlimit no_core = {0, 0};
  c.start = clock::now();
  c.pid = ::fork();
  if (c.pid == 0) {
    ::setpgid(0, 0);                          // so a timeout kills whatever it started too
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);       // and it does not outlive a killed parent
    if (::getppid() != parent) ::_exit(127);
    if (limits.max_memory > 0) ::setrlimit(RLIMIT_AS, &as_limit);
    ::setrlimit(RLIMIT_CORE, &no_core);       // a million crashing files, no core dumps
    if (null_fd >= 0) ::dup2(null_fd, 0);
    if (log_fd >= 0) {
      ::dup2(log_fd, 1);
      ::dup2(log_fd, 2);
    }
    ::execv(exe.c_str(), argv.data());
    ::_exit(127);
  }
  if (log_fd >= 0) ::close(log_fd);
  if (null_fd >= 0) ::close(null_fd);
  if (c.pid < 0) throw std::runtime_error(std::string("cannot start a child process: ") + std::strerror(errno));
  ::setpgid(c.pid, c.pid);  // also here: no race with an early kill
  c.pidfd = int(::syscall(SYS_pidfd_open, c.pid, 0));
  c.deadline = limits.timeout_seconds > 0 && limits.timeout_seconds < 1e9  // beyond: none (and no overflow)
                   ? c.start + std::chrono::duration_cast<clock::duration>(std::chrono::duration<double>(limits.timeout_seconds))
                   : clock::time_point::max();
  return c;
}

void kill_child(Child& c) {
  if (c.pid <= 0) return;
  ::kill(-c.pid, SIGKILL);
  ::kill(c.pid, SIGKILL);
}

std::optional<nlohmann::json> reap_child(Child& c, const Limits& limits) {
  // Peek without reaping: while the child is a zombie its pid (and so its process group
  // id) cannot be reused, so what it left running in its group can still be killed safely.
  siginfo_t info{};
  if (::waitid(P_PID, id_t(c.pid), &info, WEXITED | WNOHANG | WNOWAIT) == 0 && info.si_pid == 0) {
    if (!c.killed_for_timeout && clock::now() >= c.deadline) {
      c.killed_for_timeout = true;
      kill_child(c);
    }
    return std::nullopt;
  }
  const double seconds = std::chrono::duration<double>(clock::now() - c.start).count();
  if (c.pidfd >= 0) ::close(c.pidfd);
  c.pidfd = -1;
  ::kill(-c.pid, SIGKILL);  // anything the child left behind in its group
  int status = 0;
  pid_t r = ::waitpid(c.pid, &status, 0);
  nlohmann::json entry;
  std::error_code ec;
  if (r < 0) {
    entry = entry_for(c, "crashed", std::string("lost the child: ") + std::strerror(errno), seconds);
  } else if (c.killed_for_timeout) {
    entry = entry_for(c, "timeout", "no result after " + seconds_text(limits.timeout_seconds) + " s (killed)", seconds);
  } else if (WIFSIGNALED(status)) {
    std::string e = "killed by " + signal_name(WTERMSIG(status));
    if (limits.max_memory > 0) e += " (possibly out of memory under --max-memory)";
    std::string last = last_line_of(c.log);
    if (!last.empty()) e += "; last output: " + last;
    entry = entry_for(c, "crashed", e, seconds);
  } else if (WEXITSTATUS(status) == kExitOutOfMemory) {
    entry = entry_for(c, "failed", "out of memory (over --max-memory " + std::to_string(limits.max_memory) + " bytes)", seconds);
  } else {
    std::ifstream f(c.result);
    auto result = f ? nlohmann::json::parse(f, nullptr, false) : nlohmann::json();
    if (!result.is_object() || !result.contains("status")) {
      std::string e = "exited with code " + std::to_string(WEXITSTATUS(status)) + " without a result";
      std::string last = last_line_of(c.log);
      if (!last.empty()) e += "; last output: " + last;
      entry = entry_for(c, "crashed", e, seconds);
    } else {
      const auto& e = result.value("error", nlohmann::json());
      entry = entry_for(c, result["status"].get<std::string>(), e.is_string() ? e.get<std::string>() : "", seconds);
      for (const char* k : {"problems_before", "problems_after", "tolerance"})
        if (result.contains(k)) entry[k] = result[k];
      if (result["status"] != "failed") entry["output"] = c.job.input;
    }
  }
  fs::remove(c.result, ec);
  fs::remove(c.log, ec);
  c.pid = -1;
  return entry;
}

nlohmann::json run_job(const std::string& exe, const Job& job, const Limits& limits) {
  std::string tmpl = (fs::temp_directory_path() / "kintsugi-batch-XXXXXX").string();
  if (!::mkdtemp(tmpl.data())) throw std::runtime_error(std::string("cannot make a scratch folder: ") + std::strerror(errno));
  const fs::path scratch = tmpl;
  Child c = spawn_child(exe, job, limits, scratch, 0);
  std::optional<nlohmann::json> entry;
  while (!(entry = reap_child(c, limits))) {
    if (c.pidfd >= 0) {
      struct pollfd p = {c.pidfd, POLLIN, 0};
      ::poll(&p, 1, 100);  // wakes when the child exits; 100 ms to check the deadline
    } else {
      ::usleep(10000);
    }
  }
  std::error_code ec;
  fs::remove_all(scratch, ec);
  return *entry;
}

// kintsugi batch-file IN OUT RESULT [--tol T]: beautify IN into OUT and write RESULT
// {"status", "problems_before", "problems_after", "tolerance", "error"}.
int run_batch_file(const std::vector<std::string>& argv, std::ostream& /*out*/, std::ostream& err) {
  Args args;
  std::string error;
  if (!args.parse(argv, {"--tol"}, {}, &error) || args.positional().size() != 3) {
    err << "kintsugi batch-file: " << (error.empty() ? "expected IN OUT RESULT" : error) << " (used by kintsugi batch)\n";
    return kExitBadInput;
  }
  const std::string in = args.positional()[0], out_path = args.positional()[1], result_path = args.positional()[2];
  auto given = args.number("--tol", 0, &error);
  if (!given) {
    err << "kintsugi batch-file: " << error << "\n";
    return kExitBadInput;
  }
  auto write_result = [&](const nlohmann::json& j) {
    std::ofstream f(result_path);
    f << j.dump() << "\n";
    return bool(f);
  };
  nlohmann::json result;
  try {
    if (test_switch_names("KINTSUGI_TEST_HANG", in)) test_hang();
    if (test_switch_names("KINTSUGI_TEST_CRASH", in)) std::abort();
    if (test_switch_names("KINTSUGI_TEST_ALLOCATE", in)) test_allocate();
    nlohmann::json report = api::beautify_file(in, out_path, args.has("--tol") ? given : std::nullopt);
    int left = 0;
    for (const auto& [type, n] : report["problems_after"].items()) left += n.get<int>();
    const int repaired = api::repaired_count(report);
    result = {{"status", repaired == 0 ? "unchanged" : left == 0 ? "repaired" : "partly_repaired"},
              {"problems_before", report["problems_before"]},
              {"problems_after", report["problems_after"]},
              {"tolerance", report["tolerance"]},
              {"error", nullptr}};
  } catch (const std::bad_alloc&) {
    err << "kintsugi batch-file: " << in << ": out of memory\n";
    return kExitOutOfMemory;
  } catch (const std::exception& e) {
    result = {{"status", "failed"}, {"error", e.what()}};
    write_result(result);
    err << "kintsugi batch-file: " << e.what() << "\n";
    return kExitBadInput;
  }
  if (!write_result(result)) {
    err << "kintsugi batch-file: cannot write " << result_path << "\n";
    return kExitBadInput;
  }
  return kExitOk;
}

}  // namespace kintsugi::cli::batch
