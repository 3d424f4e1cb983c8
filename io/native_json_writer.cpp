// The native JSON writer (spec/file-format.md), streaming: the body's elements go
// straight from the Body into the output text, one element per line, with no JSON
// document in between (only the small `meta` object goes through nlohmann). A million
// faces write in seconds with memory in proportion to the output alone, or to a
// 1 MiB buffer when the output is a sink (write_native_to, write_native_file).
//
// The bytes are those nlohmann's ordered_json dump gave before (tests/io/reference_writer.cpp
// keeps that writer as the tests' oracle): `{"id": 0, "point": [1.0, 0.0, 2.0]}`, a space
// after every ':' and ','. Numbers are spelled the way nlohmann spells a double (at least
// one digit after a point, or an exponent "1e-06", "1.5e+300"), with the digits of
// std::to_chars' shortest round-trip representation.
#include "io/native_json.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <variant>

namespace kintsugi::io {

namespace {

// The layout nlohmann's serializer gives a finite double, with the shortest digits:
//   0.0, -0.0; digits with a point when the decimal exponent is in [-5, 15)
//   (1.0, 0.25, 123456.0, 0.0001); otherwise d.igitse±XX (1e-05, 1.5e+16).
// Returns the end of what it wrote; `p` needs 32 bytes. Non-finite numbers are written
// as null, as nlohmann does (no valid body has one; the reader refuses it).
char* put_double(char* p, double d) {
  if (!std::isfinite(d)) {
    std::memcpy(p, "null", 4);
    return p + 4;
  }
  if (std::signbit(d)) {
    *p++ = '-';
    d = -d;
  }
  if (d == 0) {
    std::memcpy(p, "0.0", 3);
    return p + 3;
  }
  // Shortest round-trip digits in scientific form: "D[.DDDD]e±XX[X]".
  char sci[32];
  const char* end = std::to_chars(sci, sci + sizeof sci, d, std::chars_format::scientific).ptr;
  char digits[24];
  int k = 0;
  const char* s = sci;
  for (; s < end && *s != 'e'; ++s)
    if (*s != '.') digits[k++] = *s;
  int exponent = 0;
  const bool negative_exponent = s + 1 < end && s[1] == '-';
  for (const char* e = s + 2; e < end; ++e) exponent = exponent * 10 + (*e - '0');
  if (negative_exponent) exponent = -exponent;
  // The value is 0.digits × 10^n.
  const int n = exponent + 1;
  constexpr int kMinExp = -4, kMaxExp = 15;  // nlohmann's bounds for double
  if (k <= n && n <= kMaxExp) {  // digits[000].0
    std::memcpy(p, digits, std::size_t(k));
    p += k;
    std::memset(p, '0', std::size_t(n - k));
    p += n - k;
    *p++ = '.';
    *p++ = '0';
    return p;
  }
  if (0 < n && n <= kMaxExp) {  // dig.its
    std::memcpy(p, digits, std::size_t(n));
    p += n;
    *p++ = '.';
    std::memcpy(p, digits + n, std::size_t(k - n));
    return p + (k - n);
  }
  if (kMinExp < n && n <= 0) {  // 0.[000]digits
    *p++ = '0';
    *p++ = '.';
    std::memset(p, '0', std::size_t(-n));
    p += -n;
    std::memcpy(p, digits, std::size_t(k));
    return p + k;
  }
  *p++ = digits[0];  // d[.igits]e±XX
  if (k > 1) {
    *p++ = '.';
    std::memcpy(p, digits + 1, std::size_t(k - 1));
    p += k - 1;
  }
  *p++ = 'e';
  int e = n - 1;
  *p++ = e < 0 ? '-' : '+';
  if (e < 0) e = -e;
  if (e < 10) *p++ = '0';
  return std::to_chars(p, p + 4, e).ptr;
}

template <class... Fs>
struct Overload : Fs... {
  using Fs::operator()...;
};
// clang before 17 does not deduce aggregate template arguments without a guide.
template <class... Fs>
Overload(Fs...) -> Overload<Fs...>;

// Appends JSON text to `out`; after each element, hands `out` to the sink (if any) once
// it holds kChunk bytes, and empties it.
class Writer {
 public:
  static constexpr std::size_t kChunk = std::size_t(1) << 20;

