// The native JSON reader (spec/file-format.md): a bounded parser and a validating reader
// that turns the document into a BodyDescription and lets assemble() check the topology.
// The writer is io/native_json_writer.cpp, atomic file writes io/atomic_file.cpp.
#include "io/native_json.h"

#include "invariants/assemble.h"
#include "geometry/freeform.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
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
std::string at(const std::string& ptr, std::string_view key) { return ptr + "/" + escape_token(key); }
std::string at(const std::string& ptr, std::size_t index) { return ptr + "/" + std::to_string(index); }

// "<pointer>: <message>", or the message alone for the whole document.
std::string located(const std::string& ptr, const std::string& message) {
  return ptr.empty() ? message : ptr + ": " + message;
}

// Shortest text that reads back as the same double (what the writer writes, too).
std::string number_text(double d) { return json(d).dump(); }

// What a value is, for "expected X, found Y" messages: short values verbatim.
std::string describe_value(const json& j) {
  switch (j.type()) {
    case json::value_t::object: return "an object";
    case json::value_t::array: return "an array";
    case json::value_t::string: {
      const auto& s = j.get_ref<const std::string&>();
      if (s.size() > 40) return "a string";
      return "the string " + j.dump(-1, ' ', false, json::error_handler_t::replace);
    }
    default: return j.dump();
  }
}

// ---- bounded parsing ----------------------------------------------------------------
//
// nlohmann's parser is iterative, but the document it builds is destroyed and copied
// recursively, and a 100 000-deep `[[[[...` would overflow the stack there. So we build
// the document ourselves from SAX events, refusing nesting beyond kMaxNativeDepth before
// it exists. The same events let us name the place of a syntax error, refuse numbers that
// overflow a double (which the lexer turns into ±inf), and refuse duplicate keys (which
// nlohmann would silently resolve to the last one).
//
// The element arrays of the top-level object ("vertices", ... "shells": by far the bulk
// of a document) are not built: each of their elements is built alone, handed to the
// ElementSink as soon as it is complete, and dropped, so the document in memory is the
// top level, `meta`, and one element. (A whole document as nlohmann values takes about
// ten times the bytes of its text.)

// The element arrays, in the order the reader checks them.
enum ElementKind { kVertices, kEdges, kLoops, kFaces, kShells, kElementKinds };
const char* const kElementKeys[kElementKinds] = {"vertices", "edges", "loops", "faces", "shells"};

class ElementSink {
 public:
  virtual ~ElementSink() = default;
  // Element `index` of the top-level array `kind`, complete.
  virtual void element(ElementKind kind, std::size_t index, const json& value) = 0;
};

class BoundedDocumentBuilder {
 public:
  json root;
  std::string error;

  explicit BoundedDocumentBuilder(ElementSink* sink) : sink_(sink) {}

  bool null() { return add(json(nullptr)); }
  bool boolean(bool v) { return add(json(v)); }
  bool number_integer(json::number_integer_t v) { return add(json(v)); }
  bool number_unsigned(json::number_unsigned_t v) { return add(json(v)); }
  bool number_float(json::number_float_t v, const json::string_t& text) {
    if (!std::isfinite(v)) return fail("number " + text + " is out of the range of a double");
    return add(json(v));
  }
  bool string(json::string_t& v) { return add(json(std::move(v))); }
  bool binary(json::binary_t&) { return fail("binary values are not part of JSON"); }
  bool start_object(std::size_t) { return open(json::object()); }
  bool start_array(std::size_t) { return open(json::array()); }
  bool end_object() { return close(); }
  bool end_array() { return close(); }
  bool key(json::string_t& k) {
    Level& top = stack_.back();
    if (top.node->contains(k)) {
      top.key = std::move(k);
      top.has_key = true;
      return fail("key appears twice in the same object");
    }
    top.key = std::move(k);
    top.has_key = true;
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
    json* node;
    std::string key;         // objects: the key whose value comes next
    bool has_key = false;
    std::string open_child;  // the token of the child container being built, if any
    std::size_t count = 0;   // arrays: the children so far (a streamed array keeps none)
    int streams = -1;        // an element array of the top level: its ElementKind
    int delivers = -1;       // an element of such an array: its kind, handed over when closed
    std::size_t index = 0;   // ... and its index
  };
  std::vector<Level> stack_;
  ElementSink* sink_;
  json element_;  // the element of an element array being built

