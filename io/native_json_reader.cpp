// The native JSON reader (spec/file-format.md): a bounded parser and a validating reader
// that turns the document into a BodyDescription and lets assemble() check the topology.
// The writer is io/native_json_writer.cpp, atomic file writes io/atomic_file.cpp.
#include "io/native_json.h"

#include "io/json_tree.h"
#include "io/native_json_parse.h"

#include "invariants/assemble.h"
#include "kernel/huge_pages.h"
#include "kernel/threads.h"
#include "geometry/freeform.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <iterator>
#include <memory>
#include <numbers>
#include <utility>
#include <vector>

namespace kintsugi::io {

using json = nlohmann::json;

namespace {

// ---- JSON pointers (RFC 6901) -------------------------------------------------------

std::string escape_token(std::string_view key) {
  std::string out;
  for (char c : key) {
    if (c == '~')
      out += "~0";
    else if (c == '/')
      out += "~1";
    else
      out += c;
  }
  return out;
}
std::string spell(const std::string& ptr, std::string_view key) { return ptr + "/" + escape_token(key); }
std::string spell(const std::string& ptr, std::size_t index) { return ptr + "/" + std::to_string(index); }

// A JSON pointer spelled only when asked: a million-element document has tens of millions
// of places, and only a refused one is ever named. A Ptr refers to its parent, so it
// lives no longer than the full expression or the scope of the Ptr it was made from.
class Ptr {
 public:
  Ptr(const char* root) : root_(root) {}  // NOLINT: a literal pointer ("/format") reads as one
  explicit Ptr(std::string_view root) : root_(root) {}
  Ptr(const Ptr& parent, std::string_view key) : parent_(&parent), key_(key), step_(kKey) {}
  Ptr(const Ptr& parent, std::size_t index) : parent_(&parent), index_(index), step_(kIndex) {}
  // A root with one step, which needs no parent to outlive it: at("/vertices", 3).
  template <class Step>
  static Ptr root(const char* root, Step step) {
    Ptr r(root);
    r.set(step);
    return r;
  }

  std::string str() const {
    std::string p = parent_ ? parent_->str() : std::string(root_);
    if (step_ == kKey) return spell(p, key_);
    if (step_ == kIndex) return spell(p, index_);
    return p;
  }

 private:
  void set(std::string_view key) {
    key_ = key;
    step_ = kKey;
  }
  void set(std::size_t index) {
    index_ = index;
    step_ = kIndex;
  }
  enum Step { kNone, kKey, kIndex };
  const Ptr* parent_ = nullptr;
  std::string_view root_, key_;
  std::size_t index_ = 0;
  Step step_ = kNone;
};
Ptr at(const char* root, std::string_view key) { return Ptr::root(root, key); }
Ptr at(const char* root, std::size_t index) { return Ptr::root(root, index); }
Ptr at(const Ptr& ptr, std::string_view key) { return Ptr(ptr, key); }
Ptr at(const Ptr& ptr, std::size_t index) { return Ptr(ptr, index); }

// "<pointer>: <message>", or the message alone for the whole document.
std::string located(const std::string& ptr, const std::string& message) {
  return ptr.empty() ? message : ptr + ": " + message;
}

// Shortest text that reads back as the same double (what the writer writes, too).
std::string number_text(double d) { return json(d).dump(); }

// What a value is, for "expected X, found Y" messages: short values verbatim.
std::string describe_value(JsonView j) {
  if (j.is_object()) return "an object";
  if (j.is_array()) return "an array";
  if (j.is_string()) return j.as_string().size() > 40 ? "a string" : "the string " + j.dump();
  return j.dump();
}

// ---- the reference parser ------------------------------------------------------------
//
// nlohmann's SAX parser, building JsonTrees: what the reader falls back on whenever
// simdjson gives up (io/native_json_parse.h), and the parser the tests and the json_reader
// fuzz target hold the fast one to. Its events let us refuse nesting beyond
// kMaxNativeDepth before it exists, name the place of a syntax error, refuse numbers that
// overflow a double (which the lexer turns into ±inf), and refuse duplicate keys (which
// nlohmann would silently resolve to the last one).
//
// The element arrays of the top-level object are not built: each of their elements is
// built alone in a tree of its own, handed to the ElementSink as soon as it is complete,
// and dropped, so the document in memory is the top level, `meta`, and one element.

class BoundedDocumentBuilder {
 public:
  std::string error;

  explicit BoundedDocumentBuilder(ElementSink* sink) : sink_(sink) {}

  // The top-level value, once parsed.
  JsonView root() const { return root_tree_.empty() ? JsonView() : JsonView(&root_tree_, 0); }

  bool null() { return add([](JsonTreeBuilder& b) { b.null(); }); }
  bool boolean(bool v) { return add([&](JsonTreeBuilder& b) { b.boolean(v); }); }
  bool number_integer(json::number_integer_t v) { return add([&](JsonTreeBuilder& b) { b.integer(v); }); }
  bool number_unsigned(json::number_unsigned_t v) { return add([&](JsonTreeBuilder& b) { b.unsigned_integer(v); }); }
  bool number_float(json::number_float_t v, const json::string_t& text) {
    if (!std::isfinite(v)) return fail("number " + text + " is out of the range of a double");
    return add([&](JsonTreeBuilder& b) { b.floating(v); });
  }
  bool string(json::string_t& v) { return add([&](JsonTreeBuilder& b) { b.string(v); }); }
  bool binary(json::binary_t&) { return fail("binary values are not part of JSON"); }
  bool start_object(std::size_t) { return open(false); }
  bool start_array(std::size_t) { return open(true); }
  bool end_object() { return close(); }
  bool end_array() { return close(); }
  bool key(json::string_t& k) {
    Level& top = stack_.back();
    top.key = k;
    top.has_key = true;
    if (!builder(top).key(k)) return fail("key appears twice in the same object");
    return true;
  }
  bool parse_error(std::size_t, const std::string&, const json::exception& ex) {
    // ex.what() is "[json.exception.parse_error.101] parse error at line 1, column 5: ...".
    std::string what = ex.what();
    if (auto close_bracket = what.find("] "); what.rfind("[json.exception", 0) == 0 && close_bracket != std::string::npos)
      what = what.substr(close_bracket + 2);
    return fail("not valid JSON: " + what);
  }

 private:
  struct Level {
    bool array;
    std::string key;         // objects: the key whose value comes next
    bool has_key = false;
    std::string open_child;  // the token of the child container being built, if any
    std::size_t count = 0;   // arrays: the children so far
    int streams = -1;        // an element array of the top level: its ElementKind
    int delivers = -1;       // an element of such an array: its kind, handed over when closed
    std::size_t index = 0;   // ... and its index
    bool in_element = false; // built in the element's tree, not the top level's
  };
  std::vector<Level> stack_;
  ElementSink* sink_;
  JsonTree root_tree_, element_tree_;
  JsonTreeBuilder root_{&root_tree_}, element_{&element_tree_};

  JsonTreeBuilder& builder(const Level& l) { return l.in_element ? element_ : root_; }

