// The native reader's two-thread parse (io/native_json_parse.h says what is cut where and
// why the result is the whole document's). simdjson parses one document on one thread; a
// document of hundreds of megabytes is mostly one or two element arrays, and their
// elements are independent, so the two halves of the text are parsed and checked at once.
#include "io/native_json_parse.h"

#include "kernel/huge_pages.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <exception>
#include <memory>
#include <string_view>
#include <thread>
#include <utility>

namespace kintsugi::io {

namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

// The kind of element whose text starts at `p` (an object), from the keys before its first
// '}': each kind has a key no other kind has, and the writer puts it before any nested
// object closes. Looking no further keeps the next array's keys out. A guess: a wrong one
// fails the parse, and the text is then read whole.
bool guess_kind(const char* p, std::size_t n, ElementKind* kind) {
  std::string_view text(p, std::min<std::size_t>(n, 256));
  text = text.substr(0, text.find('}'));
  // In an order that keeps them apart: an edge's half-edges name a "loop", a face's
  // "surface" is not "face", a loop has "face", "first" or "lone".
  static constexpr std::array<std::pair<std::string_view, ElementKind>, 7> kKeys = {{{"\"he\"", kEdges},
                                                                                    {"\"point\"", kVertices},
                                                                                    {"\"genus\"", kShells},
                                                                                    {"\"shell\"", kFaces},
                                                                                    {"\"face\"", kLoops},
                                                                                    {"\"first\"", kLoops},
                                                                                    {"\"lone\"", kLoops}}};
  for (const auto& [key, k] : kKeys)
    if (text.find(key) != std::string_view::npos) {
      *kind = k;
      return true;
    }
  return false;
}

}  // namespace

bool find_cut(const char* text, std::size_t size, std::size_t reach, Cut* cut) {
  const std::size_t end = std::min(size, size / 2 + reach);
  for (std::size_t nl = size / 2; nl < end; ++nl) {
    const void* found = std::memchr(text + nl, '\n', end - nl);
    if (!found) return false;
    nl = std::size_t(static_cast<const char*>(found) - text);
    std::size_t comma = nl, next = nl + 1;
    while (comma > 0 && is_space(text[comma - 1])) --comma;
    if (comma == 0 || text[comma - 1] != ',') continue;
    --comma;
    while (next < size && is_space(text[next])) ++next;
    if (next >= size || text[next] != '{') continue;
    if (!guess_kind(text + next, size - next, &cut->kind)) continue;
    cut->comma = comma;
    cut->next = next;
    return true;
  }
  return false;
}

FastParse parse_native_simdjson_halves(char* text, std::size_t size, std::size_t capacity, ElementSink* head,
                                       JsonTree* head_root, ElementSink* tail, JsonTree* tail_root, ElementKind* cut,
                                       std::size_t* head_count) {
  Cut c;
  // Elements are short: an element boundary within a few megabytes of the middle, or the
  // middle is in something else (meta, one huge element) and one thread reads it all.
  if (!find_cut(text, size, std::size_t(4) << 20, &c)) return FastParse::kUseReference;

  // The second half, on its own thread: `{"":[` and the text from the next element, copied
  // into a buffer with simdjson's padding (the copy is a small part of parsing it).
  static constexpr std::string_view kOpen = "{\"\":[";
  FastParse tail_result = FastParse::kUseReference;
  std::size_t tail_count = 0;
  std::exception_ptr tail_error;
  std::thread second([&] {
    try {
      const std::size_t n = kOpen.size() + (size - c.next);
      const std::size_t padded = n + simdjson_padding();
      auto buffer = std::make_unique_for_overwrite<char[]>(padded);
      advise_huge_pages(buffer.get(), padded);
      std::memcpy(buffer.get(), kOpen.data(), kOpen.size());
      std::memcpy(buffer.get() + kOpen.size(), text + c.next, size - c.next);
      std::memset(buffer.get() + n, ' ', simdjson_padding());
      tail_result = parse_native_simdjson_tail(buffer.get(), n, padded, c.kind, tail, tail_root, &tail_count);
    } catch (...) {
      tail_error = std::current_exception();
    }
  });

  // The first half, here: the text up to the comma, closed by "]}" written over the comma
  // and the byte after it (white space, which the second half does not start before).
  FastParse head_result = FastParse::kUseReference;
  std::exception_ptr head_error;
  const char saved[2] = {text[c.comma], text[c.comma + 1]};
  text[c.comma] = ']';
  text[c.comma + 1] = '}';
  ElementKind head_kind = kVertices;
  try {
    head_result = parse_native_simdjson_head(text, c.comma + 2, capacity, head, head_root, &head_kind, head_count);
  } catch (...) {
    head_error = std::current_exception();
  }
  text[c.comma] = saved[0];
  text[c.comma + 1] = saved[1];
  second.join();
  if (head_error) std::rethrow_exception(head_error);
  if (tail_error) std::rethrow_exception(tail_error);
  if (head_result != FastParse::kDone || tail_result != FastParse::kDone || head_kind != c.kind || *head_count == 0 ||
      tail_count == 0)
    return FastParse::kUseReference;
  *cut = c.kind;
  return FastParse::kDone;
}

}  // namespace kintsugi::io
