// The native writer as it was before it streamed (commit edac8ce, io/native_json.cpp):
// every element built as an nlohmann::ordered_json and dumped. Slow and memory-hungry,
// but simple enough to trust, so the tests use it as an oracle for the streamed writer:
// same bytes except how numbers are spelled (nlohmann's Grisu2 digits vs std::to_chars'
// shortest ones), and every number the same double.
#include "tests/io/reference_writer.h"

#include <stdexcept>

#include "kernel/assemble.h"

namespace kintsugi::io::reference {

using json = nlohmann::json;
using ojson = nlohmann::ordered_json;

namespace {

ojson vec3_json(const geo::Vec3& p) { return ojson::array({p.x(), p.y(), p.z()}); }
ojson frame_json(const geo::Frame& f) {
  ojson j = ojson::object();
  j["origin"] = vec3_json(f.origin);
  j["x"] = vec3_json(f.x);
  j["z"] = vec3_json(f.z);
  return j;
}

template <class... Fs>
struct Overload : Fs... {
  using Fs::operator()...;
};
// clang before 17 does not deduce aggregate template arguments without a guide.
template <class... Fs>
Overload(Fs...) -> Overload<Fs...>;

ojson surface_json(const geo::Surface& s) {
  return std::visit(
      Overload{[](const std::monostate&) { return ojson(nullptr); },
               [](const geo::Plane& p) { return ojson{{"type", "plane"}, {"frame", frame_json(p.frame)}}; },
               [](const geo::Cylinder& c) {
                 return ojson{{"type", "cylinder"}, {"frame", frame_json(c.frame)}, {"radius", c.radius}};
               },
               [](const geo::Cone& c) {
                 return ojson{{"type", "cone"},
                              {"frame", frame_json(c.frame)},
                              {"radius", c.radius},
                              {"half_angle", c.half_angle}};
               },
               [](const geo::Sphere& c) {
                 return ojson{{"type", "sphere"}, {"frame", frame_json(c.frame)}, {"radius", c.radius}};
               },
               [](const geo::Torus& t) {
                 return ojson{{"type", "torus"},
                              {"frame", frame_json(t.frame)},
                              {"major_radius", t.major_radius},
                              {"minor_radius", t.minor_radius}};
               },
               [](const auto&) -> ojson { throw std::logic_error("reference writer: free-form surfaces are not covered"); }},
      s);
}

ojson curve_json(const geo::Curve& c) {
  return std::visit(
      Overload{[](const std::monostate&) { return ojson(nullptr); },
               [](const geo::Line& l) {
                 return ojson{{"type", "line"}, {"origin", vec3_json(l.origin)}, {"direction", vec3_json(l.direction)}};
               },
               [](const geo::Circle& k) {
                 return ojson{{"type", "circle"}, {"frame", frame_json(k.frame)}, {"radius", k.radius}};
               },
               [](const geo::Ellipse& e) {
                 return ojson{{"type", "ellipse"},
                              {"frame", frame_json(e.frame)},
                              {"major_radius", e.major_radius},
                              {"minor_radius", e.minor_radius}};
               },
               [](const geo::Polyline& p) {
                 ojson pts = ojson::array();
                 for (const auto& q : p.points) pts.push_back(vec3_json(q));
                 return ojson{{"type", "polyline"}, {"points", std::move(pts)}, {"chordal_error", p.chordal_error}};
               },
               [](const geo::BSplineCurve&) -> ojson { throw std::logic_error("reference writer: free-form curves are not covered"); }},
      c);
}

// One element on one line, with a space after ':' and ',' (nlohmann's compact form has
// none, its indented form puts every number on its own line). Element objects hold only
// our own keys and type names, numbers, booleans and null, so no string contains ':' or
// ',' and spacing the compact form is safe.
void dump_inline(const ojson& j, std::string& out) {
  for (char c : j.dump()) {
    out += c;
    if (c == ',' || c == ':') out += ' ';
  }
}

void section(std::string& out, const char* key, const std::vector<ojson>& items) {
  out += "  \"";
  out += key;
  out += "\": [";
  for (std::size_t i = 0; i < items.size(); ++i) {
    out += i ? ",\n    " : "\n    ";
    dump_inline(items[i], out);
  }
  out += items.empty() ? "],\n" : "\n  ],\n";
}

ojson optional_id(const std::optional<std::uint32_t>& v) { return v ? ojson(*v) : ojson(nullptr); }

}  // namespace

std::string write_native(const Body& b, const nlohmann::json& meta, const std::string& units) {
  const BodyDescription d = describe(b);
  std::vector<ojson> vs, es, ls, fs, ss;
  for (const auto& v : d.vertices) vs.push_back(ojson{{"id", v.id}, {"point", vec3_json(v.point)}});
  for (const auto& e : d.edges) {
    ojson he = ojson::array();
    for (const auto& h : e.he) he.push_back(ojson{{"origin", h.origin}, {"next", h.next}, {"loop", h.loop}});
    es.push_back(ojson{{"id", e.id}, {"he", std::move(he)}, {"curve", curve_json(e.curve)}});
  }
  for (const auto& l : d.loops) {
    ojson j{{"id", l.id}, {"face", optional_id(l.face)}};
    if (l.first)
      j["first"] = *l.first;
    else
      j["lone"] = optional_id(l.lone);
    ls.push_back(std::move(j));
  }
  for (const auto& f : d.faces)
    fs.push_back(ojson{{"id", f.id},
                       {"shell", f.shell},
                       {"loops", f.loops},
                       {"same_sense", f.same_sense},
                       {"surface", surface_json(f.surface)}});
  for (const auto& s : d.shells) ss.push_back(ojson{{"id", s.id}, {"genus", s.genus}});

  std::string out = "{\n  \"format\": \"kintsugi-brep\",\n  \"version\": 1,\n  \"units\": ";
  out += json(units).dump(-1, ' ', false, json::error_handler_t::replace) + ",\n";
  section(out, "vertices", vs);
  section(out, "edges", es);
  section(out, "loops", ls);
  section(out, "faces", fs);
  section(out, "shells", ss);
  std::string m = meta.dump(2, ' ', false, json::error_handler_t::replace);
  out += "  \"meta\": ";
  for (char c : m) {
    out += c;
    if (c == '\n') out += "  ";
  }
  out += "\n}\n";
  return out;
}

}  // namespace kintsugi::io::reference
