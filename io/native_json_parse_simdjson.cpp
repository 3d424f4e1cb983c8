// The fast parser of the native reader: simdjson's On-Demand API walked value by value
// into JsonTrees (io/native_json_parse.h says when it gives up and why that is safe).
#include "io/native_json_parse.h"

#include "io/native_json.h"
#include "io/native_json_typed.h"

#include <simdjson.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <string_view>
#include <utility>
#include <vector>

namespace kintsugi::io {

namespace od = simdjson::ondemand;

namespace {

class SimdjsonTreeParser {
 public:
  // `bytes`: the document's, for ElementSink::expect; 0 when the caller has told the sink
  // how many elements come (a run of pieces counts them first).
  SimdjsonTreeParser(ElementSink* sink, JsonTree* root, std::size_t bytes) : sink_(sink), root_(root), bytes_(bytes) {}

  // A whole document; with `continued` >= 0, a piece of a document cut inside that element
  // array (native_json_parse.h), whose elements before the cut were `first_index`.
  bool document(od::document& doc, int continued = -1, std::size_t first_index = 0) {
    od::object top;
    if (doc.get_object().get(top)) return false;
    root_.reset();
    root_.open_object();
    bool first = true;
    for (auto member : top) {
      od::field field;
      std::string_view key;
      if (std::move(member).get(field) || !key_of(field, &key)) return false;
      od::value v = field.value();
      od::json_type type;
      if (v.type().get(type)) return false;
      if (continued >= 0 && first) {
        // The stand-in "" holds the rest of the cut array; it is no member of the document.
        first = false;
        if (!key.empty() || type != od::json_type::array || !elements(v, ElementKind(continued), false, first_index))
          return false;
        continued_count_ = count_ - first_index;
        // Until another member follows, the piece ends inside this array.
        last_kind_ = continued;
        last_count_ = count_;
        continue;
      }
      first = false;
      if (!root_.key(key)) return false;
      const int kind = element_kind(key);
      last_kind_ = -1;
      if (kind >= 0 && type == od::json_type::array) {
        if (!elements(v, ElementKind(kind))) return false;
        last_kind_ = kind;
        last_count_ = count_;
      } else if (!value(v, root_, 1)) {
        return false;
      }
    }
    root_.close();
    // Nothing but white space after the top level (current_location fails at the end).
    const char* rest = nullptr;
    return doc.current_location().get(rest) == simdjson::OUT_OF_BOUNDS;
  }

  // The last member of the top level, if it was an element array: its kind (else -1) and
  // its number of elements (for the stand-in "", counted from the array's start).
  int last_kind() const { return last_kind_; }
  std::size_t last_count() const { return last_count_; }
  // For a second half: the number of elements in the stand-in.
  std::size_t continued_count() const { return continued_count_; }

 private:
  ElementSink* sink_;
  JsonTreeBuilder root_;
  std::size_t bytes_;
  JsonTree element_tree_;
  JsonTreeBuilder element_{&element_tree_};
  int last_kind_ = -1;
  std::size_t last_count_ = 0, continued_count_ = 0, count_ = 0;

  static int element_kind(std::string_view key) {
    for (int k = 0; k < kElementKinds; ++k)
      if (key == kElementKeys[k]) return k;
    return -1;
  }

  // A member's key. Most keys have no escapes, and their text in the document is the key:
  // no copy into simdjson's string buffer (stage 1 has checked the document's UTF-8, its
  // quotes and that no control character is unescaped).
  static bool key_of(od::field& field, std::string_view* key) {
    const char* raw = field.key().raw();
    const char* end = raw;
    while (*end != '"' && *end != '\\') ++end;
    if (*end == '"') {
      *key = std::string_view(raw, std::size_t(end - raw));
      return true;
    }
    return !field.unescaped_key().get(*key);
  }

  // An element array: an empty stand-in in the top level (`stand_in`); each element
  // built alone, numbered from `first_index`.
  bool elements(od::value& v, ElementKind kind, bool stand_in = true, std::size_t first_index = 0) {
    if (stand_in) {
      root_.open_array();
      root_.close();
    }
    od::array a;
    std::size_t count = 0;
    if (v.get_array().get(a) || a.count_elements().get(count)) return false;
    if (bytes_) sink_->expect(kind, count, bytes_);
    std::size_t index = first_index;
    for (auto item : a) {
      od::value e;
      if (std::move(item).get(e)) return false;
      element_.reset();
      if (BodyDescription* direct = sink_->direct(kind)) {
        // Typed reading (io/native_json_typed.h), else the element's object from its start
        // as a tree.
        od::json_type type;
        if (e.type().get(type)) return false;
        if (type == od::json_type::object) {
          od::object o;
          if (e.get_object().get(o)) return false;
          const Typed typed = read_typed_element(o, kind, direct);
          if (typed == Typed::kError) return false;
          if (typed == Typed::kRead) {
            sink_->appended(kind, index++);
            continue;
          }
          bool nonempty = false;
          if (o.reset().get(nonempty) || !members(o, element_, 2)) return false;
          sink_->element(kind, index++, JsonView(&element_tree_, 0));
          continue;
        }
      }
      if (!value(e, element_, 2)) return false;
      sink_->element(kind, index++, JsonView(&element_tree_, 0));
    }
    count_ = index;
    return true;
  }