  // Pointer of the value being parsed now.
  std::string here() const {
    std::string p;
    for (std::size_t i = 0; i < stack_.size(); ++i) {
      const Level& l = stack_[i];
      if (i + 1 < stack_.size())
        p += "/" + l.open_child;
      else if (l.array)
        p += "/" + std::to_string(l.count);
      else if (l.has_key)
        p += "/" + escape_token(l.key);
    }
    return p;
  }
  bool fail(const std::string& message) {
    error = located(here(), message);
    return false;
  }
  // Which tree the next value goes to, and whether it is an element of an element array
  // (*delivers: its kind, or -1) with its index; starts the element's tree if so.
  JsonTreeBuilder& place(int* delivers, std::size_t* index, bool* in_element) {
    *delivers = -1;
    *in_element = false;
    if (stack_.empty()) {
      root_.reset();
      return root_;
    }
    Level& top = stack_.back();
    const std::size_t i = top.count;
    if (top.array)
      ++top.count;
    else
      top.has_key = false;
    if (top.streams >= 0) {
      *delivers = top.streams;
      *index = i;
      *in_element = true;
      element_.reset();
      return element_;
    }
    *in_element = top.in_element;
    return builder(top);
  }
  template <class Value>
  bool add(Value value) {
    int delivers;
    std::size_t index;
    bool in_element;
    value(place(&delivers, &index, &in_element));
    if (delivers >= 0) deliver(delivers, index);
    return true;
  }
  void deliver(int kind, std::size_t index) { sink_->element(ElementKind(kind), index, JsonView(&element_tree_, 0)); }
  bool open(bool array) {
    if (stack_.size() >= kMaxNativeDepth)
      return fail("nesting is deeper than " + std::to_string(kMaxNativeDepth) + " levels");
    int streams = -1;
    if (!stack_.empty()) {
      Level& parent = stack_.back();
      parent.open_child = parent.array ? std::to_string(parent.count) : escape_token(parent.key);
      // An array that is a member of the top-level object under an element key: it stays
      // empty in the top level's tree, its elements go to the sink.
      if (sink_ && stack_.size() == 1 && !parent.array && array)
        for (int k = 0; k < kElementKinds; ++k)
          if (parent.key == kElementKeys[k]) streams = k;
    }
    Level level{array, {}, false, {}, 0, streams, -1, 0, false};
    JsonTreeBuilder& b = place(&level.delivers, &level.index, &level.in_element);
    if (array)
      b.open_array();
    else
      b.open_object();
    stack_.push_back(std::move(level));
    return true;
  }
  bool close() {
    const Level& top = stack_.back();
    builder(top).close();
    const int delivers = top.delivers;
    const std::size_t index = top.index;
    stack_.pop_back();
    if (delivers >= 0) deliver(delivers, index);
    return true;
  }
};

// ---- validating reader --------------------------------------------------------------

const char* const kUnits[] = {"nm", "um", "mm", "cm", "m", "in", "ft"};

// One kind of element: ids → position in its array, for references and messages.
// Ids are below 2·count + 1024 (record() checks that first), so a dense table serves.
struct IdTable {
  const char* kind;    // "vertex"
  const char* plural;  // "vertices": also the top-level key
  std::vector<std::uint32_t> slot;  // id → 1 + position in the array; 0: no such id

  // The position of element `id`, or npos.
  std::size_t find(std::uint64_t id) const {
    return id < slot.size() && slot[std::size_t(id)] ? std::size_t(slot[std::size_t(id)] - 1) : std::string::npos;
  }
  bool contains(std::uint64_t id) const { return find(id) != std::string::npos; }
};

// Reads a document in two stages: element(), for each element of the element arrays as
// the parser completes it (BoundedDocumentBuilder), then finish() with the rest of the
// document once it has parsed. Errors come out in the order the checks are listed in
// spec/file-format.md whatever the order of the arrays in the text: an element's error
// is kept until finish() has checked the top level and the arrays before it.
class DocumentReader final : public ElementSink {
 public:
  explicit DocumentReader(std::string* error) : error_(error) {}

  void element(ElementKind kind, std::size_t i, JsonView e) override {
    Pending& k = pending_[kind];
    k.count = i + 1;
    if (k.failed) return;
    bool ok = false;
    switch (kind) {
      case kVertices: ok = vertex(e, i, &d_.vertices.emplace_back()); break;
      case kEdges: ok = edge(e, i, &d_.edges.emplace_back()); break;
      case kLoops: ok = loop(e, i, &d_.loops.emplace_back()); break;
      case kFaces: ok = face(e, i, &d_.faces.emplace_back()); break;
      case kShells: ok = shell(e, i, &d_.shells.emplace_back()); break;
      case kElementKinds: break;
    }
    if (!ok) {
      k.failed = true;
      k.failed_at = i;
      k.error = std::move(message_);
    }
  }

  // Typed reading appends to the descriptions only until an element of its kind is refused:
  // the ones after it are counted, not read (the refusal is the first, whatever follows).
  BodyDescription* direct(ElementKind kind) override { return pending_[kind].failed ? nullptr : &d_; }
  void appended(ElementKind kind, std::size_t i) override { pending_[kind].count = i + 1; }

  void expect(ElementKind kind, std::size_t count, std::size_t bytes) override {
    // Reserving the descriptions saves copying them as they grow (an EdgeDesc is large).
    // Not past what the document's bytes can hold of valid elements: `[1,1,1,...]` must
    // not reserve gigabytes. The shortest valid elements are {"id":0,"point":[0,0,0]},
    // {"id":0,"he":[{"origin":0,"next":0,"loop":0},{...}]}, {"id":0,"lone":0},
    // {"id":0,"shell":0,"loops":[0],"same_sense":true} and {"id":0,"genus":0}.
    static constexpr std::size_t kShortest[kElementKinds] = {24, 75, 17, 45, 18};
    count = std::min(count, bytes / kShortest[kind]);
    auto more = [count](auto& v) {
      // At least doubling, should a parser tell a piece at a time (as pushing would).
      if (v.capacity() - v.size() < count) v.reserve(std::max(v.size() + count, 2 * v.capacity()));
    };
    switch (kind) {
      case kVertices: more(d_.vertices); break;
      case kEdges: more(d_.edges); break;
      case kLoops: more(d_.loops); break;
      case kFaces: more(d_.faces); break;
      case kShells: more(d_.shells); break;
      case kElementKinds: break;
    }
  }

  // Takes the elements `tail` read from the second half of a document cut in array `cut`
  // (io/native_json_parse.h), after this reader's, which read the first half. False when
  // either refused an element: the caller then reads the whole text again, so that the
  // refusal names the element's place in the whole document.
  bool absorb(DocumentReader&& tail, ElementKind cut) {
    for (int k = 0; k < kElementKinds; ++k)
      if (pending_[k].failed || tail.pending_[k].failed || (k != cut && pending_[k].count && tail.pending_[k].count))
        return false;
    auto append = [](auto& to, auto& from) {
      if (to.empty()) {
        to = std::move(from);
        return;
      }
      to.reserve(to.size() + from.size());
      std::move(from.begin(), from.end(), std::back_inserter(to));
    };
    append(d_.vertices, tail.d_.vertices);
    append(d_.edges, tail.d_.edges);
    append(d_.loops, tail.d_.loops);
    append(d_.faces, tail.d_.faces);
    append(d_.shells, tail.d_.shells);
    for (int k = 0; k < kElementKinds; ++k) pending_[k].count += tail.pending_[k].count;
    return true;
  }

  // The document without its elements (the element arrays are there, empty).
  std::optional<NativeDocument> finish(JsonView doc) {
    NativeDocument out;
    if (!top_level(doc, &out) || !settle(kVertices, vertex_ids_, d_.vertices) || !settle(kEdges, edge_ids_, d_.edges) ||
        !settle(kLoops, loop_ids_, d_.loops) || !settle(kFaces, face_ids_, d_.faces) ||
        !settle(kShells, shell_ids_, d_.shells) || !references(d_))
      return refuse();
    AssembleError why;
    std::optional<Body> body = assemble(std::move(d_), &why);
    if (!body) {
      fail(pointer_of(why.element), why.message);
      return refuse();
    }
    out.body = std::move(*body);
    return out;
  }

