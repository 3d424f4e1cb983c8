#include "geometry/types.h"

namespace kintsugi::geo {

namespace {
template <class... Fs>
struct Overload : Fs... {
  using Fs::operator()...;
};
// clang before 17 does not deduce aggregate template arguments without this guide.
template <class... Fs>
Overload(Fs...) -> Overload<Fs...>;
}  // namespace

const char* surface_type_name(const Surface& s) {
  return std::visit(Overload{[](const std::monostate&) { return "none"; },
                             [](const Plane&) { return "plane"; },
                             [](const Cylinder&) { return "cylinder"; },
                             [](const Cone&) { return "cone"; },
                             [](const Sphere&) { return "sphere"; },
                             [](const Torus&) { return "torus"; }},
                    s);
}

const char* curve_type_name(const Curve& c) {
  return std::visit(Overload{[](const std::monostate&) { return "none"; },
                             [](const Line&) { return "line"; },
                             [](const Circle&) { return "circle"; },
                             [](const Ellipse&) { return "ellipse"; },
                             [](const Polyline&) { return "polyline"; }},
                    c);
}

}  // namespace kintsugi::geo
