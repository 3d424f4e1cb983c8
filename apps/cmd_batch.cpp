#include "apps/args.h"
#include "apps/batch.h"
#include "apps/commands.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <iomanip>
#include <ostream>
#include <poll.h>
#include <sstream>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

namespace kintsugi::cli {

namespace {

using namespace batch;
using clock = std::chrono::steady_clock;

const char* kHelp =
    "usage: kintsugi batch IN_DIR OUT_DIR [--tol T | --tol-from-meta] [--jobs N] [--timeout S]\n"
    "                      [--max-memory M] [--resume] [--manifest FILE] [--shard I/N]\n\n"
    "Beautifies every .step/.stp/.iges/.igs/.brep/.json under IN_DIR (recursively) into the same\n"
    "relative path under OUT_DIR, each file in its own child process: a crash, hang or\n"
    "memory blow-up in one file (inside OpenCASCADE's reader too) costs that file only and\n"
    "is recorded as such. A progress bar on a terminal, one line per file otherwise.\n\n"
    "  --tol T          one length tolerance for every file\n"
    "  --tol-from-meta  each file's meta.tolerance, else 1e-3 x its size (the default)\n"
    "  --jobs N         files at once (default: every core)\n"
    "  --timeout S      seconds per file before it is killed (default 600; 0: none)\n"
    "  --max-memory M   address space per child, e.g. 2G, 512M (default: no limit)\n"
    "  --resume         skip the files the manifest already records\n"
    "  --manifest FILE  where to record (default OUT_DIR/kintsugi-batch.jsonl)\n"
    "  --shard I/N      only the files whose index in the sorted list is I modulo N\n"
    "                   (0 <= I < N; for job arrays, each with its own --manifest)\n\n"
    "The manifest has one JSON line per file, written and flushed as each file ends:\n"
    "{\"input\", \"output\", \"status\": repaired|partly_repaired|unchanged|failed|timeout|crashed,\n"
    "\"problems_before\", \"problems_after\" (counts by type), \"tolerance\", \"seconds\",\n"
    "\"error\"}. At the end a summary table is printed and FILE-summary.json written.\n\n"
    "Exit: 0 every file processed (whatever it needed); 3 some failed, timed out or crashed;\n"
    "2 bad usage.\n";

std::atomic<int> g_stop_signal{0};
void on_stop_signal(int sig) { g_stop_signal = sig; }

std::string clock_text(double seconds) {
  long s = long(seconds + 0.5);
  std::ostringstream o;
  if (s >= 3600) o << s / 3600 << ":" << std::setw(2) << std::setfill('0') << (s / 60) % 60;
  else o << s / 60;
  o << ":" << std::setw(2) << std::setfill('0') << s % 60;
  return o.str();
}

// Progress on stderr: a bar redrawn in place on a terminal, a line per file otherwise.
class Progress {
 public:
  Progress(std::ostream& err, std::size_t total, bool bar) : err_(err), total_(total), bar_(bar), start_(clock::now()) {}
  void file_done(const nlohmann::json& entry) {
    ++done_;
    const std::string status = entry["status"].get<std::string>();
    if (status == "failed" || status == "timeout" || status == "crashed") ++failed_;
    if (bar_) return draw();
    err_ << "kintsugi batch: [" << done_ << "/" << total_ << "] " << entry["input"].get<std::string>() << ": " << status;
    if (entry["error"].is_string()) err_ << ": " << entry["error"].get<std::string>();
    err_ << "\n";
  }
  void draw() {
    if (!bar_) return;
    const double elapsed = std::chrono::duration<double>(clock::now() - start_).count();
    const double rate = elapsed > 0 ? double(done_) / elapsed : 0;
    constexpr int kWidth = 30;
    const int filled = total_ ? int(kWidth * double(done_) / double(total_)) : kWidth;
    std::ostringstream o;
    o << "\r[" << std::string(filled, '#') << std::string(kWidth - filled, '.') << "] " << done_ << "/" << total_ << "  "
      << failed_ << " failed  " << std::fixed << std::setprecision(1) << rate << " files/s  ";
    if (rate > 0 && done_ < total_) o << clock_text(double(total_ - done_) / rate) << " left";
    o << "\x1b[K";
    err_ << o.str() << std::flush;
  }
  void finish() {
    if (bar_) err_ << "\n";
  }