  Writer(std::string& out, const ChunkSink* sink) : out_(out), sink_(sink) {}

  bool document(const Body& b, const nlohmann::json& meta, const std::string& units) {
    raw("{\n  \"format\": \"kintsugi-brep\",\n  \"version\": 1,\n  \"units\": ");
    raw(nlohmann::json(units).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
    raw(",\n");

    open_section("vertices");
    for (VertexH v : b.vertices()) {
      next_element();
      raw("{\"id\": ");
      uint(v.idx());
      raw(", \"point\": ");
      vec3(b.point(v));
      raw("}");
      if (!element_done()) return false;
    }
    close_section();

    open_section("edges");
    for (EdgeH e : b.edges()) {
      next_element();
      raw("{\"id\": ");
      uint(e.idx());
      raw(", \"he\": [");
      for (unsigned side = 0; side < 2; ++side) {
        const HalfedgeH h = halfedge_of(e, side);
        raw(side ? ", {\"origin\": " : "{\"origin\": ");
        uint(b.origin(h).idx());
        raw(", \"next\": ");
        uint(b.next(h).idx());
        raw(", \"loop\": ");
        uint(b.loop(h).idx());
        raw("}");
      }
      raw("], \"curve\": ");
      curve(b.curve(e));
      raw("}");
      if (!element_done()) return false;
    }
    close_section();

    open_section("loops");
    for (LoopH l : b.loops()) {
      next_element();
      raw("{\"id\": ");
      uint(l.idx());
      raw(", \"face\": ");
      if (b.is_border(l))
        raw("null");
      else
        uint(b.face(l).idx());
      if (b.is_lone(l)) {
        raw(", \"lone\": ");
        uint(b.lone_vertex(l).idx());
      } else {
        raw(", \"first\": ");
        uint(b.first(l).idx());
      }
      raw("}");
      if (!element_done()) return false;
    }
    close_section();

    open_section("faces");
    for (FaceH f : b.faces()) {
      next_element();
      raw("{\"id\": ");
      uint(f.idx());
      raw(", \"shell\": ");
      uint(b.shell(f).idx());
      raw(", \"loops\": [");
      bool first = true;
      for (LoopH l : b.loops_of(f)) {
        if (!first) raw(", ");
        first = false;
        uint(l.idx());
      }
      raw(b.same_sense(f) ? "], \"same_sense\": true, \"surface\": " : "], \"same_sense\": false, \"surface\": ");
      surface(b.surface(f));
      raw("}");
      if (!element_done()) return false;
    }
    close_section();

    open_section("shells");
    for (ShellH s : b.shells()) {
      next_element();
      raw("{\"id\": ");
      uint(s.idx());
      raw(", \"genus\": ");
      uint(b.shell_genus(s));
      raw("}");
      if (!element_done()) return false;
    }
    close_section();

    // meta is free-form and small: nlohmann's indented dump, shifted right by two.
    raw("  \"meta\": ");
    const std::string m = meta.dump(2, ' ', false, nlohmann::json::error_handler_t::replace);
    for (std::size_t start = 0;;) {
      const std::size_t nl = m.find('\n', start);
      if (nl == std::string::npos) {
        raw(std::string_view(m).substr(start));
        break;
      }
      raw(std::string_view(m).substr(start, nl + 1 - start));
      raw("  ");
      start = nl + 1;
    }
    raw("\n}\n");
    return flush();
  }

 private:
  std::string& out_;
  const ChunkSink* sink_;
  bool first_in_section_ = true;

  void raw(std::string_view s) { out_.append(s); }
  void uint(std::uint32_t v) {
    char buf[16];
    out_.append(buf, std::to_chars(buf, buf + sizeof buf, v).ptr);
  }
  void number(double d) {
    char buf[40];
    out_.append(buf, put_double(buf, d));
  }
  void vec3(const geo::Vec3& p) {
    char buf[3 * 40 + 8];
    char* q = buf;
    *q++ = '[';
    q = put_double(q, p.x());
    *q++ = ',';
    *q++ = ' ';
    q = put_double(q, p.y());
    *q++ = ',';
    *q++ = ' ';
    q = put_double(q, p.z());
    *q++ = ']';
    out_.append(buf, q);
  }
  void frame(const geo::Frame& f) {
    raw("{\"origin\": ");
    vec3(f.origin);
    raw(", \"x\": ");
    vec3(f.x);
    raw(", \"z\": ");
    vec3(f.z);
    raw("}");
  }
  // `, "key": number`
  void member(std::string_view key, double d) {
    raw(", \"");
    raw(key);
    raw("\": ");
    number(d);
  }

  void numbers(std::string_view key, const std::vector<double>& v) {
    raw(", \"");
    raw(key);
    raw("\": [");
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (i) raw(", ");
      number(v[i]);
    }
    raw("]");
  }
  void integers(std::string_view key, const std::vector<int>& v) {
    raw(", \"");
    raw(key);
    raw("\": [");
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (i) raw(", ");
      raw(std::to_string(v[i]));
    }
    raw("]");
  }
  void integer(std::string_view key, int v) {
    raw(", \"");
    raw(key);
    raw("\": ");
    raw(std::to_string(v));
  }
  void boolean(std::string_view key, bool v) {
    raw(", \"");
    raw(key);
    raw(v ? "\": true" : "\": false");
  }
  void points(std::string_view key, const std::vector<geo::Vec3>& v) {
    raw(", \"");
    raw(key);
    raw("\": [");
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (i) raw(", ");
      vec3(v[i]);
    }
    raw("]");
  }
  void vector_member(std::string_view key, const geo::Vec3& v) {
    raw(", \"");
    raw(key);
    raw("\": ");
    vec3(v);
  }
  // Free-form data (spec/file-format.md, "Free-form geometry"); weights only when rational.
  void bspline_curve(const geo::BSplineCurve& c) {
    raw("{\"type\": \"bspline_curve\"");
    integer("degree", c.degree);
    points("poles", c.poles);
    if (!c.weights.empty()) numbers("weights", c.weights);
    numbers("knots", c.knots);
    integers("multiplicities", c.multiplicities);
    boolean("periodic", c.periodic);
    raw("}");
  }
  void bspline_surface(const geo::BSplineSurface& b) {
    raw("{\"type\": \"bspline_surface\"");
    integer("u_degree", b.u_degree);
    integer("v_degree", b.v_degree);
    integer("u_count", b.u_count);
    integer("v_count", b.v_count);
    points("poles", b.poles);
    if (!b.weights.empty()) numbers("weights", b.weights);
    numbers("u_knots", b.u_knots);
    numbers("v_knots", b.v_knots);
    integers("u_multiplicities", b.u_multiplicities);
    integers("v_multiplicities", b.v_multiplicities);
    boolean("u_periodic", b.u_periodic);
    boolean("v_periodic", b.v_periodic);
    raw("}");
  }

