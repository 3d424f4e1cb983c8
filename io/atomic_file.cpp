// Atomic file writes (spec/file-format.md, "Writing files"): a fresh temporary file in
// the target's directory, fsynced, renamed over the target, the directory fsynced.
#include "io/native_json.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>

namespace kintsugi::io {

namespace {

bool fail_io(std::string* error, const std::string& message) {
  if (error) *error = message;
  return false;
}

}  // namespace

bool write_file_atomically_streamed(const std::string& path, const std::function<bool(const ChunkSink&)>& produce,
                                    std::string* error, const std::string& must_not_overwrite) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  if (path.empty() || !target.has_filename()) return fail_io(error, "'" + path + "' is not a file name");
  if (!must_not_overwrite.empty()) {
    std::error_code ec;
    if (fs::exists(target, ec) && fs::exists(must_not_overwrite, ec) && fs::equivalent(target, must_not_overwrite, ec))
      return fail_io(error, path + ": refusing to overwrite the input file " + must_not_overwrite);
  }
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");

  // A fresh name in the same directory (so the rename stays within one file system);
  // O_EXCL never reuses someone else's file, 0666 lets the umask decide the mode.
  static std::atomic<unsigned> counter{0};
  std::string temp;
  int fd = -1;
  for (int attempt = 0; attempt < 100 && fd < 0; ++attempt) {
    temp = (dir / ("." + target.filename().string() + ".tmp-" + std::to_string(::getpid()) + "-" +
                   std::to_string(counter++)))
               .string();
    fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0 && errno != EEXIST) break;
  }
  if (fd < 0)
    return fail_io(error, path + ": cannot create a temporary file in " + dir.string() + ": " + std::strerror(errno));

  auto abandon = [&](const std::string& why) {
    if (fd >= 0) ::close(fd);
    ::unlink(temp.c_str());
    return fail_io(error, why);
  };
  auto system_error = [&](const std::string& what) { return path + ": " + what + ": " + std::strerror(errno); };

  std::string write_error;  // set by the sink when a write fails
  const ChunkSink sink = [&](std::string_view bytes) {
    for (std::size_t done = 0; done < bytes.size();) {
      ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
      if (n < 0) {
        if (errno == EINTR) continue;
        write_error = system_error("cannot write " + temp);
        return false;
      }
      done += std::size_t(n);
    }
    return true;
  };
  bool produced;
  try {
    produced = produce(sink);
  } catch (const std::exception& e) {  // e.g. out of memory while producing
    return abandon(path + ": cannot produce the contents: " + e.what());
  }
  if (!write_error.empty()) return abandon(write_error);
  if (!produced) return abandon(path + ": the contents could not be produced");
  if (::fsync(fd) != 0) return abandon(system_error("cannot flush " + temp));
  int closed = ::close(fd);
  fd = -1;
  if (closed != 0) return abandon(system_error("cannot close " + temp));
  if (::rename(temp.c_str(), path.c_str()) != 0) return abandon(system_error("cannot rename " + temp + " over it"));
  // Make the rename itself durable; failing here loses nothing already visible.
  int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) {
    (void)::fsync(dfd);
    ::close(dfd);
  }
  return true;
}

bool write_file_atomically(const std::string& path, const std::string& contents, std::string* error,
                           const std::string& must_not_overwrite) {
  return write_file_atomically_streamed(
      path, [&](const ChunkSink& sink) { return sink(contents); }, error, must_not_overwrite);
}

}  // namespace kintsugi::io
