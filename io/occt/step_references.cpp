#include "io/occt/step_references.h"

#include <cctype>
#include <unordered_set>
#include <vector>

namespace kintsugi::io {

namespace {

bool digit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

// "#0012" and "#12" are the same entity.
std::string_view id_digits(std::string_view s) {
  while (s.size() > 1 && s[0] == '0') s.remove_prefix(1);
  return s;
}

}  // namespace

std::string step_dangling_reference(std::string_view text) {
  std::unordered_set<std::string_view> defined;
  struct Ref {
    std::string_view id, in;
  };
  std::vector<Ref> refs;
  std::size_t pos = text.find("DATA;");
  bool at_statement_start = true;  // after "DATA;" or a ';'
  std::string_view current;        // the instance being read
  while (pos != std::string_view::npos && pos < text.size()) {
    char c = text[pos];
    if (c == '\'') {  // a string ('' inside is an escaped quote: two toggles)
      std::size_t end = text.find('\'', pos + 1);
      pos = end == std::string_view::npos ? end : end + 1;
      continue;
    }
    if (c == '/' && pos + 1 < text.size() && text[pos + 1] == '*') {
      std::size_t end = text.find("*/", pos + 2);
      pos = end == std::string_view::npos ? end : end + 2;
      continue;
    }
    if (c == ';') {
      at_statement_start = true;
      ++pos;
      continue;
    }
    if (c == '#') {
      std::size_t e = pos + 1;
      while (e < text.size() && digit(text[e])) ++e;
      std::string_view id = id_digits(text.substr(pos + 1, e - pos - 1));
      if (!id.empty()) {
        std::size_t after = e;
        while (after < text.size() && std::isspace(static_cast<unsigned char>(text[after]))) ++after;
        if (at_statement_start && after < text.size() && text[after] == '=') {
          defined.insert(id);
          current = id;
        } else {
          refs.push_back({id, current});
        }
      }
      at_statement_start = false;
      pos = e;
      continue;
    }
    if (!std::isspace(static_cast<unsigned char>(c))) at_statement_start = false;
    ++pos;
  }
  for (const Ref& r : refs)
    if (!defined.count(r.id))
      return "entity #" + std::string(r.in) + " refers to #" + std::string(r.id) + ", which the file does not define";
  return "";
}

}  // namespace kintsugi::io
