#include "geometry/revolution_measure.h"

#include "geometry/frame.h"

#include <algorithm>
#include <cmath>

namespace kintsugi::geo {

namespace {

// 2 sin(h/2) / h, the ratio (sin b - sin a) / (h cos m) and its like reduce to; 1 at h = 0.
double sinc_half(double h) { return std::abs(h) < 1e-8 ? 1.0 - h * h / 24 : 2 * std::sin(h / 2) / h; }

// (1/h) ∫_a^b (v - a) cos v dv and (1/h) ∫_a^b (b - v) cos v dv, h = b - a ≥ 0: the
// cosine weighted by the width rising from 0 at a (falling to 0 at b). Written with the
// midpoint's sine so that a thin triangle does not subtract two nearly equal cosines
// divided by its height.
double rising(double a, double b) { return std::sin(b) - std::sin(0.5 * (a + b)) * sinc_half(b - a); }
double falling(double a, double b) { return std::sin(0.5 * (a + b)) * sinc_half(b - a) - std::sin(a); }

// The area element as A + B cos v with a fixed sign over the triangle, if it has one.
struct Element {
  double a, b;
};
std::optional<Element> element(const Surface& s, double vmin, double vmax) {
  if (const auto* k = std::get_if<Sphere>(&s)) {
    const double slack = 1e-12;
    if (vmin < -kPi / 2 - slack || vmax > kPi / 2 + slack) return std::nullopt;
    return Element{0.0, k->radius * k->radius};
  }
  if (const auto* k = std::get_if<Torus>(&s)) {
    if (!(std::abs(k->major_radius) > std::abs(k->minor_radius))) return std::nullopt;  // R + r cos v changes sign
    const double sign = k->major_radius > 0 ? 1.0 : -1.0;
    return Element{k->minor_radius * sign * k->major_radius, k->minor_radius * sign * k->minor_radius};
  }
  return std::nullopt;
}

}  // namespace

bool has_exact_triangle_area(const Surface& s) {
  if (std::holds_alternative<Sphere>(s)) return true;
  if (const auto* k = std::get_if<Torus>(&s)) return std::abs(k->major_radius) > std::abs(k->minor_radius);
  return false;
}

std::optional<double> exact_triangle_area(const Surface& s, const std::array<Vec2, 3>& t) {
  std::array<Vec2, 3> p = t;
  std::sort(p.begin(), p.end(), [](const Vec2& x, const Vec2& y) { return x.y() < y.y(); });
  const double v0 = p[0].y(), v1 = p[1].y(), v2 = p[2].y();
  const std::optional<Element> g = element(s, v0, v2);
  if (!g) return std::nullopt;
  const double h = v2 - v0;
  if (!(h > 0)) return 0.0;
  // The slice at v1 runs from the middle vertex to the long side.
  const double u_long = p[0].x() + (p[2].x() - p[0].x()) * (v1 - v0) / h;
  const double width = std::abs(p[1].x() - u_long);
  const double h1 = v1 - v0, h2 = v2 - v1;
  return width * (g->a * h / 2 + g->b * (rising(v0, v1) * (h1 > 0 ? 1.0 : 0.0) + falling(v1, v2) * (h2 > 0 ? 1.0 : 0.0)));
}

ExtremeCandidates extreme_candidates(const Surface& s) {
  ExtremeCandidates out;
  const Frame* f = nullptr;
  if (const auto* k = std::get_if<Sphere>(&s)) f = &k->frame;
  if (const auto* k = std::get_if<Torus>(&s)) f = &k->frame;
  if (!f) return out;
  const bool sphere = std::holds_alternative<Sphere>(s);
  const Vec3 fx = f->x.normalized(), fy = f->y().normalized(), fz = f->z.normalized();
  for (int i = 0; i < 3; ++i) {
    const Vec3 d = Vec3::Unit(i);
    const double x = d.dot(fx), y = d.dot(fy), b = d.dot(fz);
    const double a = std::hypot(x, y);
    if (a < 1e-9) {
      // The axis is along d: the height depends on v alone, largest and smallest at
      // v = ±π/2 (the poles; the torus's top and bottom circles).
      out.circles.push_back(kPi / 2);
      out.circles.push_back(-kPi / 2);
      continue;
    }
    const double phi = std::atan2(y, x);
    if (sphere) {
      // c ± r d: the direction's own longitude and latitude, and the antipode.
      out.points.emplace_back(phi, std::atan2(b, a));
      out.points.emplace_back(phi + kPi, -std::atan2(b, a));
    } else {
      // On the meridian u = φ the height is (R + r cos v)·a + r·b·sin v, stationary where
      // (sin v, cos v) ∥ (b, a); on u = φ + π it is -(R + r cos v)·a + r·b·sin v,
      // stationary where (sin v, cos v) ∥ (-b, a).
      const double v = std::atan2(b, a), w = std::atan2(-b, a);
      out.points.emplace_back(phi, v);
      out.points.emplace_back(phi, v + kPi);
      out.points.emplace_back(phi + kPi, w);
      out.points.emplace_back(phi + kPi, w + kPi);
    }
  }
  return out;
}

}  // namespace kintsugi::geo