 private:
  std::string* error_;
  std::string message_;  // the last failure, located
  BodyDescription d_;
  // What element() saw of each array: how many, and the first element it refused.
  struct Pending {
    std::size_t count = 0;
    bool failed = false;
    std::size_t failed_at = 0;
    std::string error;
  };
  Pending pending_[kElementKinds];
  IdTable vertex_ids_{"vertex", "vertices", {}}, edge_ids_{"edge", "edges", {}}, loop_ids_{"loop", "loops", {}},
      face_ids_{"face", "faces", {}}, shell_ids_{"shell", "shells", {}};

  bool fail(const std::string& ptr, const std::string& message) {
    message_ = located(ptr, message);
    return false;
  }
  bool fail(const Ptr& ptr, const std::string& message) { return fail(ptr.str(), message); }
  bool fail(const char* ptr, const std::string& message) { return fail(std::string(ptr), message); }
  std::optional<NativeDocument> refuse() {
    if (error_) *error_ = std::move(message_);
    return std::nullopt;
  }

  // Records the ids of the elements of `kind` in `t` now their count is known, in order,
  // up to the first element element() refused, whose error comes after theirs.
  template <class Desc>
  bool settle(ElementKind kind, IdTable& t, const std::vector<Desc>& items) {
    const Pending& k = pending_[kind];
    const std::size_t good = k.failed ? k.failed_at : k.count;
    t.slot.assign(2 * k.count + 1024, 0);
    for (std::size_t i = 0; i < good; ++i)
      if (!record(t, items[i].id, i, k.count)) return false;
    if (k.failed) {
      message_ = k.error;
      return false;
    }
    return true;
  }

  // -- values --

  // Checks `j` is an object whose keys are all in `allowed`; names every stranger.
  bool object_with_keys(JsonView j, const Ptr& ptr, std::initializer_list<std::string_view> allowed,
                        const std::string& what) {
    if (!j.is_object()) return fail(ptr, "expected " + what + " (an object), found " + describe_value(j));
    std::vector<std::string> unknown;
    for (JsonView item = j.first(); item; item = item.next()) {
      bool known = false;
      for (std::string_view a : allowed) known = known || item.key() == a;
      if (!known) unknown.emplace_back(item.key());
    }
    if (unknown.empty()) return true;
    std::string names, expected;
    for (const auto& u : unknown) names += (names.empty() ? "\"" : ", \"") + u + "\"";
    for (std::string_view a : allowed) expected += (expected.empty() ? "" : ", ") + std::string(a);
    return fail(at(ptr, unknown.front()),
                std::string(unknown.size() == 1 ? "unknown key " : "unknown keys ") + names + " in " + what +
                    " (it has " + expected + ")");
  }
  // The member `key` of object `obj`, or an absent view after reporting it missing.
  JsonView required(JsonView obj, const Ptr& ptr, const char* key) {
    JsonView v = obj.find(key);
    if (!v) fail(at(ptr, key), "is missing");
    return v;
  }
  // The member `key`, or an absent view when it is absent or null (an optional reference).
  static JsonView optional_member(JsonView obj, const char* key) {
    JsonView v = obj.find(key);
    return v && !v.is_null() ? v : JsonView();
  }

  bool number(JsonView j, const Ptr& ptr, double* out) {
    if (!j.is_number()) return fail(ptr, "expected a number, found " + describe_value(j));
    *out = j.as_double();
    // The parser refuses overflow; this guards documents built any other way.
    if (!std::isfinite(*out)) return fail(ptr, "expected a finite number");
    return true;
  }
  bool positive(JsonView j, const Ptr& ptr, double* out) {
    if (!number(j, ptr, out)) return false;
    if (!(*out > 0)) return fail(ptr, "must be positive, found " + number_text(*out));
    return true;
  }
  bool integer(JsonView j, const Ptr& ptr, std::uint64_t max, std::uint64_t* out) {
    if (j.is_number_unsigned()) {
      *out = j.as_unsigned();
    } else if (j.is_number_integer()) {
      return fail(ptr, "expected a non-negative integer, found " + j.dump());
    } else if (j.is_number_float()) {
      return fail(ptr, "expected an integer, found " + j.dump());
    } else {
      return fail(ptr, "expected a non-negative integer, found " + describe_value(j));
    }
    if (*out > max) return fail(ptr, std::to_string(*out) + " is out of range (at most " + std::to_string(max) + ")");
    return true;
  }
  bool id(JsonView j, const Ptr& ptr, std::uint64_t max, std::uint32_t* out) {
    std::uint64_t v;
    if (!integer(j, ptr, max, &v)) return false;
    *out = std::uint32_t(v);
    return true;
  }
  bool vec3(JsonView j, const Ptr& ptr, geo::Vec3* out) {
    if (!j.is_array() || j.size() != 3)
      return fail(ptr, "expected [x, y, z] (an array of 3 numbers), found " +
                           (j.is_array() ? "an array of " + std::to_string(j.size()) : describe_value(j)));
    for (std::size_t i = 0; i < 3; ++i)
      if (!number(j[i], at(ptr, i), &(*out)[Eigen::Index(i)])) return false;
    return true;
  }
  bool unit_vec3(JsonView j, const Ptr& ptr, geo::Vec3* out) {
    if (!vec3(j, ptr, out)) return false;
    double length = out->norm();
    if (!(std::abs(length - 1.0) <= kUnitTolerance))
      return fail(ptr, "is not a unit vector (its length is " + number_text(length) + ")");
    return true;
  }
  bool frame(JsonView j, const Ptr& ptr, geo::Frame* out) {
    if (!object_with_keys(j, ptr, {"origin", "x", "z"}, "a frame")) return false;
    JsonView o, x, z;
    if (!(o = required(j, ptr, "origin")) || !(x = required(j, ptr, "x")) || !(z = required(j, ptr, "z"))) return false;
    if (!vec3(*o, at(ptr, "origin"), &out->origin) || !unit_vec3(*x, at(ptr, "x"), &out->x) ||
        !unit_vec3(*z, at(ptr, "z"), &out->z))
      return false;
    double dot = out->x.dot(out->z);
    if (!(std::abs(dot) <= kUnitTolerance))
      return fail(ptr, "x and z are not perpendicular (their dot product is " + number_text(dot) + ")");
    return true;
  }
  // Reads the number member `key` of `obj`, checked by `check` (one of the above).
  template <class Check>
  bool field(JsonView obj, const Ptr& ptr, const char* key, double* out, Check check) {
    JsonView v = required(obj, ptr, key);
    return v && (this->*check)(*v, at(ptr, key), out);
  }
  // The "type" member of a geometry object.
  bool geometry_type(JsonView j, const Ptr& ptr, const char* what, std::string* type) {
    if (!j.is_object()) return fail(ptr, std::string("expected ") + what + " (an object or null), found " + describe_value(j));
    JsonView t = required(j, ptr, "type");
    if (!t) return false;
    if (!t->is_string()) return fail(at(ptr, "type"), "expected a string, found " + describe_value(*t));
    *type = std::string(t->as_string());
    return true;
  }

  // -- free-form geometry (spec/file-format.md, "Free-form geometry") --