  // An object's members into `b` (as value() reads an object).
  bool members(od::object& o, JsonTreeBuilder& b, std::size_t open) {
    if (open >= kMaxNativeDepth) return false;
    b.open_object();
    for (auto member : o) {
      od::field field;
      std::string_view key;
      if (std::move(member).get(field) || !key_of(field, &key) || !b.key(key)) return false;
      od::value child = field.value();
      if (!value(child, b, open + 1)) return false;
    }
    b.close();
    return true;
  }

  // One value into `b`; `open` containers enclose it in the document.
  bool value(od::value& v, JsonTreeBuilder& b, std::size_t open) {
    od::json_type type;
    if (v.type().get(type)) return false;
    switch (type) {
      case od::json_type::object: {
        od::object o;  // members() checks the depth
        return !v.get_object().get(o) && members(o, b, open);
      }
      case od::json_type::array: {
        if (open >= kMaxNativeDepth) return false;
        od::array a;
        if (v.get_array().get(a)) return false;
        b.open_array();
        for (auto item : a) {
          od::value child;
          if (std::move(item).get(child) || !value(child, b, open + 1)) return false;
        }
        b.close();
        return true;
      }
      case od::json_type::number: return number(v, b);
      case od::json_type::string: {
        std::string_view s;
        if (v.get_string().get(s)) return false;
        b.string(s);
        return true;
      }
      case od::json_type::boolean: {
        bool x;
        if (v.get_bool().get(x)) return false;
        b.boolean(x);
        return true;
      }
      case od::json_type::null: {
        bool is_null = false;
        if (v.is_null().get(is_null) || !is_null) return false;
        b.null();
        return true;
      }
    }
    return false;
  }

  // As nlohmann types numbers (io/native_json_typed.h).
  bool number(od::value& v, JsonTreeBuilder& b) {
    JsonNumber n;
    if (!read_json_number(v, &n)) return false;
    switch (n.type) {
      case JsonNumber::kFloat: b.floating(n.d); return true;
      case JsonNumber::kSigned: b.integer(n.i); return true;
      case JsonNumber::kUnsigned: b.unsigned_integer(n.u); return true;
    }
    return false;
  }
};

}  // namespace

std::size_t simdjson_padding() { return simdjson::SIMDJSON_PADDING; }

FastParse parse_native_simdjson(const TextSource& text, ElementSink* sink, JsonTree* root, std::size_t piece_bytes) {
  Run run;
  run.end = text.size();
  run.piece_bytes = piece_bytes;
  RunEnds ends;
  return parse_native_simdjson_run(text, run, sink, root, &ends);
}

FastParse parse_native_simdjson(const char* text, std::size_t size, std::size_t capacity, ElementSink* sink,
                                JsonTree* root, std::size_t piece_bytes) {
  return parse_native_simdjson(MemorySource(text, size, capacity), sink, root, piece_bytes);
}

namespace {

// One piece of a run: text[begin, end), continuing array `continued` (or -1); `cut`, where
// the next piece starts, if `more`.
struct Piece {
  std::size_t begin = 0, end = 0;
  bool more = false;
  Cut cut;
};

// A piece as simdjson reads it: in place when it is the whole text in memory (which has its
// padding), else copied into `buffer` with the stand-in's brackets.
class PieceReader {
 public:
  explicit PieceReader(const TextSource& text) : text_(text), size_(text.size()) {}

