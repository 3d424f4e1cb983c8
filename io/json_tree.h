// A small JSON tree for the native reader: the values of one element (or of the top level
// and `meta`) in a flat array of 24-byte nodes, reused from element to element, so reading
// a million elements allocates nothing once the first has warmed the buffers.
//
// Two parsers fill it (io/native_json_parse.h): simdjson's On-Demand parser, fast, and
// nlohmann's SAX parser, which names the line and column of a syntax error. The reader
// (io/native_json_reader.cpp) checks what they built through JsonView, whichever built it.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <string_view>
#include <unordered_set>
#include <vector>

namespace kintsugi::io {

class JsonTree {
 public:
  enum class Kind : std::uint8_t { kNull, kBool, kInt, kUint, kFloat, kString, kArray, kObject };
  static constexpr std::uint32_t kNone = 0xFFFFFFFFu;

  struct Node {
    Kind kind = Kind::kNull;
    std::uint32_t next = kNone;  // the next member or element of the parent
    union {
      bool b;
      std::int64_t i;   // kInt: negative, or written with a minus sign ("-0")
      std::uint64_t u;  // kUint: written without a minus sign
      double d;
      struct {
        std::uint32_t offset, length;
      } s;  // kString: in chars_
      struct {
        std::uint32_t first, count;
      } c;  // kArray, kObject
    } v{};
    std::uint32_t key_offset = 0, key_length = 0;  // a member of an object: its key, in chars_
  };

  void clear() {
    nodes_.clear();
    chars_.clear();
  }
  bool empty() const { return nodes_.empty(); }
  const Node& node(std::uint32_t i) const { return nodes_[i]; }
  std::string_view chars(std::uint32_t offset, std::uint32_t length) const {
    return std::string_view(chars_).substr(offset, length);
  }

  // Appends a node; returns its index. Strings and keys are copied into the tree.
  std::uint32_t add(Kind kind) {
    nodes_.emplace_back().kind = kind;
    return std::uint32_t(nodes_.size() - 1);
  }
  std::uint32_t add_string(std::string_view s) {
    const std::uint32_t n = add(Kind::kString);
    nodes_[n].v.s = {store(s), std::uint32_t(s.size())};
    return n;
  }
  Node& at(std::uint32_t i) { return nodes_[i]; }
  std::uint32_t store(std::string_view s) {
    const std::uint32_t offset = std::uint32_t(chars_.size());
    chars_.append(s);
    return offset;
  }

 private:
  std::vector<Node> nodes_;
  std::string chars_;
};

class JsonView;

// Builds a JsonTree from a parser's events in document order: open a container, give each
// member its key, add values, close. Refuses a key that appears twice in one object
// (nlohmann's parser would keep the last; simdjson's would keep both). Nesting depth is
// the parser's to bound.
class JsonTreeBuilder {
 public:
  explicit JsonTreeBuilder(JsonTree* tree) : tree_(tree) {}

  // Starts a new tree (the tree is cleared).
  void reset() {
    tree_->clear();
    stack_.clear();
  }
  // The key of the next value in the innermost object; false if that object has it already.
  bool key(std::string_view k);
  // Values: each returns its node's index.
  std::uint32_t null() { return place(tree_->add(JsonTree::Kind::kNull)); }
  std::uint32_t boolean(bool b);
  std::uint32_t integer(std::int64_t i);
  std::uint32_t unsigned_integer(std::uint64_t u);
  std::uint32_t floating(double d);
  std::uint32_t string(std::string_view s) { return place(tree_->add_string(s)); }
  std::uint32_t open_array() { return open(JsonTree::Kind::kArray); }
  std::uint32_t open_object() { return open(JsonTree::Kind::kObject); }
  void close() { stack_.pop_back(); }
  // A copy of `v` (of another tree), as one value; false if an object in it has a key
  // twice (it cannot, when that tree was built by a builder). As deep as `v`.
  bool copy(JsonView v);

 private:
  struct Open {
    std::uint32_t node;
    std::uint32_t last = JsonTree::kNone;
    std::unordered_set<std::string> keys;  // only past kLinearKeys members
  };

  static constexpr std::uint32_t kLinearKeys = 16;

  JsonTree* tree_;
  std::vector<Open> stack_;
  std::uint32_t key_offset_ = 0, key_length_ = 0;

  std::uint32_t open(JsonTree::Kind kind);
  std::uint32_t place(std::uint32_t n);
};

// An object with the members of `a`, then those of `b` (both objects), in `out`: the top
// level of a document read in pieces. False if a key is in both (the whole text has it
// twice).
bool join_objects(JsonView a, JsonView b, JsonTree* out);

// A node of a JsonTree, read-only; a default one is "absent" (a missing member).
class JsonView {
 public:
  JsonView() = default;
  JsonView(const JsonTree* tree, std::uint32_t node) : tree_(tree), node_(node) {}

  explicit operator bool() const { return tree_ != nullptr; }
  // A view reads like the `const json*` it stands for in the reader: `*v`, `v->size()`.
  const JsonView& operator*() const { return *this; }
  const JsonView* operator->() const { return this; }
  JsonTree::Kind kind() const { return n().kind; }
  bool is_null() const { return kind() == JsonTree::Kind::kNull; }
  bool is_boolean() const { return kind() == JsonTree::Kind::kBool; }
  bool is_object() const { return kind() == JsonTree::Kind::kObject; }
  bool is_array() const { return kind() == JsonTree::Kind::kArray; }
  bool is_string() const { return kind() == JsonTree::Kind::kString; }
  bool is_number() const { return is_number_integer() || kind() == JsonTree::Kind::kFloat; }
  bool is_number_integer() const { return kind() == JsonTree::Kind::kInt || kind() == JsonTree::Kind::kUint; }
  bool is_number_unsigned() const { return kind() == JsonTree::Kind::kUint; }
  bool is_number_float() const { return kind() == JsonTree::Kind::kFloat; }

  bool as_bool() const { return n().v.b; }
  std::uint64_t as_unsigned() const { return n().v.u; }
  double as_double() const;
  std::string_view as_string() const { return tree_->chars(n().v.s.offset, n().v.s.length); }
  // Is this the string `s`?
  bool is_string(std::string_view s) const { return is_string() && as_string() == s; }

  // Arrays and objects: the number of elements or members.
  std::size_t size() const { return n().v.c.count; }
  bool empty() const { return size() == 0; }
  // Element i of an array (walks i links: for short arrays).
  JsonView operator[](std::size_t i) const;
  // Member `key` of an object, or an absent view.
  JsonView find(std::string_view key) const;
  // The first child, and the next sibling (absent at the end): for loops over elements.
  JsonView first() const { return link(n().v.c.first); }
  JsonView next() const { return link(n().next); }
  // The key of this member of an object.
  std::string_view key() const { return tree_->chars(n().key_offset, n().key_length); }

  // The value as JSON text (numbers, true/false/null as nlohmann writes them; strings
  // quoted, invalid UTF-8 replaced), and as an nlohmann value (for `meta`).
  std::string dump() const { return to_json().dump(-1, ' ', false, nlohmann::json::error_handler_t::replace); }
  nlohmann::json to_json() const;

 private:
  const JsonTree* tree_ = nullptr;
  std::uint32_t node_ = 0;
  const JsonTree::Node& n() const { return tree_->node(node_); }
  JsonView link(std::uint32_t i) const { return i == JsonTree::kNone ? JsonView() : JsonView(tree_, i); }
};

}  // namespace kintsugi::io