  bool count_field(JsonView obj, const Ptr& ptr, const char* key, int lo, int* out) {
    JsonView v = required(obj, ptr, key);
    std::uint64_t n = 0;
    if (!v || !integer(*v, at(ptr, key), 1u << 24, &n)) return false;
    if (int(n) < lo) return fail(at(ptr, key), "must be at least " + std::to_string(lo) + ", found " + std::to_string(n));
    *out = int(n);
    return true;
  }
  bool flag_field(JsonView obj, const Ptr& ptr, const char* key, bool* out) {
    JsonView v = required(obj, ptr, key);
    if (!v) return false;
    if (!v->is_boolean()) return fail(at(ptr, key), "expected true or false, found " + describe_value(*v));
    *out = v->as_bool();
    return true;
  }
  bool number_list(JsonView obj, const Ptr& ptr, const char* key, std::vector<double>* out) {
    JsonView v = required(obj, ptr, key);
    if (!v) return false;
    const Ptr p = at(ptr, key);
    if (!v->is_array()) return fail(p, "expected an array of numbers, found " + describe_value(*v));
    out->resize(v->size());
    std::size_t i = 0;
    for (JsonView x = v->first(); x; x = x.next(), ++i)
      if (!number(x, at(p, i), &(*out)[i])) return false;
    return true;
  }
  bool integer_list(JsonView obj, const Ptr& ptr, const char* key, std::vector<int>* out) {
    JsonView v = required(obj, ptr, key);
    if (!v) return false;
    const Ptr p = at(ptr, key);
    if (!v->is_array()) return fail(p, "expected an array of integers, found " + describe_value(*v));
    out->resize(v->size());
    std::size_t i = 0;
    for (JsonView x = v->first(); x; x = x.next(), ++i) {
      std::uint64_t n = 0;
      if (!integer(x, at(p, i), 1u << 24, &n)) return false;
      if (n == 0) return fail(at(p, i), "a multiplicity must be at least 1");
      (*out)[i] = int(n);
    }
    return true;
  }
  bool point_list(JsonView obj, const Ptr& ptr, const char* key, std::vector<geo::Vec3>* out) {
    JsonView v = required(obj, ptr, key);
    if (!v) return false;
    const Ptr p = at(ptr, key);
    if (!v->is_array()) return fail(p, "expected an array of points, found " + describe_value(*v));
    out->resize(v->size());
    std::size_t i = 0;
    for (JsonView x = v->first(); x; x = x.next(), ++i)
      if (!vec3(x, at(p, i), &(*out)[i])) return false;
    return true;
  }
  // Knots strictly increasing, multiplicities summing to what the degree and pole count
  // need (open: poles + degree + 1; periodic: poles, the last knot's counted once).
  bool knot_vector(const Ptr& ptr, const char* knots_key, const std::vector<double>& knots,
                   const std::vector<int>& mults, int degree, std::size_t poles, bool periodic) {
    if (knots.size() < 2) return fail(at(ptr, knots_key), "expected at least 2 knots, found " + std::to_string(knots.size()));
    if (mults.size() != knots.size())
      return fail(ptr, std::string("the multiplicities do not match ") + knots_key + " (" + std::to_string(mults.size()) +
                           " and " + std::to_string(knots.size()) + ")");
    for (std::size_t i = 1; i < knots.size(); ++i)
      if (!(knots[i] > knots[i - 1])) return fail(at(at(ptr, knots_key), i), "knots must be strictly increasing");
    std::size_t sum = 0;
    for (std::size_t i = 0; i < mults.size(); ++i)
      if (!periodic || i + 1 < mults.size()) sum += std::size_t(mults[i]);
    const std::size_t need = periodic ? poles : poles + std::size_t(degree) + 1;
    if (sum != need)
      return fail(ptr, std::string("the multiplicities of ") + knots_key + " sum to " + std::to_string(sum) + ", but degree " +
                           std::to_string(degree) + " with " + std::to_string(poles) + " poles needs " + std::to_string(need));
    return true;
  }
  bool weights_ok(const Ptr& ptr, const std::vector<double>& w, std::size_t poles) {
    if (w.empty()) return true;
    if (w.size() != poles)
      return fail(at(ptr, "weights"), "expected one weight per pole (" + std::to_string(poles) + "), found " + std::to_string(w.size()));
    for (std::size_t i = 0; i < w.size(); ++i)
      if (!(w[i] > 0)) return fail(at(at(ptr, "weights"), i), "weights must be positive");
    return true;
  }
  bool freeform_available(const Ptr& ptr) {
    if (std::string why = geo::freeform_unavailable(); !why.empty()) return fail(ptr, why);
    return true;
  }
  bool bspline_curve(JsonView j, const Ptr& ptr, geo::BSplineCurve* c) {
    if (!object_with_keys(j, ptr, {"type", "degree", "poles", "weights", "knots", "multiplicities", "periodic"},
                          "a bspline_curve"))
      return false;
    if (JsonView t = j.find("type"); t && !t.is_string("bspline_curve")) return fail(at(ptr, "type"), "expected \"bspline_curve\"");
    if (!count_field(j, ptr, "degree", 1, &c->degree) || !point_list(j, ptr, "poles", &c->poles) ||
        !number_list(j, ptr, "knots", &c->knots) || !integer_list(j, ptr, "multiplicities", &c->multiplicities) ||
        !flag_field(j, ptr, "periodic", &c->periodic))
      return false;
    if (j.find("weights") && !number_list(j, ptr, "weights", &c->weights)) return false;
    if (c->poles.size() < 2) return fail(at(ptr, "poles"), "expected at least 2 poles");
    return weights_ok(ptr, c->weights, c->poles.size()) &&
           knot_vector(ptr, "knots", c->knots, c->multiplicities, c->degree, c->poles.size(), c->periodic);
  }
  bool bspline_surface(JsonView j, const Ptr& ptr, geo::BSplineSurface* b) {
    if (!object_with_keys(j, ptr,
                          {"type", "u_degree", "v_degree", "u_count", "v_count", "poles", "weights", "u_knots", "v_knots",
                           "u_multiplicities", "v_multiplicities", "u_periodic", "v_periodic"},
                          "a bspline_surface"))
      return false;
    if (JsonView t = j.find("type"); t && !t.is_string("bspline_surface")) return fail(at(ptr, "type"), "expected \"bspline_surface\"");
    if (!count_field(j, ptr, "u_degree", 1, &b->u_degree) || !count_field(j, ptr, "v_degree", 1, &b->v_degree) ||
        !count_field(j, ptr, "u_count", 2, &b->u_count) || !count_field(j, ptr, "v_count", 2, &b->v_count) ||
        !point_list(j, ptr, "poles", &b->poles) || !number_list(j, ptr, "u_knots", &b->u_knots) ||
        !number_list(j, ptr, "v_knots", &b->v_knots) || !integer_list(j, ptr, "u_multiplicities", &b->u_multiplicities) ||
        !integer_list(j, ptr, "v_multiplicities", &b->v_multiplicities) ||
        !flag_field(j, ptr, "u_periodic", &b->u_periodic) || !flag_field(j, ptr, "v_periodic", &b->v_periodic))
      return false;
    if (j.find("weights") && !number_list(j, ptr, "weights", &b->weights)) return false;
    const std::size_t n = std::size_t(b->u_count) * std::size_t(b->v_count);
    if (b->poles.size() != n)
      return fail(at(ptr, "poles"), "expected u_count x v_count = " + std::to_string(n) + " poles, found " + std::to_string(b->poles.size()));
    return weights_ok(ptr, b->weights, n) &&
           knot_vector(ptr, "u_knots", b->u_knots, b->u_multiplicities, b->u_degree, std::size_t(b->u_count), b->u_periodic) &&
           knot_vector(ptr, "v_knots", b->v_knots, b->v_multiplicities, b->v_degree, std::size_t(b->v_count), b->v_periodic);
  }
  // The backend's own verdict on data that passed the structural checks.
  bool freeform_valid(const Ptr& ptr, const geo::Surface& s) {
    std::string why = geo::require_freeform().surface_problem(s);
    return why.empty() || fail(ptr, why);
  }
  bool freeform_valid(const Ptr& ptr, const geo::Curve& c) {
    std::string why = geo::require_freeform().curve_problem(c);
    return why.empty() || fail(ptr, why);
  }

