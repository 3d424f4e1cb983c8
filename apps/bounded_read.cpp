// The child-process guard around OpenCASCADE's readers (apps/bounded_read.h).
#include "apps/bounded_read.h"

#include "apps/batch.h"
#include "io/native_json.h"

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <new>
#include <poll.h>
#include <sstream>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#if defined(__SANITIZE_ADDRESS__)
#define KINTSUGI_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define KINTSUGI_ASAN 1
#endif
#endif

namespace kintsugi::cli {

namespace {

std::optional<ReadBounds> g_bounds;

std::string number_text(double x) {
  std::ostringstream o;
  o << x;
  return o.str();
}

}  // namespace

std::optional<ReadBounds> read_bounds_from_environment(std::string* error) {
  ReadBounds b;
  if (const char* t = std::getenv("KINTSUGI_READ_TIMEOUT"); t && *t) {
    char* end = nullptr;
    double s = std::strtod(t, &end);
    if (*end != '\0' || !(s > 0) || s > 1e9) {
      *error = std::string("KINTSUGI_READ_TIMEOUT must be a positive number of seconds, not '") + t + "'";
      return std::nullopt;
    }
    b.seconds = s;
  }
  if (const char* m = std::getenv("KINTSUGI_READ_MAX_MEMORY"); m && *m) {
    auto bytes = batch::parse_size(m);
    if (!bytes) {
      *error = std::string("KINTSUGI_READ_MAX_MEMORY must be a size (512M, 4G, bytes; 0 for none), not '") + m + "'";
      return std::nullopt;
    }
    b.max_memory = *bytes;
  }
  return b;
}

void bound_cad_reads(const ReadBounds& b) { g_bounds = b; }

#ifdef KINTSUGI_HAVE_OCCT

namespace {

// The child's whole life: read, write one reply to `fd`, exit without running any
// destructor of the parent's state. Reply: 'E' + message, or 'O' + the body (with its
// units) as a native document.
[[noreturn]] void child_read(const std::string& path, io::CadFormat f, int fd) {
  auto put = [fd](std::string_view s) {
    while (!s.empty()) {
      ssize_t n = ::write(fd, s.data(), s.size());
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) return false;
      s.remove_prefix(std::size_t(n));
    }
    return true;
  };
  try {
    std::string error;
    auto imp = io::import_cad(path, f, &error);
    if (!imp) {
      put("E" + error);
      ::_exit(0);
    }
    bool ok = put("O") &&
              io::write_native_to(imp->body, nlohmann::json::object(), imp->units, put);
    ::_exit(ok ? 0 : 1);
  } catch (const std::bad_alloc&) {
    ::_exit(batch::kExitOutOfMemory);
  } catch (...) {
    ::_exit(1);
  }
}

}  // namespace

std::optional<io::CadImport> import_cad_bounded(const std::string& path, io::CadFormat f, std::string* error) {
  if (!g_bounds) return io::import_cad(path, f, error);
  const ReadBounds bounds = *g_bounds;
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) {
    *error = path + ": cannot start the reader: " + std::strerror(errno);
    return std::nullopt;
  }
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) {
    *error = path + ": cannot start the reader: " + std::strerror(errno);
    ::close(fds[0]);
    ::close(fds[1]);
    return std::nullopt;
  }
  if (pid == 0) {
    ::close(fds[0]);
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);  // never outlives the parent
    if (::getppid() != parent) ::_exit(1);
    struct rlimit no_core = {0, 0};
    ::setrlimit(RLIMIT_CORE, &no_core);
#ifndef KINTSUGI_ASAN
    if (bounds.max_memory > 0) {
      struct rlimit as = {rlim_t(bounds.max_memory), rlim_t(bounds.max_memory)};
      ::setrlimit(RLIMIT_AS, &as);
    }
#endif
    child_read(path, f, fds[1]);
  }
  ::close(fds[1]);

  using clock = std::chrono::steady_clock;
  const auto deadline = clock::now() + std::chrono::duration_cast<clock::duration>(std::chrono::duration<double>(bounds.seconds));
  std::string reply;
  bool timed_out = false;
  char buf[1 << 16];
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - clock::now()).count();
    if (left <= 0) {
      timed_out = true;
      break;
    }
    struct pollfd p = {fds[0], POLLIN, 0};
    int r = ::poll(&p, 1, int(std::min<long long>(left, 1000)));
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) continue;
    ssize_t n = ::read(fds[0], buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // end of file: the child is done (or died)
    reply.append(buf, std::size_t(n));
  }
  ::close(fds[0]);
  if (timed_out) ::kill(pid, SIGKILL);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }

  const std::string limit_mem = number_text(double(bounds.max_memory) / double(1 << 20)) + " MiB";
  if (timed_out) {
    *error = path + ": reading did not finish within " + number_text(bounds.seconds) +
             " s and was stopped (a corrupt or hostile file? KINTSUGI_READ_TIMEOUT sets the limit)";
    return std::nullopt;
  }
  if (WIFSIGNALED(status)) {
    *error = path + ": OpenCASCADE's reader crashed (signal " + std::to_string(WTERMSIG(status)) + ", " +
             strsignal(WTERMSIG(status)) + ")" +
             (bounds.max_memory > 0 ? ", possibly out of memory under the limit of " + limit_mem : "");
    return std::nullopt;
  }
  if (WEXITSTATUS(status) == batch::kExitOutOfMemory) {
    *error = path + ": reading needs more than " + limit_mem +
             " of memory and was stopped (KINTSUGI_READ_MAX_MEMORY sets the limit)";
    return std::nullopt;
  }
  if (WEXITSTATUS(status) != 0 || reply.empty()) {
    *error = path + ": the reader failed without a message (exit " + std::to_string(WEXITSTATUS(status)) + ")";
    return std::nullopt;
  }
  if (reply[0] == 'E') {
    *error = reply.substr(1);
    return std::nullopt;
  }
  if (reply[0] != 'O') {
    *error = path + ": the reader's reply is garbled";
    return std::nullopt;
  }
  std::string why;
  auto doc = io::read_native(std::string_view(reply).substr(1), &why);
  if (!doc) {
    *error = path + ": the body read could not be handed over: " + why;
    return std::nullopt;
  }
  io::CadImport out;
  out.body = std::move(doc->body);
  out.units = doc->units;
  return out;
}

#endif

}  // namespace kintsugi::cli
