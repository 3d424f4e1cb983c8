// Typed reading of the common elements (io/native_json_typed.h says what and why). Every
// check here is one of DocumentReader's (io/native_json_reader.cpp), made the same way on
// the same numbers: a value that passes here passes there and is read as the same value.
#include "io/native_json_typed.h"

#include <charconv>
#include <cmath>
#include <numbers>
#include <string_view>
#include <utility>

namespace kintsugi::io {

namespace od = simdjson::ondemand;

bool read_json_number(od::value& v, JsonNumber* out) {
  const bool negative = v.is_negative();
  od::number_type type;
  if (v.get_number_type().get(type)) return false;
  switch (type) {
    case od::number_type::floating_point_number: {
      std::string_view token = v.raw_json_token();
      while (!token.empty() && (token.back() == ' ' || token.back() == '\t' || token.back() == '\n' || token.back() == '\r'))
        token.remove_suffix(1);
      double d;
      if (v.get_double().get(d)) return false;  // also: outside a double
      // simdjson 3.0's portable kernel gets long mantissas wrong (0.444...4 of 110 digits
      // read as 1.4e-88: the json_reader fuzz target). Its fast path, up to 19 digits, is
      // exact; a longer number is read by from_chars, correctly rounded as nlohmann's strtod
      // is, and whatever the locale. Past a double's range (an underflow simdjson let
      // through) the reference parser decides.
      if (token.size() > 19) {
        auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), d);
        if (ec != std::errc() || end != token.data() + token.size()) return false;
      }
      out->type = JsonNumber::kFloat;
      out->d = d;
      return true;
    }
    case od::number_type::signed_integer: {
      std::int64_t i;
      if (v.get_int64().get(i)) return false;
      if (negative) {
        out->type = JsonNumber::kSigned;
        out->i = i;
      } else {
        out->type = JsonNumber::kUnsigned;
        out->u = std::uint64_t(i);
      }
      return true;
    }
    case od::number_type::unsigned_integer: {
      std::uint64_t u;
      if (v.get_uint64().get(u)) return false;  // also: past 64 bits
      out->type = JsonNumber::kUnsigned;
      out->u = u;
      return true;
    }
  }
  return false;
}

namespace {

// Reads one element; each step returns false to stop, with error_ set when simdjson
// failed (else the element is simply not one this reader takes).
class TypedReader {
 public:
  bool error() const { return error_; }

  bool vertex(od::object& o, VertexDesc* out) {
    bool id_seen = false, point_seen = false;
    for (auto member : o) {
      std::string_view key;
      od::value v;
      if (!field(member, &key, &v)) return false;
      if (key == "id") {
        if (!once(&id_seen) || !id(v, kMaxId, &out->id)) return false;
      } else if (key == "point") {
        if (!once(&point_seen) || !vec3(v, &out->point)) return false;
      } else {
        return false;
      }
    }
    return id_seen && point_seen;
  }

  bool edge(od::object& o, EdgeDesc* out) {
    bool id_seen = false, he_seen = false, curve_seen = false;
    for (auto member : o) {
      std::string_view key;
      od::value v;
      if (!field(member, &key, &v)) return false;
      if (key == "id") {
        if (!once(&id_seen) || !id(v, kMaxEdgeId, &out->id)) return false;
      } else if (key == "he") {
        if (!once(&he_seen) || !halfedges(v, out->he)) return false;
      } else if (key == "curve") {
        if (!once(&curve_seen) || !curve(v, &out->curve)) return false;
      } else {
        return false;
      }
    }
    return id_seen && he_seen;
  }

  bool loop(od::object& o, LoopDesc* out) {
    bool id_seen = false, face_seen = false, first_seen = false, lone_seen = false;
    for (auto member : o) {
      std::string_view key;
      od::value v;
      if (!field(member, &key, &v)) return false;
      if (key == "id") {
        if (!once(&id_seen) || !id(v, kMaxId, &out->id)) return false;
      } else if (key == "face") {
        if (!once(&face_seen) || !optional_id(v, &out->face)) return false;
      } else if (key == "first") {
        if (!once(&first_seen) || !optional_id(v, &out->first)) return false;
      } else if (key == "lone") {
        if (!once(&lone_seen) || !optional_id(v, &out->lone)) return false;
      } else {
        return false;
      }
    }
    // A cycle of half-edges or a lone vertex, not both, not neither.
    return id_seen && out->first.has_value() != out->lone.has_value();
  }