  // -- geometry --

  bool surface(JsonView j, const Ptr& ptr, geo::Surface* out) {
    if (!j || j->is_null()) {
      *out = std::monostate{};
      return true;
    }
    std::string type;
    if (!geometry_type(*j, ptr, "a surface", &type)) return false;
    const std::string what = "a " + type + " surface";
    auto with_frame = [&](geo::Frame* f) {
      JsonView fr = required(*j, ptr, "frame");
      return fr && frame(*fr, at(ptr, "frame"), f);
    };
    if (type == "plane") {
      geo::Plane s;
      if (!object_with_keys(*j, ptr, {"type", "frame"}, what) || !with_frame(&s.frame)) return false;
      *out = s;
    } else if (type == "cylinder" || type == "sphere") {
      double r;
      geo::Frame f;
      if (!object_with_keys(*j, ptr, {"type", "frame", "radius"}, what) || !with_frame(&f) ||
          !field(*j, ptr, "radius", &r, &DocumentReader::positive))
        return false;
      if (type == "cylinder")
        *out = geo::Cylinder{f, r};
      else
        *out = geo::Sphere{f, r};
    } else if (type == "cone") {
      geo::Cone s;
      if (!object_with_keys(*j, ptr, {"type", "frame", "radius", "half_angle"}, what) || !with_frame(&s.frame) ||
          !field(*j, ptr, "radius", &s.radius, &DocumentReader::number) ||
          !field(*j, ptr, "half_angle", &s.half_angle, &DocumentReader::number))
        return false;
      // radius 0 is allowed: the frame origin is then the apex.
      if (!(s.radius >= 0)) return fail(at(ptr, "radius"), "must not be negative, found " + number_text(s.radius));
      if (!(std::abs(s.half_angle) < std::numbers::pi / 2) || s.half_angle == 0)
        return fail(at(ptr, "half_angle"),
                    "must be in (-pi/2, pi/2) and not 0 (radians), found " + number_text(s.half_angle));
      *out = s;
    } else if (type == "torus") {
      geo::Torus s;
      if (!object_with_keys(*j, ptr, {"type", "frame", "major_radius", "minor_radius"}, what) ||
          !with_frame(&s.frame) || !field(*j, ptr, "major_radius", &s.major_radius, &DocumentReader::positive) ||
          !field(*j, ptr, "minor_radius", &s.minor_radius, &DocumentReader::positive))
        return false;
      if (!(s.minor_radius < s.major_radius))
        return fail(at(ptr, "minor_radius"), "must be less than major_radius (" + number_text(s.major_radius) +
                                                 "), found " + number_text(s.minor_radius));
      *out = s;
    } else if (type == "bspline_surface") {
      geo::BSplineSurface b;
      if (!freeform_available(ptr) || !bspline_surface(*j, ptr, &b)) return false;
      *out = std::move(b);
      return freeform_valid(ptr, *out);
    } else if (type == "revolution_surface") {
      geo::RevolutionSurface r;
      JsonView basis, o, a;
      if (!freeform_available(ptr) || !object_with_keys(*j, ptr, {"type", "basis", "origin", "axis"}, what) ||
          !(basis = required(*j, ptr, "basis")) || !bspline_curve(*basis, at(ptr, "basis"), &r.basis) ||
          !(o = required(*j, ptr, "origin")) || !vec3(*o, at(ptr, "origin"), &r.origin) ||
          !(a = required(*j, ptr, "axis")) || !unit_vec3(*a, at(ptr, "axis"), &r.axis))
        return false;
      *out = std::move(r);
      return freeform_valid(ptr, *out);
    } else if (type == "extrusion_surface") {
      geo::ExtrusionSurface e;
      JsonView basis, d;
      if (!freeform_available(ptr) || !object_with_keys(*j, ptr, {"type", "basis", "direction"}, what) ||
          !(basis = required(*j, ptr, "basis")) || !bspline_curve(*basis, at(ptr, "basis"), &e.basis) ||
          !(d = required(*j, ptr, "direction")) || !unit_vec3(*d, at(ptr, "direction"), &e.direction))
        return false;
      *out = std::move(e);
      return freeform_valid(ptr, *out);
    } else if (type == "offset_surface") {
      geo::OffsetSurface o;
      JsonView basis;
      if (!freeform_available(ptr) || !object_with_keys(*j, ptr, {"type", "basis", "distance"}, what) ||
          !(basis = required(*j, ptr, "basis")) || !bspline_surface(*basis, at(ptr, "basis"), &o.basis) ||
          !field(*j, ptr, "distance", &o.distance, &DocumentReader::number))
        return false;
      *out = std::move(o);
      return freeform_valid(ptr, *out);
    } else {
      return fail(at(ptr, "type"), "unknown surface type \"" + type +
                                       "\" (expected plane, cylinder, cone, sphere, torus, bspline_surface, "
                                       "revolution_surface, extrusion_surface or offset_surface; null for none)");
    }
    return true;
  }

  bool curve(JsonView j, const Ptr& ptr, geo::Curve* out) {
    if (!j || j->is_null()) {
      *out = std::monostate{};
      return true;
    }
    std::string type;
    if (!geometry_type(*j, ptr, "a curve", &type)) return false;
    const std::string what = "a " + type + " curve";
    if (type == "line") {
      geo::Line c;
      JsonView o, d;
      if (!object_with_keys(*j, ptr, {"type", "origin", "direction"}, what) || !(o = required(*j, ptr, "origin")) ||
          !(d = required(*j, ptr, "direction")) || !vec3(*o, at(ptr, "origin"), &c.origin) ||
          !unit_vec3(*d, at(ptr, "direction"), &c.direction))
        return false;
      *out = c;
    } else if (type == "circle") {
      geo::Circle c;
      JsonView f;
      if (!object_with_keys(*j, ptr, {"type", "frame", "radius"}, what) || !(f = required(*j, ptr, "frame")) ||
          !frame(*f, at(ptr, "frame"), &c.frame) || !field(*j, ptr, "radius", &c.radius, &DocumentReader::positive))
        return false;
      *out = c;
    } else if (type == "ellipse") {
      geo::Ellipse c;
      JsonView f;
      if (!object_with_keys(*j, ptr, {"type", "frame", "major_radius", "minor_radius"}, what) ||
          !(f = required(*j, ptr, "frame")) || !frame(*f, at(ptr, "frame"), &c.frame) ||
          !field(*j, ptr, "major_radius", &c.major_radius, &DocumentReader::positive) ||
          !field(*j, ptr, "minor_radius", &c.minor_radius, &DocumentReader::positive))
        return false;
      if (!(c.minor_radius <= c.major_radius))
        return fail(at(ptr, "minor_radius"), "must not exceed major_radius (" + number_text(c.major_radius) +
                                                 "), found " + number_text(c.minor_radius));
      *out = c;
    } else if (type == "polyline") {
      geo::Polyline c;
      JsonView pts;
      if (!object_with_keys(*j, ptr, {"type", "points", "chordal_error"}, what) ||
          !(pts = required(*j, ptr, "points")) ||
          !field(*j, ptr, "chordal_error", &c.chordal_error, &DocumentReader::number))
        return false;
      if (!(c.chordal_error >= 0))
        return fail(at(ptr, "chordal_error"), "must not be negative, found " + number_text(c.chordal_error));
      const Ptr pp = at(ptr, "points");
      if (!pts->is_array() || pts->size() < 2)
        return fail(pp, "expected an array of at least 2 points, found " +
                            (pts->is_array() ? "an array of " + std::to_string(pts->size()) : describe_value(*pts)));
      c.points.resize(pts->size());
      std::size_t i = 0;
      for (JsonView x = pts->first(); x; x = x.next(), ++i)
        if (!vec3(x, at(pp, i), &c.points[i])) return false;
      *out = std::move(c);
    } else if (type == "bspline_curve") {
      geo::BSplineCurve b;
      if (!freeform_available(ptr) || !bspline_curve(*j, ptr, &b)) return false;
      *out = std::move(b);
      return freeform_valid(ptr, *out);
    } else {
      return fail(at(ptr, "type"), "unknown curve type \"" + type +
                                       "\" (expected line, circle, ellipse, polyline or bspline_curve; null for none)");
    }
    return true;
  }

