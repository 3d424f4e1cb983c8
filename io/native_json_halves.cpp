// The native reader's two-thread parse (io/native_json_parse.h says what is cut where and
// why the result is the whole document's). simdjson parses one document on one thread; a
// document of hundreds of megabytes is mostly one or two element arrays, and their
// elements are independent, so the two halves of the text are parsed and checked at once.
#include "io/native_json_parse.h"

#include <algorithm>
#include <array>
#include <condition_variable>
#include <cstdint>
#include <cstring>
#include <exception>
#include <memory>
#include <mutex>
#include <string_view>
#include <thread>
#include <utility>
#include <vector>

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

bool find_cut_at(const char* text, std::size_t size, std::size_t from, std::size_t reach, Cut* cut) {
  const std::size_t end = from + std::min(reach, size - std::min(size, from));
  for (std::size_t nl = from; nl < end; ++nl) {
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

bool find_cut(const char* text, std::size_t size, std::size_t reach, Cut* cut) {
  return find_cut_at(text, size, size / 2, reach, cut);
}

bool find_cut_in(const TextSource& text, std::size_t from, std::size_t reach, Cut* cut) {
  if (const char* whole = text.whole()) return find_cut_at(whole, text.size(), from, reach, cut);
  // Windows of 64 KiB, each read with 64 bytes before it (the white space before a line
  // break) and 512 after it (the white space after, and the next element's keys).
  static constexpr std::size_t kWindow = std::size_t(64) << 10, kBefore = 64, kAfter = 512;
  const std::size_t size = text.size(), end = from + std::min(reach, size - std::min(size, from));
  std::vector<char> buffer;
  for (std::size_t lo = from; lo < end; lo += kWindow) {
    const std::size_t start = lo - std::min(lo, kBefore), stop = std::min(size, lo + kWindow + kAfter);
    buffer.resize(stop - start);
    if (!text.read(start, stop - start, buffer.data())) return false;
    Cut c;
    if (find_cut_at(buffer.data(), stop - start, lo - start, std::min(kWindow, end - lo), &c)) {
      *cut = c;
      cut->comma += start, cut->next += start;
      return true;
    }
  }
  return false;
}

FastParse parse_native_simdjson_halves(const char* text, std::size_t size, std::size_t capacity, ElementSink* head,
                                       JsonTree* head_root, ElementSink* tail, JsonTree* tail_root, ElementKind* cut,
                                       std::size_t* head_count, std::size_t piece_bytes) {
  return parse_native_simdjson_halves(MemorySource(text, size, capacity), head, head_root, tail, tail_root, cut,
                                      head_count, piece_bytes);
}

FastParse parse_native_simdjson_halves(const TextSource& text, ElementSink* head, JsonTree* head_root, ElementSink* tail,
                                       JsonTree* tail_root, ElementKind* cut, std::size_t* head_count,
                                       std::size_t piece_bytes) {
  const std::size_t size = text.size();
  Cut c;
  // Elements are short: an element boundary within a few megabytes of the middle, or the
  // middle is in something else (meta, one huge element) and one thread reads it all.
  if (!find_cut_in(text, size / 2, std::size_t(4) << 20, &c)) return FastParse::kUseReference;

  // The second half on its own thread, the first here.
  Run first, second;
  first.end = c.comma;
  second.begin = c.next, second.end = size, second.continued = int(c.kind);
  first.piece_bytes = second.piece_bytes = piece_bytes;
  // The first half's descriptions make room for the second's, which are appended to them
  // (DocumentReader::absorb): the second half tells its counts once it has them (zeros if
  // it stops first), and the first waits for them before its elements.
  struct {
    std::mutex mutex;
    std::condition_variable told;
    bool ready = false;
    ElementCounts counts{};
    void tell(const ElementCounts& c) {
      std::lock_guard<std::mutex> lock(mutex);
      if (ready) return;
      counts = c;
      ready = true;
      told.notify_all();
    }
  } second_counts;
  second.room = [&](const ElementCounts& mine) {
    second_counts.tell(mine);
    return mine;
  };
  first.room = [&](const ElementCounts& mine) {
    std::unique_lock<std::mutex> lock(second_counts.mutex);
    second_counts.told.wait(lock, [&] { return second_counts.ready; });
    ElementCounts both = mine;
    for (std::size_t k = 0; k < both.size(); ++k) both[k] += second_counts.counts[k];
    return both;
  };
  RunEnds first_ends, second_ends;
  FastParse tail_result = FastParse::kUseReference;
  std::exception_ptr tail_error;
  std::thread thread([&] {
    try {
      tail_result = parse_native_simdjson_run(text, second, tail, tail_root, &second_ends);
    } catch (...) {
      tail_error = std::current_exception();
    }
    second_counts.tell(ElementCounts{});  // if it stopped before counting
  });
  FastParse head_result = FastParse::kUseReference;
  std::exception_ptr head_error;
  try {
    head_result = parse_native_simdjson_run(text, first, head, head_root, &first_ends);
  } catch (...) {
    head_error = std::current_exception();
  }
  thread.join();
  if (head_error) std::rethrow_exception(head_error);
  if (tail_error) std::rethrow_exception(tail_error);
  if (head_result != FastParse::kDone || tail_result != FastParse::kDone || first_ends.last_kind != int(c.kind) ||
      first_ends.last_count == 0 || second_ends.first_count == 0)
    return FastParse::kUseReference;
  *cut = c.kind;
  *head_count = first_ends.last_count;
  return FastParse::kDone;
}

}  // namespace kintsugi::io
