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
                             [](const Torus&) { return "torus"; },
                             [](const BSplineSurface&) { return "bspline_surface"; },
                             [](const RevolutionSurface&) { return "revolution_surface"; },
                             [](const ExtrusionSurface&) { return "extrusion_surface"; },
                             [](const OffsetSurface&) { return "offset_surface"; }},
                    s);
}

const char* curve_type_name(const Curve& c) {
  return std::visit(Overload{[](const std::monostate&) { return "none"; },
                             [](const Line&) { return "line"; },
                             [](const Circle&) { return "circle"; },
                             [](const Ellipse&) { return "ellipse"; },
                             [](const Polyline&) { return "polyline"; },
                             [](const BSplineCurve&) { return "bspline_curve"; }},
                    c);
}

bool is_freeform(const Surface& s) { return s.index() >= std::variant_size_v<Surface> - 4; }
bool is_freeform(const Curve& c) { return std::holds_alternative<BSplineCurve>(c); }

std::shared_ptr<const void>* cache_slot(const Surface& s) {
  return std::visit(
      [](const auto& x) -> std::shared_ptr<const void>* {
        if constexpr (requires { x.cache; })
          return &x.cache;
        else
          return nullptr;
      },
      s);
}

}  // namespace kintsugi::geo