  // -- document --

  bool top_level(JsonView doc, NativeDocument* out) {
    if (!object_with_keys(doc, "", {"format", "version", "units", "vertices", "edges", "loops", "faces", "shells", "meta"},
                          "a kintsugi-brep document"))
      return false;
    JsonView format, version, units;
    if (!(format = required(doc, "", "format"))) return false;
    if (!format->is_string("kintsugi-brep")) return fail("/format", "expected \"kintsugi-brep\", found " + describe_value(*format));
    if (!(version = required(doc, "", "version"))) return false;
    std::uint64_t v;
    if (!integer(*version, "/version", kMaxId, &v)) return false;
    if (v != 1) return fail("/version", "unsupported version " + std::to_string(v) + " (this reader reads version 1)");
    if (!(units = required(doc, "", "units"))) return false;
    bool known = false;
    for (const char* u : kUnits) known = known || units->is_string(u);
    if (!known)
      return fail("/units", "expected one of \"nm\", \"um\", \"mm\", \"cm\", \"m\", \"in\", \"ft\", found " +
                                describe_value(*units));
    out->units = std::string(units->as_string());
    for (const char* key : {"vertices", "edges", "loops", "faces", "shells"}) {
      JsonView a = required(doc, "", key);
      if (!a) return false;
      if (!a->is_array()) return fail(at("", key), "expected an array, found " + describe_value(*a));
    }
    if (JsonView m = doc.find("meta")) {
      if (!meta(m)) return false;
      out->meta = m.to_json();
    }
    return true;
  }

  // meta is free-form; the two keys kintsugi itself reads are checked.
  bool meta(JsonView m) {
    if (!m.is_object()) return fail("/meta", "expected an object, found " + describe_value(m));
    if (JsonView t = m.find("tolerance")) {
      double tol;
      if (!positive(*t, "/meta/tolerance", &tol)) return false;
    }
    if (JsonView d = m.find("defects")) {
      if (!d->is_array()) return fail("/meta/defects", "expected an array, found " + describe_value(*d));
      std::size_t i = 0;
      for (JsonView defect = d->first(); defect; defect = defect.next(), ++i) {
        const Ptr p = at("/meta/defects", i);
        if (!defect.is_object()) return fail(p, "expected a defect (an object), found " + describe_value(defect));
        JsonView type, elements, size;
        double s;
        if (!(type = required(defect, p, "type")) || !(elements = required(defect, p, "elements")) ||
            !(size = required(defect, p, "size")))
          return false;
        if (!type->is_string()) return fail(at(p, "type"), "expected a string, found " + describe_value(*type));
        if (!elements->is_array()) return fail(at(p, "elements"), "expected an array, found " + describe_value(*elements));
        if (!number(*size, at(p, "size"), &s)) return false;
      }
    }
    return true;
  }

  // Records `id` of element `i` in `t` (sized for `count`): unique, and below the bound
  // assemble() enforces (2·count + 1024), checked here too so the message names the place.
  bool record(IdTable& t, std::uint32_t id, std::size_t i, std::size_t count) {
    std::uint64_t limit = 2 * std::uint64_t(count) + 1024;
    if (id >= limit)
      return fail(at(at(at("", t.plural), i), "id"), std::string(t.kind) + " id " + std::to_string(id) +
                                                      " is too large for " + std::to_string(count) + " " + t.plural +
                                                      " (ids must be below " + std::to_string(limit) + ")");
    if (std::size_t seen = t.find(id); seen != std::string::npos)
      return fail(at(at(at("", t.plural), i), "id"), std::string(t.kind) + " id " + std::to_string(id) +
                                                      " is used twice (also at " + at(at("", t.plural), seen).str() + ")");
    t.slot[id] = std::uint32_t(i + 1);
    return true;
  }

  // One element each; ids are recorded by settle() once the array's length is known.

  bool vertex(JsonView v, std::size_t i, VertexDesc* out) {
    const Ptr p = at("/vertices", i);
    JsonView id_j, pt;
    return object_with_keys(v, p, {"id", "point"}, "a vertex") && (id_j = required(v, p, "id")) &&
           (pt = required(v, p, "point")) && id(*id_j, at(p, "id"), kMaxId, &out->id) &&
           vec3(*pt, at(p, "point"), &out->point);
  }

  bool edge(JsonView e, std::size_t i, EdgeDesc* out) {
    const Ptr p = at("/edges", i);
    JsonView id_j, he;
    if (!object_with_keys(e, p, {"id", "he", "curve"}, "an edge") || !(id_j = required(e, p, "id")) ||
        !(he = required(e, p, "he")) || !id(*id_j, at(p, "id"), kMaxEdgeId, &out->id))
      return false;
    const Ptr hp = at(p, "he");
    if (!he->is_array() || he->size() != 2)
      return fail(hp, "expected the edge's two half-edges (an array of 2 objects), found " +
                          (he->is_array() ? "an array of " + std::to_string(he->size()) : describe_value(*he)));
    for (std::size_t side = 0; side < 2; ++side) {
      JsonView h = (*he)[side];
      const Ptr sp = at(hp, side);
      JsonView o, n, l;
      if (!object_with_keys(h, sp, {"origin", "next", "loop"}, "a half-edge") || !(o = required(h, sp, "origin")) ||
          !(n = required(h, sp, "next")) || !(l = required(h, sp, "loop")) ||
          !id(*o, at(sp, "origin"), kMaxId, &out->he[side].origin) ||
          !id(*n, at(sp, "next"), kMaxId, &out->he[side].next) || !id(*l, at(sp, "loop"), kMaxId, &out->he[side].loop))
        return false;
    }
    return curve(optional_member(e, "curve"), at(p, "curve"), &out->curve);
  }

  bool loop(JsonView l, std::size_t i, LoopDesc* out) {
    const Ptr p = at("/loops", i);
    JsonView id_j;
    if (!object_with_keys(l, p, {"id", "face", "first", "lone"}, "a loop") || !(id_j = required(l, p, "id")) ||
        !id(*id_j, at(p, "id"), kMaxId, &out->id))
      return false;
    std::uint32_t v;
    if (JsonView f = optional_member(l, "face")) {
      if (!id(*f, at(p, "face"), kMaxId, &v)) return false;
      out->face = v;
    }
    JsonView first = optional_member(l, "first");
    JsonView lone = optional_member(l, "lone");
    if (first && lone)
      return fail(p, "has both \"first\" and \"lone\": a loop is either a cycle of half-edges or a lone vertex");
    if (!first && !lone) return fail(p, "has neither \"first\" (a half-edge of its cycle) nor \"lone\" (its lone vertex)");
    if (first) {
      if (!id(*first, at(p, "first"), kMaxId, &v)) return false;
      out->first = v;
    } else {
      if (!id(*lone, at(p, "lone"), kMaxId, &v)) return false;
      out->lone = v;
    }
    return true;
  }