  // Parses the piece into `doc`; its length with the brackets in `n`.
  bool iterate(const Piece& piece, od::document* doc, std::size_t* n) {
    static constexpr std::string_view kOpen = "{\"\":[", kClose = "]}";
    const bool opens = piece.begin > 0, closes = piece.end < size_;
    *n = piece.end - piece.begin;
    if (!opens && !closes && text_.whole())
      return !parser_.iterate(simdjson::padded_string_view(text_.whole(), size_, text_.capacity())).get(*doc);
    *n += (opens ? kOpen.size() : 0) + (closes ? kClose.size() : 0);
    const std::size_t padded = *n + simdjson_padding();
    if (buffer_.size() < padded) buffer_.resize(padded);
    char* out = buffer_.data();
    if (opens) out = std::copy(kOpen.begin(), kOpen.end(), out);
    if (!text_.read(piece.begin, piece.end - piece.begin, out)) return false;
    out += piece.end - piece.begin;
    if (closes) out = std::copy(kClose.begin(), kClose.end(), out);
    std::fill(out, buffer_.data() + buffer_.size(), ' ');
    return !parser_.iterate(simdjson::padded_string_view(buffer_.data(), *n, buffer_.size())).get(*doc);
  }

 private:
  const TextSource& text_;
  std::size_t size_;
  od::parser parser_;         // its index is sized for the largest piece, and reused
  std::vector<char> buffer_;  // reused
};

// Adds the elements of each element array (and of the stand-in "") of a piece to `counts`.
bool count_elements(od::document& doc, int continued, ElementCounts* counts) {
  od::object top;
  if (doc.get_object().get(top)) return false;
  bool first = true;
  for (auto member : top) {
    od::field field;
    if (std::move(member).get(field)) return false;
    std::string_view key;
    if (field.unescaped_key().get(key)) return false;
    int kind = -1;
    if (first && continued >= 0) {
      kind = continued;
    } else {
      for (int k = 0; k < kElementKinds; ++k)
        if (key == kElementKeys[k]) kind = k;
    }
    first = false;
    if (kind < 0) continue;
    od::value v = field.value();
    od::json_type type;
    if (v.type().get(type)) return false;
    if (type != od::json_type::array) continue;
    od::array a;
    std::size_t n = 0;
    if (v.get_array().get(a) || a.count_elements().get(n)) return false;
    (*counts)[std::size_t(kind)] += n;
  }
  return true;
}

}  // namespace

FastParse parse_native_simdjson_run(const TextSource& text, const Run& run, ElementSink* sink, JsonTree* root,
                                    RunEnds* ends) {
  // The pieces, each ending at the first cut past piece_bytes from its start.
  std::vector<Piece> pieces;
  for (std::size_t pos = run.begin;;) {
    Piece piece;
    piece.begin = pos;
    const std::size_t from = pos + std::max<std::size_t>(run.piece_bytes, 1);
    piece.more = from < run.end && find_cut_in(text, from, run.end - from, &piece.cut) && piece.cut.next < run.end;
    piece.end = piece.more ? piece.cut.comma : run.end;
    pieces.push_back(piece);
    if (!piece.more) break;
    pos = piece.cut.next;
  }
  PieceReader reader(text);
  od::document doc;
  std::size_t n = 0;
  // Several pieces: their elements counted first (Run::room). One piece: its parser tells
  // the sink as it goes.
  const bool counted = pieces.size() > 1;
  if (counted) {
    ElementCounts counts{};
    int continued = run.continued;
    for (const Piece& piece : pieces) {
      if (!reader.iterate(piece, &doc, &n) || !count_elements(doc, continued, &counts)) return FastParse::kUseReference;
      continued = int(piece.cut.kind);
    }
    if (run.room) counts = run.room(counts);
    for (int k = 0; k < kElementKinds; ++k)
      if (counts[std::size_t(k)]) sink->expect(ElementKind(k), counts[std::size_t(k)], run.end - run.begin);
  }
  JsonTree piece_root, joined;
  int continued = run.continued;
  std::size_t carried = 0;   // elements of the continued array in this run before the piece
  for (const Piece& piece : pieces) {
    if (!reader.iterate(piece, &doc, &n)) return FastParse::kUseReference;
    const bool first = piece.begin == run.begin;
    SimdjsonTreeParser p(sink, first ? root : &piece_root, counted ? 0 : n);
    if (!p.document(doc, continued, carried)) return FastParse::kUseReference;
    if (first) {
      ends->first_count = p.continued_count();
    } else {
      // The piece's members after the ones before it.
      if (!join_objects(JsonView(root, 0), JsonView(&piece_root, 0), &joined)) return FastParse::kUseReference;
      std::swap(*root, joined);
    }
    if (!piece.more) {
      ends->last_kind = p.last_kind();
      ends->last_count = p.last_count();
      return FastParse::kDone;
    }
    // The piece ends inside an element array of the kind guessed for the next one, with
    // an element before the cut.
    if (p.last_kind() != int(piece.cut.kind) || p.last_count() == 0) return FastParse::kUseReference;
    continued = int(piece.cut.kind);
    carried = p.last_count();
  }
  return FastParse::kUseReference;  // not reached: the last piece has no `more`
}

}  // namespace kintsugi::io