  void surface(const geo::Surface& s) {
    std::visit(Overload{[&](const std::monostate&) { raw("null"); },
                        [&](const geo::Plane& p) {
                          raw("{\"type\": \"plane\", \"frame\": ");
                          frame(p.frame);
                          raw("}");
                        },
                        [&](const geo::Cylinder& c) {
                          raw("{\"type\": \"cylinder\", \"frame\": ");
                          frame(c.frame);
                          member("radius", c.radius);
                          raw("}");
                        },
                        [&](const geo::Cone& c) {
                          raw("{\"type\": \"cone\", \"frame\": ");
                          frame(c.frame);
                          member("radius", c.radius);
                          member("half_angle", c.half_angle);
                          raw("}");
                        },
                        [&](const geo::Sphere& c) {
                          raw("{\"type\": \"sphere\", \"frame\": ");
                          frame(c.frame);
                          member("radius", c.radius);
                          raw("}");
                        },
                        [&](const geo::Torus& t) {
                          raw("{\"type\": \"torus\", \"frame\": ");
                          frame(t.frame);
                          member("major_radius", t.major_radius);
                          member("minor_radius", t.minor_radius);
                          raw("}");
                        },
                        [&](const geo::BSplineSurface& b) { bspline_surface(b); },
                        [&](const geo::RevolutionSurface& r) {
                          raw("{\"type\": \"revolution_surface\", \"basis\": ");
                          bspline_curve(r.basis);
                          vector_member("origin", r.origin);
                          vector_member("axis", r.axis);
                          raw("}");
                        },
                        [&](const geo::ExtrusionSurface& e) {
                          raw("{\"type\": \"extrusion_surface\", \"basis\": ");
                          bspline_curve(e.basis);
                          vector_member("direction", e.direction);
                          raw("}");
                        },
                        [&](const geo::OffsetSurface& o) {
                          raw("{\"type\": \"offset_surface\", \"basis\": ");
                          bspline_surface(o.basis);
                          member("distance", o.distance);
                          raw("}");
                        }},
               s);
  }