 private:
  std::ostream& err_;
  std::size_t total_, done_ = 0, failed_ = 0;
  bool bar_;
  clock::time_point start_;
};

bool write_line(int fd, const std::string& line, std::string* error) {
  std::string text = line + "\n";
  const char* p = text.data();
  std::size_t left = text.size();
  while (left > 0) {  // one write() for a whole line, unless the kernel splits it
    ssize_t n = ::write(fd, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      *error = std::strerror(errno);
      return false;
    }
    p += n;
    left -= std::size_t(n);
  }
  return true;
}

}  // namespace

int cmd_batch_file(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err) {
  return batch::run_batch_file(argv, out, err);
}

int cmd_batch(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err) {
  Args args;
  std::string error;
  if (!args.parse(argv, {"--tol", "--jobs", "--timeout", "--max-memory", "--manifest", "--shard"},
                  {"--tol-from-meta", "--resume", "--help"}, &error)) {
    err << "kintsugi batch: " << error << "\n" << kHelp;
    return kExitBadInput;
  }
  if (args.has("--help")) {
    out << kHelp;
    return kExitOk;
  }
  auto usage_error = [&](const std::string& what) {
    err << "kintsugi batch: " << what << "\n";
    return kExitBadInput;
  };
  if (args.positional().size() != 2) {
    err << "kintsugi batch: expected IN_DIR and OUT_DIR\n" << kHelp;
    return kExitBadInput;
  }
  if (args.has("--tol") && args.has("--tol-from-meta")) return usage_error("--tol and --tol-from-meta exclude each other");
  Job proto;
  proto.in_dir = args.positional()[0];
  proto.out_dir = args.positional()[1];
  if (args.has("--tol")) {
    auto t = args.number("--tol", 0, &error);
    if (!t || *t <= 0) return usage_error(error.empty() ? "--tol must be a positive number" : error);
    proto.tol = *t;
  }
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  auto jobs = args.integer("--jobs", cores, 1, 4096, &error);
  if (!jobs) return usage_error(error);
  Limits limits;
  auto timeout = args.number("--timeout", limits.timeout_seconds, &error);
  if (!timeout || *timeout < 0) return usage_error(error.empty() ? "--timeout must be 0 or more seconds" : error);
  limits.timeout_seconds = *timeout;
  if (args.has("--max-memory")) {
    auto m = parse_size(*args.value("--max-memory"));
    if (!m) return usage_error("--max-memory: '" + *args.value("--max-memory") + "' is not a size (e.g. 2G, 512M)");
    limits.max_memory = *m;
  }
  long shard = 0, shards = 1;
  if (args.has("--shard")) {
    const std::string s = *args.value("--shard");
    char slash = 0, extra = 0;
    std::istringstream in(s);
    if (!(in >> shard >> slash >> shards) || slash != '/' || in >> extra || shards < 1 || shard < 0 || shard >= shards)
      return usage_error("--shard: '" + s + "' is not I/N with 0 <= I < N");
  }
  std::error_code ec;
  if (!fs::is_directory(proto.in_dir, ec)) return usage_error(proto.in_dir.string() + ": not a folder");
  fs::create_directories(proto.out_dir, ec);
  if (!fs::is_directory(proto.out_dir, ec)) return usage_error(proto.out_dir.string() + ": cannot create the folder");
  const fs::path in_abs = fs::weakly_canonical(proto.in_dir, ec), out_abs = fs::weakly_canonical(proto.out_dir, ec);
  auto rel = out_abs.lexically_relative(in_abs);
  if (!rel.empty() && *rel.begin() != "..")
    return usage_error("OUT_DIR must not be IN_DIR or inside it (outputs would be read as inputs)");
  const fs::path manifest = args.has("--manifest") ? fs::path(*args.value("--manifest")) : proto.out_dir / "kintsugi-batch.jsonl";
  if (fs::exists(manifest, ec) && !args.has("--resume"))
    return usage_error(manifest.string() + " exists: --resume to go on with it, or remove it");

  std::vector<std::string> inputs = find_inputs(proto.in_dir, &error);
  if (!error.empty()) return usage_error(error);
  if (shards > 1) {
    std::vector<std::string> mine;
    for (std::size_t i = 0; i < inputs.size(); ++i)
      if (long(i % std::size_t(shards)) == shard) mine.push_back(inputs[i]);
    inputs.swap(mine);
  }
  std::set<std::string> recorded = recorded_inputs(manifest, true, &error);
  if (!error.empty()) return usage_error(error);
  std::vector<std::string> todo;
  for (const auto& f : inputs)
    if (!recorded.count(f)) todo.push_back(f);
  if (!recorded.empty()) err << "kintsugi batch: " << inputs.size() - todo.size() << " file(s) already in " << manifest.string() << "\n";

  fs::create_directories(manifest.parent_path().empty() ? fs::path(".") : manifest.parent_path(), ec);
  const int manifest_fd = ::open(manifest.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0644);
  if (manifest_fd < 0) return usage_error(manifest.string() + ": cannot open: " + std::strerror(errno));
  std::string scratch_name = (fs::temp_directory_path() / "kintsugi-batch-XXXXXX").string();
  if (!::mkdtemp(scratch_name.data())) {
    ::close(manifest_fd);
    return usage_error(std::string("cannot make a scratch folder: ") + std::strerror(errno));
  }
  const fs::path scratch = scratch_name;
  const std::string exe = self_exe();

  struct sigaction sa {};
  sa.sa_handler = on_stop_signal;
  ::sigaction(SIGINT, &sa, nullptr);
  ::sigaction(SIGTERM, &sa, nullptr);

  const auto start = clock::now();
  Progress progress(err, todo.size(), ::isatty(2));
  std::vector<Child> running;
  std::size_t next = 0;
  long serial = 0;
  bool write_failed = false;
  while ((next < todo.size() || !running.empty()) && !g_stop_signal && !write_failed) {
    while (running.size() < std::size_t(*jobs) && next < todo.size()) {
      Job j = proto;
      j.input = todo[next++];
      running.push_back(spawn_child(exe, j, limits, scratch, serial++));
    }
    // Sleep until a child exits (its pidfd turns readable), the nearest deadline, or the
    // next redraw of the progress bar.
    std::vector<pollfd> fds;
    auto wake = clock::now() + std::chrono::milliseconds(500);
    for (const Child& c : running) {
      if (c.pidfd >= 0) fds.push_back({c.pidfd, POLLIN, 0});
      else wake = std::min(wake, clock::now() + std::chrono::milliseconds(10));
      wake = std::min(wake, c.deadline);
    }
    const auto wait_ms = std::chrono::duration_cast<std::chrono::milliseconds>(wake - clock::now()).count();
    ::poll(fds.data(), fds.size(), int(std::clamp<long long>(wait_ms + 1, 0, 500)));
    for (std::size_t i = 0; i < running.size();) {
      auto entry = reap_child(running[i], limits);
      if (!entry) {
        ++i;
        continue;
      }
      if (!write_line(manifest_fd, entry->dump(), &error)) {
        err << "\nkintsugi batch: " << manifest.string() << ": cannot write: " << error << "\n";
        write_failed = true;
      }
      progress.file_done(*entry);
      running.erase(running.begin() + long(i));
    }
    progress.draw();
  }
  if (g_stop_signal || write_failed) {
    for (Child& c : running) kill_child(c);
    for (Child& c : running) {
      int st;
      ::waitpid(c.pid, &st, 0);
      if (c.pidfd >= 0) ::close(c.pidfd);
    }
  }
  progress.finish();
  ::close(manifest_fd);
  fs::remove_all(scratch, ec);
  if (g_stop_signal) {
    err << "kintsugi batch: stopped by " << ::strsignal(g_stop_signal) << "; --resume goes on from here\n";
    return 128 + g_stop_signal;
  }
  if (write_failed) return kExitBadInput;

  const double wall = std::chrono::duration<double>(clock::now() - start).count();
  Summary s = finish_run(manifest, wall, int(*jobs), todo.size(), &error);
  if (!error.empty()) err << "kintsugi batch: " << error << "\n";
  out << s.table;
  return s.exit_code;
}

}  // namespace kintsugi::cli
