// JsonTree's builder and view (io/json_tree.h).
#include "io/json_tree.h"

namespace kintsugi::io {

bool JsonTreeBuilder::key(std::string_view k) {
  Open& top = stack_.back();
  const JsonTree::Node& parent = tree_->node(top.node);
  // Few members: compare with each (an element has at most a handful). Many (a free-form
  // `meta`): a hash set, so a hostile object of a million keys stays linear.
  bool seen = false;
  if (parent.v.c.count < kLinearKeys) {
    for (std::uint32_t c = parent.v.c.first; c != JsonTree::kNone && !seen; c = tree_->node(c).next)
      seen = tree_->chars(tree_->node(c).key_offset, tree_->node(c).key_length) == k;
  } else {
    if (top.keys.empty())
      for (std::uint32_t c = parent.v.c.first; c != JsonTree::kNone; c = tree_->node(c).next)
        top.keys.emplace(tree_->chars(tree_->node(c).key_offset, tree_->node(c).key_length));
    seen = !top.keys.emplace(k).second;
  }
  key_offset_ = tree_->store(k);
  key_length_ = std::uint32_t(k.size());
  return !seen;
}

std::uint32_t JsonTreeBuilder::boolean(bool b) {
  const std::uint32_t n = tree_->add(JsonTree::Kind::kBool);
  tree_->at(n).v.b = b;
  return place(n);
}
std::uint32_t JsonTreeBuilder::integer(std::int64_t i) {
  const std::uint32_t n = tree_->add(JsonTree::Kind::kInt);
  tree_->at(n).v.i = i;
  return place(n);
}
std::uint32_t JsonTreeBuilder::unsigned_integer(std::uint64_t u) {
  const std::uint32_t n = tree_->add(JsonTree::Kind::kUint);
  tree_->at(n).v.u = u;
  return place(n);
}
std::uint32_t JsonTreeBuilder::floating(double d) {
  const std::uint32_t n = tree_->add(JsonTree::Kind::kFloat);
  tree_->at(n).v.d = d;
  return place(n);
}

std::uint32_t JsonTreeBuilder::open(JsonTree::Kind kind) {
  const std::uint32_t n = tree_->add(kind);
  tree_->at(n).v.c = {JsonTree::kNone, 0};
  place(n);
  stack_.push_back(Open{n, JsonTree::kNone, {}});
  return n;
}

// Links node n as the next child of the innermost container (with the pending key when
// that is an object); the first node of a tree is its root.
std::uint32_t JsonTreeBuilder::place(std::uint32_t n) {
  if (stack_.empty()) return n;
  Open& top = stack_.back();
  if (tree_->node(top.node).kind == JsonTree::Kind::kObject) {
    tree_->at(n).key_offset = key_offset_;
    tree_->at(n).key_length = key_length_;
  }
  JsonTree::Node& p = tree_->at(top.node);
  if (top.last == JsonTree::kNone)
    p.v.c.first = n;
  else
    tree_->at(top.last).next = n;
  ++p.v.c.count;
  top.last = n;
  return n;
}

bool JsonTreeBuilder::copy(JsonView v) {
  switch (v.kind()) {
    case JsonTree::Kind::kNull: null(); return true;
    case JsonTree::Kind::kBool: boolean(v.as_bool()); return true;
    case JsonTree::Kind::kInt: integer(std::int64_t(v.as_unsigned())); return true;
    case JsonTree::Kind::kUint: unsigned_integer(v.as_unsigned()); return true;
    case JsonTree::Kind::kFloat: floating(v.as_double()); return true;
    case JsonTree::Kind::kString: string(v.as_string()); return true;
    case JsonTree::Kind::kArray:
    case JsonTree::Kind::kObject: {
      const bool object = v.is_object();
      open(v.kind());
      for (JsonView c = v.first(); c; c = c.next())
        if ((object && !key(c.key())) || !copy(c)) return false;
      close();
      return true;
    }
  }
  return false;
}

double JsonView::as_double() const {
  switch (kind()) {
    case JsonTree::Kind::kInt: return double(n().v.i);
    case JsonTree::Kind::kUint: return double(n().v.u);
    default: return n().v.d;
  }
}

bool join_objects(JsonView a, JsonView b, JsonTree* out) {
  JsonTreeBuilder builder(out);
  builder.reset();
  builder.open_object();
  for (JsonView part : {a, b})
    for (JsonView m = part.first(); m; m = m.next())
      if (!builder.key(m.key()) || !builder.copy(m)) return false;
  builder.close();
  return true;
}

JsonView JsonView::operator[](std::size_t i) const {
  JsonView c = first();
  for (; c && i > 0; --i) c = c.next();
  return c;
}

JsonView JsonView::find(std::string_view key) const {
  for (JsonView c = first(); c; c = c.next())
    if (c.key() == key) return c;
  return {};
}

nlohmann::json JsonView::to_json() const {
  using nlohmann::json;
  switch (kind()) {
    case JsonTree::Kind::kNull: return json(nullptr);
    case JsonTree::Kind::kBool: return json(as_bool());
    case JsonTree::Kind::kInt: return json(n().v.i);
    case JsonTree::Kind::kUint: return json(n().v.u);
    case JsonTree::Kind::kFloat: return json(n().v.d);
    case JsonTree::Kind::kString: return json(std::string(as_string()));
    case JsonTree::Kind::kArray: {
      json a = json::array();
      for (JsonView c = first(); c; c = c.next()) a.push_back(c.to_json());
      return a;
    }
    case JsonTree::Kind::kObject: {
      json o = json::object();
      for (JsonView c = first(); c; c = c.next()) o[std::string(c.key())] = c.to_json();
      return o;
    }
  }
  return json();
}

}  // namespace kintsugi::io