  bool face(od::object& o, FaceDesc* out) {
    bool id_seen = false, shell_seen = false, loops_seen = false, sense_seen = false, surface_seen = false;
    for (auto member : o) {
      std::string_view key;
      od::value v;
      if (!field(member, &key, &v)) return false;
      if (key == "id") {
        if (!once(&id_seen) || !id(v, kMaxId, &out->id)) return false;
      } else if (key == "shell") {
        if (!once(&shell_seen) || !id(v, kMaxId, &out->shell)) return false;
      } else if (key == "loops") {
        if (!once(&loops_seen) || !id_list(v, &out->loops) || out->loops.empty()) return false;
      } else if (key == "same_sense") {
        if (!once(&sense_seen) || !boolean(v, &out->same_sense)) return false;
      } else if (key == "surface") {
        if (!once(&surface_seen) || !surface(v, &out->surface)) return false;
      } else {
        return false;
      }
    }
    return id_seen && shell_seen && loops_seen && sense_seen;
  }

  bool shell(od::object& o, ShellDesc* out) {
    bool id_seen = false, genus_seen = false;
    for (auto member : o) {
      std::string_view key;
      od::value v;
      if (!field(member, &key, &v)) return false;
      if (key == "id") {
        if (!once(&id_seen) || !id(v, kMaxId, &out->id)) return false;
      } else if (key == "genus") {
        if (!once(&genus_seen) || !id(v, kMaxId, &out->genus)) return false;
      } else {
        return false;
      }
    }
    return id_seen && genus_seen;
  }

 private:
  bool error_ = false;

  bool failed() {
    error_ = true;
    return false;
  }
  // A key seen for the first time (a repeat is the tree path's to refuse).
  static bool once(bool* seen) { return !std::exchange(*seen, true); }

  // A member: its key when written without escapes (never unescaped here, so that the tree
  // path may read the element again), and its value.
  template <class Member>
  bool field(Member& member, std::string_view* key, od::value* v) {
    od::field f;
    if (std::move(member).get(f)) return failed();
    const char* raw = f.key().raw();
    const char* end = raw;
    while (*end != '"' && *end != '\\') ++end;
    if (*end != '"') return false;
    *key = std::string_view(raw, std::size_t(end - raw));
    *v = f.value();
    return true;
  }

  bool type_of(od::value& v, od::json_type* type) { return !v.type().get(*type) || failed(); }

  // A string value written without escapes, as its text.
  bool plain_string(od::value& v, std::string_view* s) {
    od::json_type type;
    if (!type_of(v, &type) || type != od::json_type::string) return false;
    od::raw_json_string raw;
    if (v.get_raw_json_string().get(raw)) return failed();
    const char* begin = raw.raw();
    const char* end = begin;
    while (*end != '"' && *end != '\\') ++end;
    if (*end != '"') return false;
    *s = std::string_view(begin, std::size_t(end - begin));
    return true;
  }

  // null, which the tree path reads as an absent optional member.
  bool is_null(od::value& v, bool* null) {
    od::json_type type;
    if (!type_of(v, &type)) return false;
    *null = type == od::json_type::null;
    if (!*null) return true;
    bool is = false;
    if (v.is_null().get(is)) return failed();
    return is;
  }

