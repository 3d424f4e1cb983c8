#include "bench/bench_child.h"

#include <cstdio>
#include <iostream>
#include <string>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace kintsugi::bench {

long long peak_rss_bytes() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<long long>(u.ru_maxrss) * 1024;  // Linux reports kilobytes
}

long long current_rss_bytes() {
  long long pages = -1, resident = -1;
  if (FILE* f = std::fopen("/proc/self/statm", "r")) {
    if (std::fscanf(f, "%lld %lld", &pages, &resident) != 2) resident = -1;
    std::fclose(f);
  }
  return resident < 0 ? -1 : resident * ::sysconf(_SC_PAGESIZE);
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

nlohmann::ordered_json json_in_child(const std::function<nlohmann::ordered_json()>& work) {
  int fds[2];
  if (::pipe(fds) != 0) return {{"error", "pipe failed"}};
  std::cout.flush();
  pid_t pid = ::fork();
  if (pid < 0) return {{"error", "fork failed"}};
  if (pid == 0) {
    ::close(fds[0]);
    nlohmann::ordered_json r;
    try {
      r = work();
    } catch (const std::exception& e) {
      r = {{"error", e.what()}};
    }
    r["peak_rss_bytes"] = peak_rss_bytes();
    std::string text = r.dump();
    ssize_t n = ::write(fds[1], text.data(), text.size());
    ::_exit(n == ssize_t(text.size()) ? 0 : 1);
  }
  ::close(fds[1]);
  std::string text;
  char buf[4096];
  for (ssize_t n; (n = ::read(fds[0], buf, sizeof buf)) > 0;) text.append(buf, std::size_t(n));
  ::close(fds[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || text.empty()) return {{"error", "the child process failed"}};
  return nlohmann::ordered_json::parse(text);
}

}  // namespace kintsugi::bench
