// Typed reading of the common elements (io/native_json_typed.h says what and why). Every
// check here is one of DocumentReader's (io/native_json_reader.cpp), made the same way on
// the same numbers: a value that passes here passes there and is read as the same value.
#include "io/native_json_typed.h"

#include <charconv>
#include <cmath>
#include <numbers>
#include <string_view>
#include <initializer_list>
#include <utility>

namespace kintsugi::io {

namespace od = simdjson::ondemand;

// Through the typed getters: simdjson 3.0's get_number() reads a double of more than 19
// digits as 0 (the json_reader fuzz target found it within seconds).
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
    unsigned seen = 0;
    return members(o, {"id", "point"}, &seen,
                   [&](std::size_t k, od::value& v) { return k == 0 ? id(v, kMaxId, &out->id) : vec3(v, &out->point); }) &&
           seen == 0b11;
  }

  bool edge(od::object& o, EdgeDesc* out) {
    unsigned seen = 0;
    return members(o, {"id", "he", "curve"}, &seen,
                   [&](std::size_t k, od::value& v) {
                     switch (k) {
                       case 0: return id(v, kMaxEdgeId, &out->id);
                       case 1: return halfedges(v, out->he);
                       default: return curve(v, &out->curve);
                     }
                   }) &&
           (seen & 0b11) == 0b11;  // the curve may be absent
  }

  bool loop(od::object& o, LoopDesc* out) {
    unsigned seen = 0;
    return members(o, {"id", "face", "first", "lone"}, &seen,
                   [&](std::size_t k, od::value& v) {
                     switch (k) {
                       case 0: return id(v, kMaxId, &out->id);
                       case 1: return optional_id(v, &out->face);
                       case 2: return optional_id(v, &out->first);
                       default: return optional_id(v, &out->lone);
                     }
                   }) &&
           (seen & 1) && out->first.has_value() != out->lone.has_value();  // a cycle or a lone vertex
  }

  bool face(od::object& o, FaceDesc* out) {
    unsigned seen = 0;
    return members(o, {"id", "shell", "loops", "same_sense", "surface"}, &seen,
                   [&](std::size_t k, od::value& v) {
                     switch (k) {
                       case 0: return id(v, kMaxId, &out->id);
                       case 1: return id(v, kMaxId, &out->shell);
                       case 2: return id_list(v, &out->loops) && !out->loops.empty();
                       case 3: return boolean(v, &out->same_sense);
                       default: return surface(v, &out->surface);
                     }
                   }) &&
           (seen & 0b1111) == 0b1111;  // the surface may be absent
  }

  bool shell(od::object& o, ShellDesc* out) {
    unsigned seen = 0;
    return members(o, {"id", "genus"}, &seen,
                   [&](std::size_t k, od::value& v) { return id(v, kMaxId, k == 0 ? &out->id : &out->genus); }) &&
           seen == 0b11;
  }

 private:
  bool error_ = false;

  bool failed() {
    error_ = true;
    return false;
  }
  // Reads each member of `o` with read(k, value), k its key's place in `keys`; sets bit k
  // of *seen for each. False on a key not in `keys` or seen twice (the tree path's to read
  // or refuse), on a read that fails, or on a simdjson error.
  template <class Read>
  bool members(od::object& o, std::initializer_list<std::string_view> keys, unsigned* seen, Read read) {
    for (auto member : o) {
      std::string_view key;
      od::value v;
      if (!field(member, &key, &v)) return false;
      std::size_t k = 0;
      for (std::string_view name : keys) {
        if (name == key) break;
        ++k;
      }
      if (k == keys.size() || (*seen & (1u << k))) return false;
      *seen |= 1u << k;
      if (!read(k, v)) return false;
    }
    return true;
  }

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
  // An array or an object value, begun.
  bool array_of(od::value& v, od::array* a) {
    od::json_type type;
    if (!type_of(v, &type) || type != od::json_type::array) return false;
    return !v.get_array().get(*a) || failed();
  }
  bool object_of(od::value& v, od::object* o) {
    od::json_type type;
    if (!type_of(v, &type) || type != od::json_type::object) return false;
    return !v.get_object().get(*o) || failed();
  }

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
    od::array a;
    if (!array_of(v, &a)) return false;
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
    od::array a;
    if (!array_of(v, &a)) return false;
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
    od::object o;
    if (!object_of(v, &o)) return false;
    unsigned seen = 0;
    return members(o, {"origin", "x", "z"}, &seen,
                   [&](std::size_t k, od::value& m) {
                     return k == 0 ? vec3(m, &out->origin) : unit_vec3(m, k == 1 ? &out->x : &out->z);
                   }) &&
           seen == 0b111 && std::abs(out->x.dot(out->z)) <= kUnitTolerance;
  }

  bool halfedges(od::value& v, HalfedgeDesc* he) {
    od::array a;
    if (!array_of(v, &a)) return false;
    std::size_t side = 0;
    for (auto item : a) {
      od::value h;
      od::object o;
      if (std::move(item).get(h)) return failed();
      if (side == 2 || !object_of(h, &o)) return false;
      unsigned seen = 0;
      HalfedgeDesc& h_out = he[side];
      if (!members(o, {"origin", "next", "loop"}, &seen,
                   [&](std::size_t k, od::value& m) {
                     return id(m, kMaxId, k == 0 ? &h_out.origin : k == 1 ? &h_out.next : &h_out.loop);
                   }) ||
          seen != 0b111)
        return false;
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
    bool is(std::initializer_list<Member> members) const {
      unsigned want = 0;
      for (Member m : members) want |= 1u << m;
      return seen == want;
    }
  };
  bool geometry(od::value& v, Geometry* g) {
    od::object o;
    if (!object_of(v, &o)) return false;
    return members(o, {"type", "origin", "direction", "frame", "radius", "half_angle", "major_radius", "minor_radius"},
                   &g->seen,
                   [&](std::size_t k, od::value& m) {
                     switch (Geometry::Member(k)) {
                       case Geometry::kType: return plain_string(m, &g->type);
                       case Geometry::kOrigin: return vec3(m, &g->origin);
                       case Geometry::kDirection: return unit_vec3(m, &g->direction);
                       case Geometry::kFrame: return frame(m, &g->frame);
                       case Geometry::kRadius: return real(m, &g->radius);
                       case Geometry::kHalfAngle: return real(m, &g->half_angle);
                       case Geometry::kMajor: return real(m, &g->major_radius);
                       case Geometry::kMinor: return real(m, &g->minor_radius);
                     }
                     return false;
                   });  // which members a kind needs, "type" among them, its caller's Geometry::is says
  }

  // null (no geometry: *out is std::monostate, *none set) or a geometry object into `g`.
  template <class Variant>
  bool none_or_geometry(od::value& v, Variant* out, Geometry* g, bool* none) {
    if (!is_null(v, none)) return false;
    if (*none) {
      *out = std::monostate{};
      return true;
    }
    return geometry(v, g);
  }

  bool curve(od::value& v, geo::Curve* out) {
    bool none = false;
    Geometry g;
    if (!none_or_geometry(v, out, &g, &none)) return false;
    if (none) return true;
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
    bool none = false;
    Geometry g;
    if (!none_or_geometry(v, out, &g, &none)) return false;
    if (none) return true;
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