  // Pointer of the value being parsed now.
  std::string here() const {
    std::string p;
    for (std::size_t i = 0; i < stack_.size(); ++i) {
      const Level& l = stack_[i];
      if (i + 1 < stack_.size())
        p += "/" + l.open_child;
      else if (l.node->is_array())
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
  // Adds a value where the parser is; returns where it went (for containers) and which
  // element array it is the element of (-1: none) with its index.
  json* insert(json v, int* delivers, std::size_t* index) {
    *delivers = -1;
    if (stack_.empty()) {
      root = std::move(v);
      return &root;
    }
    Level& top = stack_.back();
    if (top.node->is_array()) {
      const std::size_t i = top.count++;
      if (top.streams >= 0) {
        *delivers = top.streams;
        *index = i;
        element_ = std::move(v);
        return &element_;
      }
      top.node->push_back(std::move(v));
      return &top.node->back();
    }
    top.has_key = false;
    json& slot = (*top.node)[top.key];
    slot = std::move(v);
    return &slot;
  }
  bool add(json v) {
    int delivers;
    std::size_t index;
    insert(std::move(v), &delivers, &index);
    if (delivers >= 0) deliver(delivers, index);
    return true;
  }
  void deliver(int kind, std::size_t index) {
    sink_->element(ElementKind(kind), index, element_);
    element_ = json();
  }
  bool open(json container) {
    if (stack_.size() >= kMaxNativeDepth)
      return fail("nesting is deeper than " + std::to_string(kMaxNativeDepth) + " levels");
    int streams = -1;
    if (!stack_.empty()) {
      Level& parent = stack_.back();
      parent.open_child = parent.node->is_array() ? std::to_string(parent.count) : escape_token(parent.key);
      // An array that is a member of the top-level object under an element key.
      if (sink_ && stack_.size() == 1 && parent.node->is_object() && container.is_array())
        for (int k = 0; k < kElementKinds; ++k)
          if (parent.key == kElementKeys[k]) streams = k;
    }
    Level level{nullptr, {}, false, {}, 0, streams, -1, 0};
    level.node = insert(std::move(container), &level.delivers, &level.index);
    // Children are complete before their next sibling is added, so `node` stays valid
    // while it is on the stack.
    stack_.push_back(std::move(level));
    return true;
  }
  bool close() {
    const int delivers = stack_.back().delivers;
    const std::size_t index = stack_.back().index;
    stack_.pop_back();
    if (delivers >= 0) deliver(delivers, index);
    return true;
  }
};

// ---- validating reader --------------------------------------------------------------

constexpr std::uint64_t kMaxId = 0xFFFFFFFEu;        // 0xFFFFFFFF is the invalid handle
constexpr std::uint64_t kMaxEdgeId = 0x7FFFFFFEu;    // its half-edges must be ids too
constexpr double kUnitTolerance = 1e-9;              // unit length and perpendicularity

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

  void element(ElementKind kind, std::size_t i, const json& e) override {
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

  // The document without its elements (the element arrays are there, empty).
  std::optional<NativeDocument> finish(const json& doc) {
    NativeDocument out;
    if (!top_level(doc, &out) || !settle(kVertices, vertex_ids_, d_.vertices) || !settle(kEdges, edge_ids_, d_.edges) ||
        !settle(kLoops, loop_ids_, d_.loops) || !settle(kFaces, face_ids_, d_.faces) ||
        !settle(kShells, shell_ids_, d_.shells) || !references(d_))
      return refuse();
    AssembleError why;
    std::optional<Body> body = assemble(d_, &why);
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
  bool object_with_keys(const json& j, const std::string& ptr, std::initializer_list<std::string_view> allowed,
                        const std::string& what) {
    if (!j.is_object()) return fail(ptr, "expected " + what + " (an object), found " + describe_value(j));
    std::vector<std::string> unknown;
    for (const auto& item : j.items()) {
      bool known = false;
      for (std::string_view a : allowed) known = known || item.key() == a;
      if (!known) unknown.push_back(item.key());
    }
    if (unknown.empty()) return true;
    std::string names, expected;
    for (const auto& u : unknown) names += (names.empty() ? "\"" : ", \"") + u + "\"";
    for (std::string_view a : allowed) expected += (expected.empty() ? "" : ", ") + std::string(a);
    return fail(at(ptr, unknown.front()),
                std::string(unknown.size() == 1 ? "unknown key " : "unknown keys ") + names + " in " + what +
                    " (it has " + expected + ")");
  }
  // The member `key` of object `obj`, or nullptr after reporting it missing.
  const json* required(const json& obj, const std::string& ptr, const char* key) {
    auto it = obj.find(key);
    if (it == obj.end()) {
      fail(at(ptr, key), "is missing");
      return nullptr;
    }
    return &*it;
  }
  // The member `key`, or nullptr when it is absent or null (an optional reference).
  static const json* optional_member(const json& obj, const char* key) {
    auto it = obj.find(key);
    return it == obj.end() || it->is_null() ? nullptr : &*it;
  }

  bool number(const json& j, const std::string& ptr, double* out) {
    if (!j.is_number()) return fail(ptr, "expected a number, found " + describe_value(j));
    *out = j.get<double>();
    // The parser refuses overflow; this guards documents built any other way.
    if (!std::isfinite(*out)) return fail(ptr, "expected a finite number");
    return true;
  }
  bool positive(const json& j, const std::string& ptr, double* out) {
    if (!number(j, ptr, out)) return false;
    if (!(*out > 0)) return fail(ptr, "must be positive, found " + number_text(*out));
    return true;
  }
  bool integer(const json& j, const std::string& ptr, std::uint64_t max, std::uint64_t* out) {
    if (j.is_number_unsigned()) {
      *out = j.get<std::uint64_t>();
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
  bool id(const json& j, const std::string& ptr, std::uint64_t max, std::uint32_t* out) {
    std::uint64_t v;
    if (!integer(j, ptr, max, &v)) return false;
    *out = std::uint32_t(v);
    return true;
  }
  bool vec3(const json& j, const std::string& ptr, geo::Vec3* out) {
    if (!j.is_array() || j.size() != 3)
      return fail(ptr, "expected [x, y, z] (an array of 3 numbers), found " +
                           (j.is_array() ? "an array of " + std::to_string(j.size()) : describe_value(j)));
    for (std::size_t i = 0; i < 3; ++i)
      if (!number(j[i], at(ptr, i), &(*out)[Eigen::Index(i)])) return false;
    return true;
  }
  bool unit_vec3(const json& j, const std::string& ptr, geo::Vec3* out) {
    if (!vec3(j, ptr, out)) return false;
    double length = out->norm();
    if (!(std::abs(length - 1.0) <= kUnitTolerance))
      return fail(ptr, "is not a unit vector (its length is " + number_text(length) + ")");
    return true;
  }
  bool frame(const json& j, const std::string& ptr, geo::Frame* out) {
    if (!object_with_keys(j, ptr, {"origin", "x", "z"}, "a frame")) return false;
    const json *o = nullptr, *x = nullptr, *z = nullptr;
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
  bool field(const json& obj, const std::string& ptr, const char* key, double* out, Check check) {
    const json* v = required(obj, ptr, key);
    return v && (this->*check)(*v, at(ptr, key), out);
  }
  // The "type" member of a geometry object.
  bool geometry_type(const json& j, const std::string& ptr, const char* what, std::string* type) {
    if (!j.is_object()) return fail(ptr, std::string("expected ") + what + " (an object or null), found " + describe_value(j));
    const json* t = required(j, ptr, "type");
    if (!t) return false;
    if (!t->is_string()) return fail(at(ptr, "type"), "expected a string, found " + describe_value(*t));
    *type = t->get<std::string>();
    return true;
  }

  // -- free-form geometry (spec/file-format.md, "Free-form geometry") --

  bool count_field(const json& obj, const std::string& ptr, const char* key, int lo, int* out) {
    const json* v = required(obj, ptr, key);
    std::uint64_t n = 0;
    if (!v || !integer(*v, at(ptr, key), 1u << 24, &n)) return false;
    if (int(n) < lo) return fail(at(ptr, key), "must be at least " + std::to_string(lo) + ", found " + std::to_string(n));
    *out = int(n);
    return true;
  }
  bool flag_field(const json& obj, const std::string& ptr, const char* key, bool* out) {
    const json* v = required(obj, ptr, key);
    if (!v) return false;
    if (!v->is_boolean()) return fail(at(ptr, key), "expected true or false, found " + describe_value(*v));
    *out = v->get<bool>();
    return true;
  }
  bool number_list(const json& obj, const std::string& ptr, const char* key, std::vector<double>* out) {
    const json* v = required(obj, ptr, key);
    if (!v) return false;
    const std::string p = at(ptr, key);
    if (!v->is_array()) return fail(p, "expected an array of numbers, found " + describe_value(*v));
    out->resize(v->size());
    for (std::size_t i = 0; i < v->size(); ++i)
      if (!number((*v)[i], at(p, i), &(*out)[i])) return false;
    return true;
  }
  bool integer_list(const json& obj, const std::string& ptr, const char* key, std::vector<int>* out) {
    const json* v = required(obj, ptr, key);
    if (!v) return false;
    const std::string p = at(ptr, key);
    if (!v->is_array()) return fail(p, "expected an array of integers, found " + describe_value(*v));
    out->resize(v->size());
    for (std::size_t i = 0; i < v->size(); ++i) {
      std::uint64_t n = 0;
      if (!integer((*v)[i], at(p, i), 1u << 24, &n)) return false;
      if (n == 0) return fail(at(p, i), "a multiplicity must be at least 1");
      (*out)[i] = int(n);
    }
    return true;
  }
  bool point_list(const json& obj, const std::string& ptr, const char* key, std::vector<geo::Vec3>* out) {
    const json* v = required(obj, ptr, key);
    if (!v) return false;
    const std::string p = at(ptr, key);
    if (!v->is_array()) return fail(p, "expected an array of points, found " + describe_value(*v));
    out->resize(v->size());
    for (std::size_t i = 0; i < v->size(); ++i)
      if (!vec3((*v)[i], at(p, i), &(*out)[i])) return false;
    return true;
  }
  // Knots strictly increasing, multiplicities summing to what the degree and pole count
  // need (open: poles + degree + 1; periodic: poles, the last knot's counted once).
  bool knot_vector(const std::string& ptr, const char* knots_key, const std::vector<double>& knots,
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
  bool weights_ok(const std::string& ptr, const std::vector<double>& w, std::size_t poles) {
    if (w.empty()) return true;
    if (w.size() != poles)
      return fail(at(ptr, "weights"), "expected one weight per pole (" + std::to_string(poles) + "), found " + std::to_string(w.size()));
    for (std::size_t i = 0; i < w.size(); ++i)
      if (!(w[i] > 0)) return fail(at(at(ptr, "weights"), i), "weights must be positive");
    return true;
  }
  bool freeform_available(const std::string& ptr) {
    if (std::string why = geo::freeform_unavailable(); !why.empty()) return fail(ptr, why);
    return true;
  }
  bool bspline_curve(const json& j, const std::string& ptr, geo::BSplineCurve* c) {
    if (!object_with_keys(j, ptr, {"type", "degree", "poles", "weights", "knots", "multiplicities", "periodic"},
                          "a bspline_curve"))
      return false;
    if (j.contains("type") && j["type"] != "bspline_curve") return fail(at(ptr, "type"), "expected \"bspline_curve\"");
    if (!count_field(j, ptr, "degree", 1, &c->degree) || !point_list(j, ptr, "poles", &c->poles) ||
        !number_list(j, ptr, "knots", &c->knots) || !integer_list(j, ptr, "multiplicities", &c->multiplicities) ||
        !flag_field(j, ptr, "periodic", &c->periodic))
      return false;
    if (j.contains("weights") && !number_list(j, ptr, "weights", &c->weights)) return false;
    if (c->poles.size() < 2) return fail(at(ptr, "poles"), "expected at least 2 poles");
    return weights_ok(ptr, c->weights, c->poles.size()) &&
           knot_vector(ptr, "knots", c->knots, c->multiplicities, c->degree, c->poles.size(), c->periodic);
  }
  bool bspline_surface(const json& j, const std::string& ptr, geo::BSplineSurface* b) {
    if (!object_with_keys(j, ptr,
                          {"type", "u_degree", "v_degree", "u_count", "v_count", "poles", "weights", "u_knots", "v_knots",
                           "u_multiplicities", "v_multiplicities", "u_periodic", "v_periodic"},
                          "a bspline_surface"))
      return false;
    if (j.contains("type") && j["type"] != "bspline_surface") return fail(at(ptr, "type"), "expected \"bspline_surface\"");
    if (!count_field(j, ptr, "u_degree", 1, &b->u_degree) || !count_field(j, ptr, "v_degree", 1, &b->v_degree) ||
        !count_field(j, ptr, "u_count", 2, &b->u_count) || !count_field(j, ptr, "v_count", 2, &b->v_count) ||
        !point_list(j, ptr, "poles", &b->poles) || !number_list(j, ptr, "u_knots", &b->u_knots) ||
        !number_list(j, ptr, "v_knots", &b->v_knots) || !integer_list(j, ptr, "u_multiplicities", &b->u_multiplicities) ||
        !integer_list(j, ptr, "v_multiplicities", &b->v_multiplicities) ||
        !flag_field(j, ptr, "u_periodic", &b->u_periodic) || !flag_field(j, ptr, "v_periodic", &b->v_periodic))
      return false;
    if (j.contains("weights") && !number_list(j, ptr, "weights", &b->weights)) return false;
    const std::size_t n = std::size_t(b->u_count) * std::size_t(b->v_count);
    if (b->poles.size() != n)
      return fail(at(ptr, "poles"), "expected u_count x v_count = " + std::to_string(n) + " poles, found " + std::to_string(b->poles.size()));
    return weights_ok(ptr, b->weights, n) &&
           knot_vector(ptr, "u_knots", b->u_knots, b->u_multiplicities, b->u_degree, std::size_t(b->u_count), b->u_periodic) &&
           knot_vector(ptr, "v_knots", b->v_knots, b->v_multiplicities, b->v_degree, std::size_t(b->v_count), b->v_periodic);
  }
  // The backend's own verdict on data that passed the structural checks.
  bool freeform_valid(const std::string& ptr, const geo::Surface& s) {
    std::string why = geo::require_freeform().surface_problem(s);
    return why.empty() || fail(ptr, why);
  }
  bool freeform_valid(const std::string& ptr, const geo::Curve& c) {
    std::string why = geo::require_freeform().curve_problem(c);
    return why.empty() || fail(ptr, why);
  }

  // -- geometry --

  bool surface(const json* j, const std::string& ptr, geo::Surface* out) {
    if (!j || j->is_null()) {
      *out = std::monostate{};
      return true;
    }
    std::string type;
    if (!geometry_type(*j, ptr, "a surface", &type)) return false;
    const std::string what = "a " + type + " surface";
    auto with_frame = [&](geo::Frame* f) {
      const json* fr = required(*j, ptr, "frame");
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
      const json *basis = nullptr, *o = nullptr, *a = nullptr;
      if (!freeform_available(ptr) || !object_with_keys(*j, ptr, {"type", "basis", "origin", "axis"}, what) ||
          !(basis = required(*j, ptr, "basis")) || !bspline_curve(*basis, at(ptr, "basis"), &r.basis) ||
          !(o = required(*j, ptr, "origin")) || !vec3(*o, at(ptr, "origin"), &r.origin) ||
          !(a = required(*j, ptr, "axis")) || !unit_vec3(*a, at(ptr, "axis"), &r.axis))
        return false;
      *out = std::move(r);
      return freeform_valid(ptr, *out);
    } else if (type == "extrusion_surface") {
      geo::ExtrusionSurface e;
      const json *basis = nullptr, *d = nullptr;
      if (!freeform_available(ptr) || !object_with_keys(*j, ptr, {"type", "basis", "direction"}, what) ||
          !(basis = required(*j, ptr, "basis")) || !bspline_curve(*basis, at(ptr, "basis"), &e.basis) ||
          !(d = required(*j, ptr, "direction")) || !unit_vec3(*d, at(ptr, "direction"), &e.direction))
        return false;
      *out = std::move(e);
      return freeform_valid(ptr, *out);
    } else if (type == "offset_surface") {
      geo::OffsetSurface o;
      const json* basis = nullptr;
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

  bool curve(const json* j, const std::string& ptr, geo::Curve* out) {
    if (!j || j->is_null()) {
      *out = std::monostate{};
      return true;
    }
    std::string type;
    if (!geometry_type(*j, ptr, "a curve", &type)) return false;
    const std::string what = "a " + type + " curve";
    if (type == "line") {
      geo::Line c;
      const json *o = nullptr, *d = nullptr;
      if (!object_with_keys(*j, ptr, {"type", "origin", "direction"}, what) || !(o = required(*j, ptr, "origin")) ||
          !(d = required(*j, ptr, "direction")) || !vec3(*o, at(ptr, "origin"), &c.origin) ||
          !unit_vec3(*d, at(ptr, "direction"), &c.direction))
        return false;
      *out = c;
    } else if (type == "circle") {
      geo::Circle c;
      const json *f = nullptr;
      if (!object_with_keys(*j, ptr, {"type", "frame", "radius"}, what) || !(f = required(*j, ptr, "frame")) ||
          !frame(*f, at(ptr, "frame"), &c.frame) || !field(*j, ptr, "radius", &c.radius, &DocumentReader::positive))
        return false;
      *out = c;
    } else if (type == "ellipse") {
      geo::Ellipse c;
      const json *f = nullptr;
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
      const json *pts = nullptr;
      if (!object_with_keys(*j, ptr, {"type", "points", "chordal_error"}, what) ||
          !(pts = required(*j, ptr, "points")) ||
          !field(*j, ptr, "chordal_error", &c.chordal_error, &DocumentReader::number))
        return false;
      if (!(c.chordal_error >= 0))
        return fail(at(ptr, "chordal_error"), "must not be negative, found " + number_text(c.chordal_error));
      const std::string pp = at(ptr, "points");
      if (!pts->is_array() || pts->size() < 2)
        return fail(pp, "expected an array of at least 2 points, found " +
                            (pts->is_array() ? "an array of " + std::to_string(pts->size()) : describe_value(*pts)));
      c.points.resize(pts->size());
      for (std::size_t i = 0; i < pts->size(); ++i)
        if (!vec3((*pts)[i], at(pp, i), &c.points[i])) return false;
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

  bool top_level(const json& doc, NativeDocument* out) {
    if (!object_with_keys(doc, "", {"format", "version", "units", "vertices", "edges", "loops", "faces", "shells", "meta"},
                          "a kintsugi-brep document"))
      return false;
    const json *format = nullptr, *version = nullptr, *units = nullptr;
    if (!(format = required(doc, "", "format"))) return false;
    if (*format != "kintsugi-brep") return fail("/format", "expected \"kintsugi-brep\", found " + describe_value(*format));
    if (!(version = required(doc, "", "version"))) return false;
    std::uint64_t v;
    if (!integer(*version, "/version", kMaxId, &v)) return false;
    if (v != 1) return fail("/version", "unsupported version " + std::to_string(v) + " (this reader reads version 1)");
    if (!(units = required(doc, "", "units"))) return false;
    bool known = false;
    for (const char* u : kUnits) known = known || *units == u;
    if (!known)
      return fail("/units", "expected one of \"nm\", \"um\", \"mm\", \"cm\", \"m\", \"in\", \"ft\", found " +
                                describe_value(*units));
    out->units = units->get<std::string>();
    for (const char* key : {"vertices", "edges", "loops", "faces", "shells"}) {
      const json* a = required(doc, "", key);
      if (!a) return false;
      if (!a->is_array()) return fail(at("", key), "expected an array, found " + describe_value(*a));
    }
    if (auto it = doc.find("meta"); it != doc.end()) {
      if (!meta(*it)) return false;
      out->meta = *it;
    }
    return true;
  }

  // meta is free-form; the two keys kintsugi itself reads are checked.
  bool meta(const json& m) {
    if (!m.is_object()) return fail("/meta", "expected an object, found " + describe_value(m));
    if (auto t = m.find("tolerance"); t != m.end()) {
      double tol;
      if (!positive(*t, "/meta/tolerance", &tol)) return false;
    }
    if (auto d = m.find("defects"); d != m.end()) {
      if (!d->is_array()) return fail("/meta/defects", "expected an array, found " + describe_value(*d));
      for (std::size_t i = 0; i < d->size(); ++i) {
        const json& defect = (*d)[i];
        const std::string p = at("/meta/defects", i);
        if (!defect.is_object()) return fail(p, "expected a defect (an object), found " + describe_value(defect));
        const json *type = nullptr, *elements = nullptr, *size = nullptr;
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
      return fail(at(at("", t.plural), i) + "/id", std::string(t.kind) + " id " + std::to_string(id) +
                                                      " is too large for " + std::to_string(count) + " " + t.plural +
                                                      " (ids must be below " + std::to_string(limit) + ")");
    if (std::size_t seen = t.find(id); seen != std::string::npos)
      return fail(at(at("", t.plural), i) + "/id", std::string(t.kind) + " id " + std::to_string(id) +
                                                      " is used twice (also at " + at(at("", t.plural), seen) + ")");
    t.slot[id] = std::uint32_t(i + 1);
    return true;
  }

  // One element each; ids are recorded by settle() once the array's length is known.

  bool vertex(const json& v, std::size_t i, VertexDesc* out) {
    const std::string p = at("/vertices", i);
    const json *id_j = nullptr, *pt = nullptr;
    return object_with_keys(v, p, {"id", "point"}, "a vertex") && (id_j = required(v, p, "id")) &&
           (pt = required(v, p, "point")) && id(*id_j, at(p, "id"), kMaxId, &out->id) &&
           vec3(*pt, at(p, "point"), &out->point);
  }

  bool edge(const json& e, std::size_t i, EdgeDesc* out) {
    const std::string p = at("/edges", i);
    const json *id_j = nullptr, *he = nullptr;
    if (!object_with_keys(e, p, {"id", "he", "curve"}, "an edge") || !(id_j = required(e, p, "id")) ||
        !(he = required(e, p, "he")) || !id(*id_j, at(p, "id"), kMaxEdgeId, &out->id))
      return false;
    const std::string hp = at(p, "he");
    if (!he->is_array() || he->size() != 2)
      return fail(hp, "expected the edge's two half-edges (an array of 2 objects), found " +
                          (he->is_array() ? "an array of " + std::to_string(he->size()) : describe_value(*he)));
    for (std::size_t side = 0; side < 2; ++side) {
      const json& h = (*he)[side];
      const std::string sp = at(hp, side);
      const json *o = nullptr, *n = nullptr, *l = nullptr;
      if (!object_with_keys(h, sp, {"origin", "next", "loop"}, "a half-edge") || !(o = required(h, sp, "origin")) ||
          !(n = required(h, sp, "next")) || !(l = required(h, sp, "loop")) ||
          !id(*o, at(sp, "origin"), kMaxId, &out->he[side].origin) ||
          !id(*n, at(sp, "next"), kMaxId, &out->he[side].next) || !id(*l, at(sp, "loop"), kMaxId, &out->he[side].loop))
        return false;
    }
    return curve(optional_member(e, "curve"), at(p, "curve"), &out->curve);
  }

  bool loop(const json& l, std::size_t i, LoopDesc* out) {
    const std::string p = at("/loops", i);
    const json *id_j = nullptr;
    if (!object_with_keys(l, p, {"id", "face", "first", "lone"}, "a loop") || !(id_j = required(l, p, "id")) ||
        !id(*id_j, at(p, "id"), kMaxId, &out->id))
      return false;
    std::uint32_t v;
    if (const json* f = optional_member(l, "face")) {
      if (!id(*f, at(p, "face"), kMaxId, &v)) return false;
      out->face = v;
    }
    const json* first = optional_member(l, "first");
    const json* lone = optional_member(l, "lone");
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

  bool face(const json& f, std::size_t i, FaceDesc* out) {
    const std::string p = at("/faces", i);
    const json *id_j = nullptr, *shell = nullptr, *ls = nullptr, *sense = nullptr;
    if (!object_with_keys(f, p, {"id", "shell", "loops", "same_sense", "surface"}, "a face") ||
        !(id_j = required(f, p, "id")) || !(shell = required(f, p, "shell")) || !(ls = required(f, p, "loops")) ||
        !(sense = required(f, p, "same_sense")) || !id(*id_j, at(p, "id"), kMaxId, &out->id) ||
        !id(*shell, at(p, "shell"), kMaxId, &out->shell))
      return false;
    const std::string lp = at(p, "loops");
    if (!ls->is_array() || ls->empty())
      return fail(lp, "expected the face's loops, outer first (a non-empty array), found " +
                          (ls->is_array() ? "an empty array" : describe_value(*ls)));
    out->loops.resize(ls->size());
    for (std::size_t k = 0; k < ls->size(); ++k)
      if (!id((*ls)[k], at(lp, k), kMaxId, &out->loops[k])) return false;
    if (!sense->is_boolean()) return fail(at(p, "same_sense"), "expected true or false, found " + describe_value(*sense));
    out->same_sense = sense->get<bool>();
    return surface(optional_member(f, "surface"), at(p, "surface"), &out->surface);
  }

  bool shell(const json& s, std::size_t i, ShellDesc* out) {
    const std::string p = at("/shells", i);
    const json *id_j = nullptr, *genus = nullptr;
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
        auto p = [&](const char* key) { return [=] { return at(at(at(at("/edges", i), "he"), side), key); }; };
        const HalfedgeDesc& h = d.edges[i].he[side];
        if (!refers(vertex_ids_, h.origin, "vertex", p("origin")) || !refers_to_halfedge(h.next, p("next")) ||
            !refers(loop_ids_, h.loop, "loop", p("loop")))
          return false;
      }
    for (std::size_t i = 0; i < d.loops.size(); ++i) {
      auto p = [&](const char* key) { return [=] { return at(at("/loops", i), key); }; };
      const LoopDesc& l = d.loops[i];
      if (l.face && !refers(face_ids_, *l.face, "face", p("face"))) return false;
      if (l.first && !refers_to_halfedge(*l.first, p("first"))) return false;
      if (l.lone && !refers(vertex_ids_, *l.lone, "vertex", p("lone"))) return false;
    }
    for (std::size_t i = 0; i < d.faces.size(); ++i) {
      const FaceDesc& f = d.faces[i];
      if (!refers(shell_ids_, f.shell, "shell", [&] { return at(at("/faces", i), "shell"); })) return false;
      for (std::size_t k = 0; k < f.loops.size(); ++k) {
        auto lp = [&] { return at(at(at("/faces", i), "loops"), k); };
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
      return i == std::string::npos ? std::string() : at(at("", t.plural), i);
    };
    const std::pair<const char*, const IdTable*> words[] = {{"vertex ", &vertex_ids_}, {"edge ", &edge_ids_},
                                                            {"loop ", &loop_ids_},     {"face ", &face_ids_},
                                                            {"shell ", &shell_ids_}};
    std::uint64_t n;
    for (auto [word, table] : words) {
      std::size_t len = std::strlen(word);
      if (element.rfind(word, 0) != 0) continue;
      std::size_t end = number_after(len, &n);
      if (end == std::string::npos) return "";
      std::string p = place(*table, n);
      std::uint64_t side;
      if (table == &edge_ids_ && !p.empty() && element.compare(end, 11, " half-edge ") == 0 &&
          number_after(end + 11, &side) != std::string::npos && side < 2)
        p = at(at(p, "he"), std::size_t(side));
      return p;
    }
    if (element.size() < 2 || number_after(1, &n) != element.size()) return "";
    switch (element[0]) {
      case 'v': return place(vertex_ids_, n);
      case 'e': return place(edge_ids_, n);
      case 'h': {
        std::string p = place(edge_ids_, n >> 1);
        return p.empty() ? p : at(at(p, "he"), std::size_t(n & 1));
      }
      case 'l': return place(loop_ids_, n);
      case 'f': return place(face_ids_, n);
      case 's': return place(shell_ids_, n);
      default: return "";
    }
  }
};

}  // namespace

namespace {

// The whole reader over characters [first, last).
template <class Iterator>
std::optional<NativeDocument> parse_document(Iterator first, Iterator last, std::string* error) {
  try {
    DocumentReader reader(error);
    BoundedDocumentBuilder builder(&reader);
    if (!json::sax_parse(std::move(first), std::move(last), &builder)) {
      if (error) *error = builder.error.empty() ? "not valid JSON" : builder.error;
      return std::nullopt;
    }
    return reader.finish(builder.root);
  } catch (const std::exception& e) {
    // Nothing above throws on bad input; this is for running out of memory.
    if (error) *error = std::string("cannot read the document: ") + e.what();
    return std::nullopt;
  }
}

// A file's bytes, read in 64 KiB chunks as the parser asks for them, so the text is never
// in memory as a whole. A read error or more than kMaxNativeBytes ends the input as if
// the file ended there, and is remembered: the caller reports it instead of whatever the
// parser made of the truncated text.
class FileSource {
 public:
  explicit FileSource(int fd) : fd_(fd) {}

  bool more() { return pos_ < len_ || refill(); }
  char get() const { return buf_[pos_]; }
  void next() { ++pos_; }
  // Reads what is left (to find whether the file goes past the limit, or cannot be read).
  void drain() {
    while (refill()) pos_ = len_;
  }
  int read_errno() const { return read_errno_; }
  bool too_large() const { return too_large_; }

  // The input iterator nlohmann's parser reads through (it uses only !=, * and ++).
  struct Iterator {
    using iterator_category = std::input_iterator_tag;
    using value_type = char;
    using difference_type = std::ptrdiff_t;
    using pointer = const char*;
    using reference = char;
    FileSource* source;  // nullptr: the end
    char operator*() const { return source->get(); }
    Iterator& operator++() {
      source->next();
      return *this;
    }
    bool operator==(const Iterator& other) const { return at_end() == other.at_end(); }
    bool operator!=(const Iterator& other) const { return !(*this == other); }
    bool at_end() const { return !source || !source->more(); }
  };

 private:
  int fd_;
  std::array<char, 1 << 16> buf_;
  std::size_t pos_ = 0, len_ = 0;
  std::uint64_t total_ = 0;
  bool ended_ = false;
  int read_errno_ = 0;
  bool too_large_ = false;

  bool refill() {
    pos_ = len_ = 0;
    while (!ended_) {
      ssize_t n = ::read(fd_, buf_.data(), buf_.size());
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) read_errno_ = errno;
      if (n > 0 && total_ + std::uint64_t(n) > kMaxNativeBytes) too_large_ = true;
      if (n <= 0 || too_large_) {
        ended_ = true;
        break;
      }
      total_ += std::uint64_t(n);
      len_ = std::size_t(n);
      return true;
    }
    return false;
  }
};

}  // namespace

std::optional<NativeDocument> read_native(std::string_view text, std::string* error) {
  if (text.size() > kMaxNativeBytes) {
    if (error)
      *error = "document is " + std::to_string(text.size()) + " bytes, more than the limit of " +
               std::to_string(kMaxNativeBytes);
    return std::nullopt;
  }
  return parse_document(text.begin(), text.end(), error);
}

std::optional<NativeDocument> read_native_file(const std::string& path, std::string* error) {
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
  // Parsed as it is read, with the cap checked as it reads, not only from stat: the file
  // may grow, or be a pipe.
  auto source = std::make_unique<FileSource>(fd);
  std::string why;
  auto doc = parse_document(FileSource::Iterator{source.get()}, FileSource::Iterator{nullptr}, &why);
  // A file past the limit or unreadable is refused as such, whatever the parser said.
  if (!doc) source->drain();
  if (source->read_errno()) return refuse(std::string("cannot read: ") + std::strerror(source->read_errno()));
  if (source->too_large())
    return refuse("is more than " + std::to_string(kMaxNativeBytes) + " bytes; refusing to read it");
  if (!doc) return refuse(why);
  return doc;
}

}  // namespace kintsugi::io