  bool face(JsonView f, std::size_t i, FaceDesc* out) {
    const Ptr p = at("/faces", i);
    JsonView id_j, shell, ls, sense;
    if (!object_with_keys(f, p, {"id", "shell", "loops", "same_sense", "surface"}, "a face") ||
        !(id_j = required(f, p, "id")) || !(shell = required(f, p, "shell")) || !(ls = required(f, p, "loops")) ||
        !(sense = required(f, p, "same_sense")) || !id(*id_j, at(p, "id"), kMaxId, &out->id) ||
        !id(*shell, at(p, "shell"), kMaxId, &out->shell))
      return false;
    const Ptr lp = at(p, "loops");
    if (!ls->is_array() || ls->empty())
      return fail(lp, "expected the face's loops, outer first (a non-empty array), found " +
                          (ls->is_array() ? "an empty array" : describe_value(*ls)));
    out->loops.resize(ls->size());
    std::size_t k = 0;
    for (JsonView x = ls->first(); x; x = x.next(), ++k)
      if (!id(x, at(lp, k), kMaxId, &out->loops[k])) return false;
    if (!sense->is_boolean()) return fail(at(p, "same_sense"), "expected true or false, found " + describe_value(*sense));
    out->same_sense = sense->as_bool();
    return surface(optional_member(f, "surface"), at(p, "surface"), &out->surface);
  }

  bool shell(JsonView s, std::size_t i, ShellDesc* out) {
    const Ptr p = at("/shells", i);
    JsonView id_j, genus;
    return object_with_keys(s, p, {"id", "genus"}, "a shell") && (id_j = required(s, p, "id")) &&
           (genus = required(s, p, "genus")) && id(*id_j, at(p, "id"), kMaxId, &out->id) &&
           id(*genus, at(p, "genus"), kMaxId, &out->genus);
  }

  // -- references --

  // Pointers are spelled only for the reference that is wrong: a million-face document
  // has millions of references.
  bool refers(const IdTable& t, std::uint64_t id, const char* noun, const std::function<std::string()>& ptr) {
    if (t.contains(id)) return true;
    return fail(ptr(), std::string("refers to ") + noun + " " + std::to_string(id) + ", which does not exist");
  }
  bool refers_to_halfedge(std::uint32_t h, const std::function<std::string()>& ptr) {
    if (edge_ids_.contains(h >> 1)) return true;
    return fail(ptr(), "refers to half-edge " + std::to_string(h) + ", which does not exist (there is no edge " +
                           std::to_string(h >> 1) + ")");
  }

  // Every reference names an element of the right kind; what they say about each other
  // (cycles, ownership, Euler–Poincaré) is assemble()'s to check.
  bool references(const BodyDescription& d) {
    for (std::size_t i = 0; i < d.edges.size(); ++i)
      for (std::size_t side = 0; side < 2; ++side) {
        auto p = [&](const char* key) { return [=] { return at(at(at(at("/edges", i), "he"), side), key).str(); }; };
        const HalfedgeDesc& h = d.edges[i].he[side];
        if (!refers(vertex_ids_, h.origin, "vertex", p("origin")) || !refers_to_halfedge(h.next, p("next")) ||
            !refers(loop_ids_, h.loop, "loop", p("loop")))
          return false;
      }
    for (std::size_t i = 0; i < d.loops.size(); ++i) {
      auto p = [&](const char* key) { return [=] { return at(at("/loops", i), key).str(); }; };
      const LoopDesc& l = d.loops[i];
      if (l.face && !refers(face_ids_, *l.face, "face", p("face"))) return false;
      if (l.first && !refers_to_halfedge(*l.first, p("first"))) return false;
      if (l.lone && !refers(vertex_ids_, *l.lone, "vertex", p("lone"))) return false;
    }
    for (std::size_t i = 0; i < d.faces.size(); ++i) {
      const FaceDesc& f = d.faces[i];
      if (!refers(shell_ids_, f.shell, "shell", [&] { return at(at("/faces", i), "shell").str(); })) return false;
      for (std::size_t k = 0; k < f.loops.size(); ++k) {
        auto lp = [&] { return at(at(at("/faces", i), "loops"), k).str(); };
        if (!refers(loop_ids_, f.loops[k], "loop", lp)) return false;
        const LoopDesc& l = d.loops[loop_ids_.find(f.loops[k])];
        if (!l.face)
          return fail(lp(), "loop " + std::to_string(l.id) + " is a border cycle (its face is null), not a loop of face " +
                                std::to_string(f.id));
        if (*l.face != f.id)
          return fail(lp(), "loop " + std::to_string(l.id) + " belongs to face " + std::to_string(*l.face) +
                                ", not to face " + std::to_string(f.id));
      }
    }
    return true;
  }