  void curve(const geo::Curve& c) {
    std::visit(Overload{[&](const std::monostate&) { raw("null"); },
                        [&](const geo::Line& l) {
                          raw("{\"type\": \"line\", \"origin\": ");
                          vec3(l.origin);
                          raw(", \"direction\": ");
                          vec3(l.direction);
                          raw("}");
                        },
                        [&](const geo::Circle& k) {
                          raw("{\"type\": \"circle\", \"frame\": ");
                          frame(k.frame);
                          member("radius", k.radius);
                          raw("}");
                        },
                        [&](const geo::Ellipse& e) {
                          raw("{\"type\": \"ellipse\", \"frame\": ");
                          frame(e.frame);
                          member("major_radius", e.major_radius);
                          member("minor_radius", e.minor_radius);
                          raw("}");
                        },
                        [&](const geo::Polyline& p) {
                          raw("{\"type\": \"polyline\", \"points\": [");
                          for (std::size_t i = 0; i < p.points.size(); ++i) {
                            if (i) raw(", ");
                            vec3(p.points[i]);
                          }
                          raw("]");
                          member("chordal_error", p.chordal_error);
                          raw("}");
                        },
                        [&](const geo::BSplineCurve& b) { bspline_curve(b); }},
               c);
  }

  // "key": [ one element per line ], or "key": [] when there are none.
  void open_section(const char* key) {
    raw("  \"");
    raw(key);
    raw("\": [");
    first_in_section_ = true;
  }
  void next_element() {
    raw(first_in_section_ ? "\n    " : ",\n    ");
    first_in_section_ = false;
  }
  void close_section() { raw(first_in_section_ ? "],\n" : "\n  ],\n"); }

  bool element_done() { return !sink_ || out_.size() < kChunk || flush(); }
  bool flush() {
    if (!sink_ || out_.empty()) return true;
    const bool ok = (*sink_)(std::string_view(out_));
    out_.clear();
    return ok;
  }
};

// A guess at the document's size from the element counts (about what the scalable
// family takes per element), so the output string rarely grows by copying itself.
std::size_t estimated_size(const Body& b) {
  const Counts c = b.counts();
  return 4096 + 90 * c.vertices + 330 * c.edges + 48 * (c.loops + c.border_cycles) + 200 * c.faces + 32 * c.shells;
}

}  // namespace

bool write_native_to(const Body& b, const nlohmann::json& meta, const std::string& units, const ChunkSink& sink) {
  std::string buffer;
  buffer.reserve(Writer::kChunk + (std::size_t(64) << 10));
  return Writer(buffer, &sink).document(b, meta, units);
}

std::string write_native(const Body& b, const nlohmann::json& meta, const std::string& units) {
  std::string out;
  out.reserve(estimated_size(b));
  Writer(out, nullptr).document(b, meta, units);
  return out;
}

bool write_native_file(const std::string& path, const Body& b, const nlohmann::json& meta, const std::string& units,
                       std::string* error, const std::string& must_not_overwrite) {
  return write_file_atomically_streamed(
      path, [&](const ChunkSink& sink) { return write_native_to(b, meta, units, sink); }, error, must_not_overwrite);
}

}  // namespace kintsugi::io
