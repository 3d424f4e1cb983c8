// rapidcheck generators for geometry tests: random frames, surfaces, rigid motions.
#pragma once

#include "geometry/frame.h"
#include "geometry/types.h"

#include <rapidcheck.h>

#include <Eigen/Geometry>

namespace kintsugi::geo::testing {

inline double gen_real(double lo, double hi) {
  // 2^20 steps: fine enough for geometry, and rapidcheck can shrink towards lo.
  const int k = *rc::gen::inRange(0, 1 << 20);
  return lo + (hi - lo) * k / double(1 << 20);
}
inline Vec3 gen_vec(double extent) {
  return Vec3(gen_real(-extent, extent), gen_real(-extent, extent), gen_real(-extent, extent));
}
// Uniform on the sphere (no rejection loop: shrinking must terminate).
inline Vec3 gen_unit() {
  const double z = gen_real(-1.0, 1.0), a = gen_real(-kPi, kPi);
  const double s = std::sqrt(std::max(0.0, 1 - z * z));
  return Vec3(s * std::cos(a), s * std::sin(a), z);
}
inline Frame gen_frame(double extent = 5.0) { return frame_from_axis(gen_vec(extent), gen_unit(), gen_unit()); }

// A rigid motion followed by a uniform scale: x -> scale·(R x + t).
struct Similarity {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Vec3 translation = Vec3::Zero();
  double scale = 1.0;
  Vec3 point(const Vec3& p) const { return scale * (rotation * p + translation); }
  Vec3 vector(const Vec3& v) const { return rotation * v; }
  Frame frame(const Frame& f) const { return Frame{point(f.origin), vector(f.x), vector(f.z)}; }
};
inline Similarity gen_similarity(bool with_scale) {
  Similarity s;
  s.rotation = Eigen::AngleAxisd(gen_real(-kPi, kPi), gen_unit()).toRotationMatrix();
  s.translation = gen_vec(10.0);
  if (with_scale) s.scale = *rc::gen::element(0.001, 0.5, 3.0, 1000.0);
  return s;
}

// Surfaces of moderate size around the origin (radii in [0.5, 3]).
inline Surface gen_surface(int kind) {
  const Frame f = gen_frame();
  switch (kind) {
    case 0: return Plane{f};
    case 1: return Cylinder{f, gen_real(0.5, 3.0)};
    case 2: {
      const double a = gen_real(0.2, 1.2) * (*rc::gen::element(-1.0, 1.0));
      return Cone{f, gen_real(0.5, 3.0), a};
    }
    case 3: return Sphere{f, gen_real(0.5, 3.0)};
    default: {
      const double R = gen_real(1.5, 3.0);
      return Torus{f, R, gen_real(0.3, 0.9) * R};
    }
  }
}
inline Surface gen_any_surface() { return gen_surface(*rc::gen::inRange(0, 5)); }

inline Surface transform(const Surface& s, const Similarity& m) {
  return std::visit(
      [&](const auto& x) -> Surface {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, std::monostate> || !requires { x.frame; }) {
          return x;  // free-form surfaces are not generated here
        } else {
          T y = x;
          y.frame = m.frame(x.frame);
          if constexpr (std::is_same_v<T, Cylinder> || std::is_same_v<T, Sphere> || std::is_same_v<T, Cone>) {
            y.radius *= m.scale;
          } else if constexpr (std::is_same_v<T, Torus>) {
            y.major_radius *= m.scale;
            y.minor_radius *= m.scale;
          }
          return y;
        }
      },
      s);
}

}  // namespace kintsugi::geo::testing
