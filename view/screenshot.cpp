#include "view/screenshot.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>
#include <vector>

extern char** environ;

namespace kintsugi::view {

namespace fs = std::filesystem;

namespace {

bool fail(std::string* error, const std::string& message) {
  if (error) *error = message;
  return false;
}

std::optional<std::string> on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "/usr/local/bin:/usr/bin:/bin");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    const fs::path candidate = fs::path(dir.empty() ? "." : dir) / name;
    if (access(candidate.c_str(), X_OK) == 0) return candidate.string();
  }
  return std::nullopt;
}

// file:// URL of an absolute path, bytes outside the unreserved set percent-encoded.
std::string file_url(const fs::path& p) {
  static const char* hex = "0123456789ABCDEF";
  std::string url = "file://";
  for (unsigned char c : p.string()) {
    if (std::isalnum(c) || c == '/' || c == '-' || c == '_' || c == '.' || c == '~') url += char(c);
    else url += {'%', hex[c >> 4], hex[c & 15]};
  }
  return url;
}

std::string tail_of(const fs::path& log, std::size_t lines) {
  std::ifstream f(log);
  std::vector<std::string> all;
  for (std::string line; std::getline(f, line);)
    if (line.find("dbus") == std::string::npos) all.push_back(line);  // noise of a desktop-less machine
  std::string out;
  for (std::size_t i = all.size() > lines ? all.size() - lines : 0; i < all.size(); ++i) out += "\n  " + all[i];
  return out;
}

// A scratch directory (the browser's profile and the picture), removed on every exit.
struct ScratchDir {
  fs::path path;
  ScratchDir() {
    std::string templ = (fs::temp_directory_path() / "kintsugi-png-XXXXXX").string();
    if (mkdtemp(templ.data())) path = templ;
  }
  ~ScratchDir() {
    std::error_code ec;
    if (!path.empty()) fs::remove_all(path, ec);
  }
};

}  // namespace

std::optional<std::string> find_chromium() {
  if (const char* given = std::getenv("KINTSUGI_CHROMIUM"); given && *given) {
    if (access(given, X_OK) == 0) return std::string(given);
    if (auto p = on_path(given)) return p;
    return std::nullopt;
  }
  for (const char* name : {"chromium", "chromium-browser", "google-chrome", "google-chrome-stable"})
    if (auto p = on_path(name)) return p;
  return std::nullopt;
}

std::optional<std::string> screenshot(const std::string& html_path, const ScreenshotOptions& o, std::string* error) {
  const auto browser = find_chromium();
  if (!browser) {
    fail(error, "--png needs Chromium (Debian: apt-get install chromium; or set KINTSUGI_CHROMIUM to the browser)");
    return std::nullopt;
  }
  std::error_code ec;
  const fs::path page = fs::absolute(html_path, ec);
  if (ec || !fs::exists(page)) {
    fail(error, "no page at " + html_path);
    return std::nullopt;
  }
  ScratchDir scratch;
  if (scratch.path.empty()) {
    fail(error, "cannot create a temporary directory for the browser");
    return std::nullopt;
  }
  const fs::path png = scratch.path / "page.png", log = scratch.path / "browser.log";
  std::vector<std::string> args = {*browser,
                                   "--headless",
                                   // WebGL without a GPU: SwiftShader, which Chromium wants opted into.
                                   "--use-angle=swiftshader",
                                   "--enable-unsafe-swiftshader",
                                   "--hide-scrollbars",
                                   "--force-device-scale-factor=1",
                                   "--no-first-run",
                                   "--disable-extensions",
                                   "--user-data-dir=" + (scratch.path / "profile").string(),
                                   "--window-size=" + std::to_string(o.width) + "," + std::to_string(o.height),
                                   "--virtual-time-budget=10000",
                                   "--screenshot=" + png.string(),
                                   file_url(page) + "?still=1&size=" + std::to_string(o.width) + "x" + std::to_string(o.height)};
  // Chromium's sandbox refuses to run as root (containers, CI).
  if (geteuid() == 0) args.insert(args.begin() + 1, "--no-sandbox");
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  posix_spawnattr_setpgroup(&attr, 0);  // its own process group: a timeout ends the browser's helpers too
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, browser->c_str(), &actions, &attr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attr);
  if (spawned != 0) {
    fail(error, "cannot start " + *browser);
    return std::nullopt;
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(o.timeout_seconds);
  int status = 0;
  for (;;) {
    const pid_t r = waitpid(pid, &status, WNOHANG);
    if (r == pid) break;
    if (r < 0) {
      fail(error, "lost track of the browser process");
      return std::nullopt;
    }
    if (std::chrono::steady_clock::now() > deadline) {
      kill(-pid, SIGKILL);
      waitpid(pid, &status, 0);
      fail(error, *browser + " took longer than " + std::to_string(o.timeout_seconds) + " s" + tail_of(log, 5));
      return std::nullopt;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  std::ifstream f(png, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  if (bytes.size() < 8 || bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0) {
    const std::string how = WIFEXITED(status) ? "exit " + std::to_string(WEXITSTATUS(status)) : "killed by a signal";
    fail(error, *browser + " wrote no picture (" + how + ")" + tail_of(log, 5));
    return std::nullopt;
  }
  return bytes;
}

}  // namespace kintsugi::view
