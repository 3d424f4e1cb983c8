// The text of a native document as the fast reader reads it (io/native_json_parse.h,
// "Pieces"): a piece at a time, so that a large file need never be in memory whole. A
// file of hundreds of megabytes read into one buffer is that much fresh memory, and on a
// virtual machine touching fresh memory costs more than parsing it (docs/benchmarks.md,
// "Pieces of a megabyte"); read a piece at a time into one reused buffer, it costs a copy
// from the page cache.
#pragma once

#include <cstddef>

namespace kintsugi::io {

class TextSource {
 public:
  virtual ~TextSource() = default;
  virtual std::size_t size() const = 0;
  // Copies text[begin, begin + n) to `out`: false if it cannot (a file that shrank or
  // failed to read; the caller then reads it some other way).
  virtual bool read(std::size_t begin, std::size_t n, char* out) const = 0;
  // The whole text, followed by simdjson's padding up to capacity(), when it is in
  // memory: a piece that is the whole text is parsed where it lies. Else null.
  virtual const char* whole() const { return nullptr; }
  virtual std::size_t capacity() const { return 0; }
};

// Text in memory, with `capacity - size` readable bytes of padding after it.
class MemorySource final : public TextSource {
 public:
  MemorySource(const char* text, std::size_t size, std::size_t capacity) : text_(text), size_(size), capacity_(capacity) {}
  std::size_t size() const override { return size_; }
  bool read(std::size_t begin, std::size_t n, char* out) const override;
  const char* whole() const override { return text_; }
  std::size_t capacity() const override { return capacity_; }

 private:
  const char* text_;
  std::size_t size_, capacity_;
};

// A regular file of `size` bytes, read with pread (any thread, any order). The caller keeps
// the descriptor open.
class FileSource final : public TextSource {
 public:
  FileSource(int fd, std::size_t size) : fd_(fd), size_(size) {}
  std::size_t size() const override { return size_; }
  bool read(std::size_t begin, std::size_t n, char* out) const override;

 private:
  int fd_;
  std::size_t size_;
};

}  // namespace kintsugi::io
