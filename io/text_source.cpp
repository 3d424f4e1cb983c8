#include "io/text_source.h"

#include <cerrno>
#include <cstring>

#include <unistd.h>

namespace kintsugi::io {

bool MemorySource::read(std::size_t begin, std::size_t n, char* out) const {
  if (begin > size_ || n > size_ - begin) return false;
  std::memcpy(out, text_ + begin, n);
  return true;
}

bool FileSource::read(std::size_t begin, std::size_t n, char* out) const {
  if (begin > size_ || n > size_ - begin) return false;
  while (n > 0) {
    const ssize_t got = ::pread(fd_, out, n, off_t(begin));
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) return false;  // an error, or the file is shorter than it was
    out += got;
    begin += std::size_t(got);
    n -= std::size_t(got);
  }
  return true;
}

}  // namespace kintsugi::io