  bool number(od::value& v, JsonNumber* n) {
    od::json_type type;
    if (!type_of(v, &type) || type != od::json_type::number) return false;
    return read_json_number(v, n) || failed();
  }
  // DocumentReader::number: any number, finite.
  bool real(od::value& v, double* out) {
    JsonNumber n;
    if (!number(v, &n)) return false;
    *out = n.as_double();
    return std::isfinite(*out);
  }
  bool positive(od::value& v, double* out) { return real(v, out) && *out > 0; }
  // DocumentReader::id: an unsigned integer up to `max`.
  bool id(od::value& v, std::uint64_t max, std::uint32_t* out) {
    JsonNumber n;
    if (!number(v, &n) || n.type != JsonNumber::kUnsigned || n.u > max) return false;
    *out = std::uint32_t(n.u);
    return true;
  }
  bool optional_id(od::value& v, std::optional<std::uint32_t>* out) {
    bool null = false;
    if (!is_null(v, &null)) return false;
    if (null) {
      out->reset();
      return true;
    }
    std::uint32_t x;
    if (!id(v, kMaxId, &x)) return false;
    *out = x;
    return true;
  }
  bool boolean(od::value& v, bool* out) {
    od::json_type type;
    if (!type_of(v, &type) || type != od::json_type::boolean) return false;
    return !v.get_bool().get(*out) || failed();
  }
  bool id_list(od::value& v, std::vector<std::uint32_t>* out) {
    od::json_type type;
    od::array a;
    if (!type_of(v, &type) || type != od::json_type::array) return false;
    if (v.get_array().get(a)) return failed();
    out->clear();
    for (auto item : a) {
      od::value x;
      std::uint32_t n;
      if (std::move(item).get(x)) return failed();
      if (!id(x, kMaxId, &n)) return false;
      out->push_back(n);
    }
    return true;
  }
  bool vec3(od::value& v, geo::Vec3* out) {
    od::json_type type;
    od::array a;
    if (!type_of(v, &type) || type != od::json_type::array) return false;
    if (v.get_array().get(a)) return failed();
    Eigen::Index k = 0;
    for (auto item : a) {
      od::value x;
      if (std::move(item).get(x)) return failed();
      if (k == 3 || !real(x, &(*out)[k])) return false;
      ++k;
    }
    return k == 3;
  }
  bool unit_vec3(od::value& v, geo::Vec3* out) {
    return vec3(v, out) && std::abs(out->norm() - 1.0) <= kUnitTolerance;
  }
  bool frame(od::value& v, geo::Frame* out) {
    od::json_type type;
    od::object o;
    if (!type_of(v, &type) || type != od::json_type::object) return false;
    if (v.get_object().get(o)) return failed();
    bool origin_seen = false, x_seen = false, z_seen = false;
    for (auto member : o) {
      std::string_view key;
      od::value m;
      if (!field(member, &key, &m)) return false;
      if (key == "origin") {
        if (!once(&origin_seen) || !vec3(m, &out->origin)) return false;
      } else if (key == "x") {
        if (!once(&x_seen) || !unit_vec3(m, &out->x)) return false;
      } else if (key == "z") {
        if (!once(&z_seen) || !unit_vec3(m, &out->z)) return false;
      } else {
        return false;
      }
    }
    return origin_seen && x_seen && z_seen && std::abs(out->x.dot(out->z)) <= kUnitTolerance;
  }
  bool halfedges(od::value& v, HalfedgeDesc* he) {
    od::json_type type;
    od::array a;
    if (!type_of(v, &type) || type != od::json_type::array) return false;
    if (v.get_array().get(a)) return failed();
    std::size_t side = 0;
    for (auto item : a) {
      od::value h;
      od::object o;
      if (std::move(item).get(h)) return failed();
      if (side == 2 || !type_of(h, &type) || type != od::json_type::object) return false;
      if (h.get_object().get(o)) return failed();
      bool origin_seen = false, next_seen = false, loop_seen = false;
      for (auto member : o) {
        std::string_view key;
        od::value m;
        if (!field(member, &key, &m)) return false;
        if (key == "origin") {
          if (!once(&origin_seen) || !id(m, kMaxId, &he[side].origin)) return false;
        } else if (key == "next") {
          if (!once(&next_seen) || !id(m, kMaxId, &he[side].next)) return false;
        } else if (key == "loop") {
          if (!once(&loop_seen) || !id(m, kMaxId, &he[side].loop)) return false;
        } else {
          return false;
        }
      }
      if (!origin_seen || !next_seen || !loop_seen) return false;
      ++side;
    }
    return side == 2;
  }