  // The pointer of an element named by assemble() or the topology check: "edge 3",
  // "edge 3 half-edge 1", "loop 2", or a printed handle "h7", "v3", "f1".
  std::string pointer_of(const std::string& element) const {
    auto number_after = [&](std::size_t pos, std::uint64_t* n) {
      std::uint64_t v = 0;
      auto [end, ec] = std::from_chars(element.data() + pos, element.data() + element.size(), v);
      if (ec != std::errc() || end == element.data() + pos) return std::string::npos;
      *n = v;
      return std::size_t(end - element.data());
    };
    auto place = [&](const IdTable& t, std::uint64_t id) -> std::string {
      const std::size_t i = t.find(id);
      return i == std::string::npos ? std::string() : at(at("", t.plural), i).str();
    };
    const std::pair<const char*, const IdTable*> words[] = {{"vertex ", &vertex_ids_}, {"edge ", &edge_ids_},
                                                            {"loop ", &loop_ids_},     {"face ", &face_ids_},
                                                            {"shell ", &shell_ids_}};
    std::uint64_t n = 0;
    for (auto [word, table] : words) {
      std::size_t len = std::strlen(word);
      if (element.rfind(word, 0) != 0) continue;
      std::size_t end = number_after(len, &n);
      if (end == std::string::npos) return "";
      std::string p = place(*table, n);
      std::uint64_t side = 0;
      if (table == &edge_ids_ && !p.empty() && element.compare(end, 11, " half-edge ") == 0 &&
          number_after(end + 11, &side) != std::string::npos && side < 2)
        p = spell(spell(p, "he"), std::size_t(side));
      return p;
    }
    if (element.size() < 2 || number_after(1, &n) != element.size()) return "";
    switch (element[0]) {
      case 'v': return place(vertex_ids_, n);
      case 'e': return place(edge_ids_, n);
      case 'h': {
        std::string p = place(edge_ids_, n >> 1);
        return p.empty() ? p : spell(spell(p, "he"), std::size_t(n & 1));
      }
      case 'l': return place(loop_ids_, n);
      case 'f': return place(face_ids_, n);
      case 's': return place(shell_ids_, n);
      default: return "";
    }
  }
};

// Documents from this size on are read in two halves at once, where two threads may be
// used (KINTSUGI_THREADS, else the machine's).
constexpr std::size_t kHalvesFromBytes = std::size_t(8) << 20;

// Files from this size on are read a piece at a time rather than whole.
constexpr std::size_t kStreamFromBytes = std::size_t(8) << 20;

bool read_in_halves(std::size_t size, NativeParser which) {
  if (which == NativeParser::kSimdjsonHalves) return true;
  return which == NativeParser::kSimdjsonFirst && size >= kHalvesFromBytes && threads_from_environment() >= 2;
}

// The fast reader in pieces (io/native_json_parse.h): `decided` once a parse has run to its
// end, with the document or the refusal of its elements (`error`); not when a parse gave
// up, and the caller reads the text another way. `release` (if given) frees the text:
// called once it has been parsed, before the body is assembled, so that the text and the
// body are never in memory together.
struct Attempt {
  bool decided = false;
  std::optional<NativeDocument> doc;
};
Attempt parse_in_pieces(const TextSource& text, NativeParser which, std::string* error,
                        const std::function<void()>& release) {
  Attempt out;
  if (which == NativeParser::kReferenceOnly) return out;
  // The tests and the fuzzer cut a document at every element (of their small documents).
  const std::size_t pieces = which == NativeParser::kSimdjsonHalves ? 1 : Run{}.piece_bytes;
  if (read_in_halves(text.size(), which)) {
    DocumentReader head(error), tail(error);
    JsonTree head_root, tail_root, root;
    ElementKind cut;
    std::size_t head_count = 0;
    if (parse_native_simdjson_halves(text, &head, &head_root, &tail, &tail_root, &cut, &head_count, pieces) ==
            FastParse::kDone &&
        head.absorb(std::move(tail), cut) && join_objects(JsonView(&head_root, 0), JsonView(&tail_root, 0), &root)) {
      if (release) release();
      out.decided = true;
      out.doc = head.finish(JsonView(&root, 0));
      return out;
    }
  }
  DocumentReader reader(error);
  JsonTree root;
  if (parse_native_simdjson(text, &reader, &root, pieces) == FastParse::kDone) {
    if (release) release();
    out.decided = true;
    out.doc = reader.finish(JsonView(&root, 0));
  }
  return out;
}

// The whole reader over text[0, size), with simdjson_padding() readable bytes past the
// end of the text (`capacity` is the whole buffer): in pieces (unless `pieces_tried`),
// then whole (a cut that is no place between elements: a large `meta` on lines of its
// own), then the reference parser.
std::optional<NativeDocument> parse_document(const char* text, std::size_t size, std::size_t capacity, NativeParser which,
                                             std::string* error, const std::function<void()>& release = {},
                                             bool pieces_tried = false) {
  try {
    const MemorySource source(text, size, capacity);
    if (!pieces_tried)
      if (Attempt a = parse_in_pieces(source, which, error, release); a.decided) return std::move(a.doc);
    if (which != NativeParser::kReferenceOnly) {
      DocumentReader reader(error);
      JsonTree root;
      if (parse_native_simdjson(source, &reader, &root, size) == FastParse::kDone) {
        if (release) release();
        return reader.finish(JsonView(&root, 0));
      }
    }
    DocumentReader reader(error);
    BoundedDocumentBuilder builder(&reader);
    if (!json::sax_parse(text, text + size, &builder)) {
      if (error) *error = builder.error.empty() ? "not valid JSON" : builder.error;
      return std::nullopt;
    }
    if (release) release();
    return reader.finish(builder.root());
  } catch (const std::exception& e) {
    // Nothing above throws on bad input; this is for running out of memory.
    if (error) *error = std::string("cannot read the document: ") + e.what();
    return std::nullopt;
  }
}

// A file's bytes, whole, with the padding the fast parser needs after them. Reads up to
// one byte past kMaxNativeBytes, checking the cap as it reads rather than trusting stat:
// the file may grow, or be a pipe.
struct FileText {
  std::unique_ptr<char[]> bytes;
  std::size_t size = 0, capacity = 0;
  int read_errno = 0;
  bool too_large = false;

  explicit FileText(int fd, std::size_t size_hint) {
    grow(std::min<std::size_t>(size_hint, kMaxNativeBytes) + 1);
    for (;;) {
      if (size == capacity - simdjson_padding()) grow(std::min<std::size_t>(2 * size, kMaxNativeBytes + 1));
      ssize_t n = ::read(fd, bytes.get() + size, capacity - simdjson_padding() - size);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) read_errno = errno;
      if (n <= 0) break;
      size += std::size_t(n);
      if (size > kMaxNativeBytes) {
        too_large = true;
        break;
      }
    }
    // The padding is only read, never interpreted; spaces keep it so even for a number
    // at the very end of a broken file.
    std::memset(bytes.get() + size, ' ', simdjson_padding());
  }

 private:
  void grow(std::size_t text_capacity) {
    text_capacity = std::max<std::size_t>(text_capacity, size + 1);
    auto more = std::make_unique_for_overwrite<char[]>(text_capacity + simdjson_padding());
    advise_huge_pages(more.get(), text_capacity + simdjson_padding());
    if (size) std::memcpy(more.get(), bytes.get(), size);
    bytes = std::move(more);
    capacity = text_capacity + simdjson_padding();
  }
};

}  // namespace

std::optional<NativeDocument> read_native(std::string_view text, std::string* error, NativeParser which) {
  if (text.size() > kMaxNativeBytes) {
    if (error)
      *error = "document is " + std::to_string(text.size()) + " bytes, more than the limit of " +
               std::to_string(kMaxNativeBytes);
    return std::nullopt;
  }
  if (which == NativeParser::kReferenceOnly) {
    std::string copy(text);
    return parse_document(copy.data(), copy.size(), copy.size(), which, error);
  }
  std::string padded;
  padded.reserve(text.size() + simdjson_padding());
  padded.assign(text);
  padded.resize(text.size() + simdjson_padding(), ' ');
  return parse_document(padded.data(), text.size(), padded.size(), which, error);
}

std::optional<NativeDocument> read_native_file(const std::string& path, std::string* error, NativeParser which) {
  auto refuse = [&](const std::string& why) {
    if (error) *error = path + ": " + why;
    return std::nullopt;
  };
  int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return refuse(std::string("cannot open: ") + std::strerror(errno));
  struct FdCloser {
    int fd;
    ~FdCloser() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) return refuse(std::string("cannot stat: ") + std::strerror(errno));
  if (S_ISDIR(st.st_mode)) return refuse("is a directory, not a file");
  if (S_ISREG(st.st_mode) && std::uint64_t(st.st_size) > kMaxNativeBytes)
    return refuse("is " + std::to_string(st.st_size) + " bytes, more than the limit of " +
                  std::to_string(kMaxNativeBytes) + "; refusing to read it");
  std::size_t hint = S_ISREG(st.st_mode) ? std::size_t(st.st_size) : std::size_t(1) << 16;
  // A large regular file is read a piece at a time, never whole (io/text_source.h); the
  // whole text is read only when the pieces give up.
  bool pieces_tried = false;
  if (S_ISREG(st.st_mode) && hint >= kStreamFromBytes && which != NativeParser::kReferenceOnly) {
    std::string why;
    try {
      Attempt a = parse_in_pieces(FileSource(fd, hint), which, &why, {});
      if (a.decided) {
        if (!a.doc) return refuse(why);
        return std::move(a.doc);
      }
    } catch (const std::exception& e) {
      return refuse(std::string("cannot read the document: ") + e.what());
    }
    pieces_tried = true;
  }
  FileText text(fd, hint);
  if (text.read_errno) return refuse(std::string("cannot read: ") + std::strerror(text.read_errno));
  if (text.too_large) return refuse("is more than " + std::to_string(kMaxNativeBytes) + " bytes; refusing to read it");
  std::string why;
  auto doc = parse_document(text.bytes.get(), text.size, text.capacity, which, &why, [&] { text.bytes.reset(); },
                            pieces_tried && text.size == hint);
  if (!doc) return refuse(why);
  return doc;
}

}  // namespace kintsugi::io