  // The members a geometry object of the analytic kinds may have.
  struct Geometry {
    std::string_view type;
    geo::Vec3 origin, direction;
    geo::Frame frame;
    double radius = 0, half_angle = 0, major_radius = 0, minor_radius = 0;
    enum Member { kType, kOrigin, kDirection, kFrame, kRadius, kHalfAngle, kMajor, kMinor };
    unsigned seen = 0;
    bool has(Member m) const { return seen & (1u << m); }
    bool is(std::initializer_list<Member> members) const {
      unsigned want = 0;
      for (Member m : members) want |= 1u << m;
      return seen == want;
    }
  };
  bool geometry(od::value& v, Geometry* g) {
    od::json_type type;
    od::object o;
    if (!type_of(v, &type) || type != od::json_type::object) return false;
    if (v.get_object().get(o)) return failed();
    for (auto member : o) {
      std::string_view key;
      od::value m;
      if (!field(member, &key, &m)) return false;
      Geometry::Member which;
      bool ok = false;
      if (key == "type") {
        which = Geometry::kType;
        ok = plain_string(m, &g->type);
      } else if (key == "origin") {
        which = Geometry::kOrigin;
        ok = vec3(m, &g->origin);
      } else if (key == "direction") {
        which = Geometry::kDirection;
        ok = unit_vec3(m, &g->direction);
      } else if (key == "frame") {
        which = Geometry::kFrame;
        ok = frame(m, &g->frame);
      } else if (key == "radius") {
        which = Geometry::kRadius;
        ok = real(m, &g->radius);
      } else if (key == "half_angle") {
        which = Geometry::kHalfAngle;
        ok = real(m, &g->half_angle);
      } else if (key == "major_radius") {
        which = Geometry::kMajor;
        ok = real(m, &g->major_radius);
      } else if (key == "minor_radius") {
        which = Geometry::kMinor;
        ok = real(m, &g->minor_radius);
      } else {
        return false;
      }
      if (!ok || g->has(which)) return false;
      g->seen |= 1u << which;
    }
    return g->has(Geometry::kType);
  }

  bool curve(od::value& v, geo::Curve* out) {
    bool null = false;
    if (!is_null(v, &null)) return false;
    if (null) {
      *out = std::monostate{};
      return true;
    }
    Geometry g;
    if (!geometry(v, &g)) return false;
    using M = Geometry::Member;
    if (g.type == "line" && g.is({M::kType, M::kOrigin, M::kDirection})) {
      *out = geo::Line{g.origin, g.direction};
      return true;
    }
    if (g.type == "circle" && g.is({M::kType, M::kFrame, M::kRadius}) && g.radius > 0) {
      *out = geo::Circle{g.frame, g.radius};
      return true;
    }
    return false;
  }

  bool surface(od::value& v, geo::Surface* out) {
    bool null = false;
    if (!is_null(v, &null)) return false;
    if (null) {
      *out = std::monostate{};
      return true;
    }
    Geometry g;
    if (!geometry(v, &g)) return false;
    using M = Geometry::Member;
    if (g.type == "plane" && g.is({M::kType, M::kFrame})) {
      *out = geo::Plane{g.frame};
      return true;
    }
    if ((g.type == "cylinder" || g.type == "sphere") && g.is({M::kType, M::kFrame, M::kRadius}) && g.radius > 0) {
      if (g.type == "cylinder")
        *out = geo::Cylinder{g.frame, g.radius};
      else
        *out = geo::Sphere{g.frame, g.radius};
      return true;
    }
    if (g.type == "cone" && g.is({M::kType, M::kFrame, M::kRadius, M::kHalfAngle}) && g.radius >= 0 &&
        std::abs(g.half_angle) < std::numbers::pi / 2 && g.half_angle != 0) {
      *out = geo::Cone{g.frame, g.radius, g.half_angle};
      return true;
    }
    if (g.type == "torus" && g.is({M::kType, M::kFrame, M::kMajor, M::kMinor}) && g.major_radius > 0 &&
        g.minor_radius > 0 && g.minor_radius < g.major_radius) {
      *out = geo::Torus{g.frame, g.major_radius, g.minor_radius};
      return true;
    }
    return false;
  }
};

// Appends an element read by `read` to `to`, or nothing.
template <class Desc, class Read>
Typed append(std::vector<Desc>& to, Read read) {
  TypedReader r;
  if (read(r, &to.emplace_back())) return Typed::kRead;
  to.pop_back();
  return r.error() ? Typed::kError : Typed::kNotTyped;
}

}  // namespace

Typed read_typed_element(od::object& o, ElementKind kind, BodyDescription* d) {
  switch (kind) {
    case kVertices: return append(d->vertices, [&](TypedReader& r, VertexDesc* e) { return r.vertex(o, e); });
    case kEdges: return append(d->edges, [&](TypedReader& r, EdgeDesc* e) { return r.edge(o, e); });
    case kLoops: return append(d->loops, [&](TypedReader& r, LoopDesc* e) { return r.loop(o, e); });
    case kFaces: return append(d->faces, [&](TypedReader& r, FaceDesc* e) { return r.face(o, e); });
    case kShells: return append(d->shells, [&](TypedReader& r, ShellDesc* e) { return r.shell(o, e); });
    case kElementKinds: break;
  }
  return Typed::kNotTyped;
}

}  // namespace kintsugi::io
