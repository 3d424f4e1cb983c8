#include "geometry/curve.h"

#include "geometry/frame.h"
#include "geometry/freeform.h"
#include "geometry/overload.h"
#include "geometry/quadrature.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace kintsugi::geo {

namespace {

[[noreturn]] void no_geometry() { throw std::invalid_argument("curve has no geometry (monostate)"); }

// Cumulative arc length at each polyline point.
std::vector<double> cumulative(const Polyline& p) {
  std::vector<double> s(p.points.size(), 0.0);
  for (std::size_t i = 1; i < p.points.size(); ++i) s[i] = s[i - 1] + (p.points[i] - p.points[i - 1]).norm();
  return s;
}

// Index of the segment [i, i+1] holding arc length t (clamped to the polyline).
std::size_t segment_at(const std::vector<double>& s, double t) {
  if (s.size() < 2) return 0;
  auto it = std::upper_bound(s.begin(), s.end(), t);
  std::size_t i = it == s.begin() ? 0 : static_cast<std::size_t>(it - s.begin()) - 1;
  return std::min(i, s.size() - 2);
}

Vec3 polyline_at(const Polyline& p, double t) {
  if (p.points.empty()) throw std::invalid_argument("polyline has no points");
  if (p.points.size() == 1) return p.points[0];
  const std::vector<double> s = cumulative(p);
  t = std::clamp(t, 0.0, s.back());
  const std::size_t i = segment_at(s, t);
  const double len = s[i + 1] - s[i];
  const double w = len > 0 ? (t - s[i]) / len : 0.0;
  return (1 - w) * p.points[i] + w * p.points[i + 1];
}

Vec3 ellipse_at(const Ellipse& e, double t) {
  return e.frame.origin + e.major_radius * std::cos(t) * e.frame.x + e.minor_radius * std::sin(t) * e.frame.y();
}

// Speed |C'(t)| of an ellipse.
double ellipse_speed(const Ellipse& e, double t) {
  return std::hypot(e.major_radius * std::sin(t), e.minor_radius * std::cos(t));
}

// Largest distance of the ellipse arc over [ta, tb] (a span under π) from its chord.
// It is reached where the tangent (-a sin t, b cos t) is parallel to the chord (dx, dy),
// i.e. a sin t dy + b cos t dx = 0: t = atan2(-b dx, a dy) + kπ; Rolle puts one of these
// inside the span.
double ellipse_sagitta(double a, double b, double ta, double tb) {
  const double x0 = a * std::cos(ta), y0 = b * std::sin(ta);
  const double dx = a * std::cos(tb) - x0, dy = b * std::sin(tb) - y0;
  const double len = std::hypot(dx, dy);
  if (!(len > 0)) return 0.0;
  const double lo = std::min(ta, tb), hi = std::max(ta, tb);
  double worst = 0.0;
  const double base = std::atan2(-b * dx, a * dy);
  for (int k = 0; k < 2; ++k) {
    // The stationary point base + kπ, moved into [lo, lo + 2π).
    double t = base + k * M_PI;
    t = lo + std::fmod(std::fmod(t - lo, 2 * M_PI) + 2 * M_PI, 2 * M_PI);
    if (t > hi) continue;
    const double px = a * std::cos(t) - x0, py = b * std::sin(t) - y0;
    worst = std::max(worst, std::abs(dx * py - dy * px) / len);
  }
  return worst;
}

// Nearest parameter on an ellipse to the in-plane point (x, y): coarse scan, then
// safeguarded Newton on D'(t) = (E(t) - q)·E'(t) inside the best scan interval.
double ellipse_parameter(const Ellipse& e, double x, double y) {
  const double a = e.major_radius, b = e.minor_radius;
  auto d2 = [&](double t) {
    const double dx = a * std::cos(t) - x, dy = b * std::sin(t) - y;
    return dx * dx + dy * dy;
  };
  constexpr int kScan = 64;
  int best = 0;
  double best_d = std::numeric_limits<double>::infinity();
  for (int i = 0; i < kScan; ++i) {
    const double d = d2(-kPi + kTwoPi * i / kScan);
    if (d < best_d) best_d = d, best = i;
  }
  const double h = kTwoPi / kScan;
  double lo = -kPi + h * (best - 1), hi = -kPi + h * (best + 1);
  auto g = [&](double t) {  // D'(t)
    return (a * std::cos(t) - x) * (-a * std::sin(t)) + (b * std::sin(t) - y) * (b * std::cos(t));
  };
  double t = -kPi + h * best;
  // The minimum of D in [lo, hi] has g(lo) <= 0 <= g(hi) unless it is at an end.
  if (!(g(lo) <= 0 && g(hi) >= 0)) return wrap_angle(t);
  for (int it = 0; it < 100; ++it) {
    const double gt = g(t);
    if (gt < 0) lo = t; else hi = t;
    const double gp = (a * a - b * b) * -std::cos(2 * t) + a * x * std::cos(t) + b * y * std::sin(t);  // D''
    double next = gp > 0 ? t - gt / gp : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - t) < 1e-15) { t = next; break; }
    t = next;
  }
  return wrap_angle(t);
}

// An ellipse's curvature radius runs from b²/a at the ends of its major axis to a²/b at
// the ends of its minor one: a uniform step fine enough for the tightest end puts
// millions of points on a flat ellipse (a = 6360, b = 0.03, met as the section of a
// nearly tangent cylinder, sampled 2^20 times and then hung the triangulation of its
// face). Instead each piece is halved until its sagitta is within the error: pieces stay
// long where the ellipse is flat and short only round its tips.
std::vector<Vec3> sample_ellipse(const Ellipse& e, double t0, double t1, double eps, std::size_t max_pieces) {
  const double a = e.major_radius, b = e.minor_radius;
  // Start from pieces that each lie in one quadrant of the ellipse (cut at its vertices,
  // t = kπ/2) and span at most π/4. Within a quadrant the tangent turns by at most 90°, so
  // the arc lies in the triangle of its chord and end tangents, whose base angles are
  // acute: every point of the arc projects inside the chord, and the distance from the
  // chord's line (ellipse_sagitta) is the distance from the polyline's segment.
  if (!(std::abs(t1 - t0) <= double(max_pieces) * (M_PI / 4))) {
    // A span of that many turns: max_pieces even pieces, as bounded as any request.
    std::vector<Vec3> out;
    for (std::size_t i = 0; i <= max_pieces; ++i) out.push_back(ellipse_at(e, t0 + (t1 - t0) * double(i) / double(max_pieces)));
    return out;
  }
  std::vector<double> cuts{t0};
  const double dir = t1 >= t0 ? 1.0 : -1.0;
  for (double k = std::floor(dir * t0 / (M_PI / 2)) + 1; k * (M_PI / 2) < dir * t1; k += 1)
    cuts.push_back(dir * k * (M_PI / 2));
  cuts.push_back(t1);
  std::vector<std::pair<double, double>> first;
  for (std::size_t c = 0; c + 1 < cuts.size(); ++c) {
    const int n = static_cast<int>(std::max(1.0, std::ceil(std::abs(cuts[c + 1] - cuts[c]) / (M_PI / 4))));
    for (int i = 0; i < n; ++i)
      first.emplace_back(cuts[c] + (cuts[c + 1] - cuts[c]) * i / n, cuts[c] + (cuts[c + 1] - cuts[c]) * (i + 1) / n);
  }
  std::vector<double> ts{t0};
  std::vector<std::pair<double, double>> stack(first.rbegin(), first.rend());  // last = next in order
  while (!stack.empty()) {
    const auto [ta, tb] = stack.back();
    stack.pop_back();
    const double tm = 0.5 * (ta + tb);
    const bool can_halve = tm != ta && tm != tb && ts.size() + stack.size() < max_pieces;
    if (can_halve && ellipse_sagitta(a, b, ta, tb) > eps) {
      stack.emplace_back(tm, tb);
      stack.emplace_back(ta, tm);
    } else {
      ts.push_back(tb);
    }
  }
  std::vector<Vec3> out;
  out.reserve(ts.size());
  for (double t : ts) out.push_back(ellipse_at(e, t));
  return out;
}

}  // namespace

Vec3 evaluate(const Curve& c, double t) {
  return std::visit(detail::Overload{[&](const std::monostate&) -> Vec3 { no_geometry(); },
                                     [&](const Line& l) -> Vec3 { return l.origin + t * l.direction; },
                                     [&](const Circle& k) -> Vec3 {
                                       return k.frame.origin + k.radius * radial(k.frame, t);
                                     },
                                     [&](const Ellipse& e) { return ellipse_at(e, t); },
                                     [&](const Polyline& p) { return polyline_at(p, t); },
                                     [&](const BSplineCurve&) {
                                       Vec3 d;
                                       return require_freeform().curve_d1(c, t, &d);
                                     }},
                    c);
}

Vec3 tangent(const Curve& c, double t) {
  return std::visit(detail::Overload{
                        [&](const std::monostate&) -> Vec3 { no_geometry(); },
                        [&](const Line& l) -> Vec3 { return l.direction.normalized(); },
                        [&](const Circle& k) -> Vec3 { return radial(k.frame, t + kPi / 2); },
                        [&](const Ellipse& e) -> Vec3 {
                          return (-e.major_radius * std::sin(t) * e.frame.x + e.minor_radius * std::cos(t) * e.frame.y())
                              .normalized();
                        },
                        [&](const Polyline& p) -> Vec3 {
                          if (p.points.size() < 2) return Vec3::UnitX();
                          const std::vector<double> s = cumulative(p);
                          std::size_t i = segment_at(s, std::clamp(t, 0.0, s.back()));
                          // Skip zero-length segments so the tangent is never NaN.
                          for (std::size_t j = i; j + 1 < p.points.size(); ++j)
                            if ((p.points[j + 1] - p.points[j]).norm() > 0) return (p.points[j + 1] - p.points[j]).normalized();
                          for (std::size_t j = i; j-- > 0;)
                            if ((p.points[j + 1] - p.points[j]).norm() > 0) return (p.points[j + 1] - p.points[j]).normalized();
                          return Vec3::UnitX();
                        },
                        [&](const BSplineCurve&) -> Vec3 {
                          Vec3 d;
                          require_freeform().curve_d1(c, t, &d);
                          return d.norm() > 0 ? Vec3(d.normalized()) : Vec3::UnitX();
                        }},
                    c);
}

CurvePoint closest_point(const Curve& c, const Vec3& p) {
  CurvePoint out;
  std::visit(detail::Overload{
                 [&](const std::monostate&) { no_geometry(); },
                 [&](const Line& l) {
                   const Vec3 d = l.direction.normalized();
                   out.t = (p - l.origin).dot(d);
                   out.point = l.origin + out.t * d;
                 },
                 [&](const Circle& k) {
                   const Vec3 q = to_local(k.frame, p);
                   out.t = std::hypot(q.x(), q.y()) > 1e-300 ? std::atan2(q.y(), q.x()) : 0.0;
                   out.point = k.frame.origin + k.radius * radial(k.frame, out.t);
                 },
                 [&](const Ellipse& e) {
                   const Vec3 q = to_local(e.frame, p);
                   out.t = ellipse_parameter(e, q.x(), q.y());
                   out.point = ellipse_at(e, out.t);
                 },
                 [&](const Polyline& pl) {
                   if (pl.points.empty()) throw std::invalid_argument("polyline has no points");
                   double best = std::numeric_limits<double>::infinity(), s = 0.0;
                   out.point = pl.points[0];
                   for (std::size_t i = 0; i + 1 < pl.points.size(); ++i) {
                     const Vec3 a = pl.points[i], ab = pl.points[i + 1] - a;
                     const double len2 = ab.squaredNorm();
                     const double w = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
                     const Vec3 x = a + w * ab;
                     const double d = (p - x).squaredNorm();
                     if (d < best) best = d, out.point = x, out.t = s + w * std::sqrt(len2);
                     s += std::sqrt(len2);
                   }
                 },
                 [&](const BSplineCurve&) {
                   const FreeformBackend& b = require_freeform();
                   out.t = b.curve_project(c, p);
                   Vec3 d;
                   out.point = b.curve_d1(c, out.t, &d);
                 }},
             c);
  out.distance = (p - out.point).norm();
  return out;
}

double parameter(const Curve& c, const Vec3& p) { return closest_point(c, p).t; }

bool is_closed(const Curve& c) {
  if (std::holds_alternative<Circle>(c) || std::holds_alternative<Ellipse>(c)) return true;
  if (const auto* b = std::get_if<BSplineCurve>(&c)) return b->periodic;
  if (const auto* p = std::get_if<Polyline>(&c))
    return p->points.size() > 2 && p->points.front() == p->points.back();
  return false;
}

double period(const Curve& c) {
  if (std::holds_alternative<Circle>(c) || std::holds_alternative<Ellipse>(c)) return kTwoPi;
  if (const auto* b = std::get_if<BSplineCurve>(&c))
    return b->periodic && b->knots.size() >= 2 ? b->knots.back() - b->knots.front() : 0.0;
  if (is_closed(c)) return curve_length(c);
  return 0.0;
}

Polyline polyline_piece(const Polyline& p, double t0, double t1) {
  Polyline out;
  out.chordal_error = p.chordal_error;
  if (p.points.size() < 2) return p;
  const std::vector<double> s = cumulative(p);
  const double len = s.back();
  const bool closed = is_closed(Curve{p});
  auto at = [&](double t) {
    if (closed && len > 0) t = std::fmod(std::fmod(t, len) + len, len);
    return evaluate(Curve{p}, t);
  };
  out.points.push_back(at(t0));
  if (t1 >= t0) {
    // The inner points met going forward, through the first point again on a closed one.
    for (int lap = 0; lap < (closed ? 2 : 1); ++lap)
      for (std::size_t i = 0; i < s.size(); ++i) {
        if (closed && lap == 1 && i == 0) continue;  // the first point is the last
        const double t = s[i] + lap * len;
        if (t > t0 && t < t1) out.points.push_back(p.points[i]);
      }
  } else {
    for (std::size_t i = s.size(); i-- > 0;)
      if (s[i] < t0 && s[i] > t1) out.points.push_back(p.points[i]);
  }
  out.points.push_back(at(t1));
  return out;
}

ParameterRange parameter_range(const Curve& c, const Vec3& p0, const Vec3& p1, double coincide_tol) {
  // A B-spline that is closed without being periodic (an edge read from a file is its
  // curve trimmed to the edge): a closed edge is the whole curve.
  if (const auto* b = std::get_if<BSplineCurve>(&c); b && !b->periodic && !b->knots.empty() &&
                                                       coincide_tol > 0 && (p0 - p1).norm() <= coincide_tol)
    return ParameterRange{b->knots.front(), b->knots.back()};
  ParameterRange r{parameter(c, p0), parameter(c, p1)};
  const double per = period(c);
  if (per > 0) {
    if ((p0 - p1).norm() <= coincide_tol) {
      r.t1 = r.t0 + per;
    } else {
      r.t1 = r.t0 + std::fmod(std::fmod(r.t1 - r.t0, per) + per, per);
      if (r.t1 <= r.t0) r.t1 += per;
    }
  }
  return r;
}

double arc_length(const Curve& c, double t0, double t1) {
  const double lo = std::min(t0, t1), hi = std::max(t0, t1);
  return std::visit(detail::Overload{
                        [&](const std::monostate&) -> double { no_geometry(); },
                        [&](const Line& l) { return (hi - lo) * l.direction.norm(); },
                        [&](const Circle& k) { return (hi - lo) * std::abs(k.radius); },
                        [&](const Ellipse& e) {
                          // Pieces of at most π/8: the speed is analytic, so 16-point
                          // Gauss-Legendre per piece is accurate to rounding for b/a > 1e-3.
                          const int pieces = std::max(1, static_cast<int>(std::ceil((hi - lo) / (kPi / 8))));
                          return detail::integrate([&](double t) { return ellipse_speed(e, t); }, lo, hi, pieces);
                        },
                        [&](const Polyline& p) {
                          // t is arc length; outside [0, L] the polyline does not continue.
                          const double len = cumulative(p).back();
                          return std::max(0.0, std::min(hi, len) - std::max(lo, 0.0));
                        },
                        [&](const BSplineCurve&) { return require_freeform().curve_length(c, lo, hi); }},
                    c);
}

double curve_length(const Curve& c) {
  return std::visit(detail::Overload{[&](const std::monostate&) -> double { no_geometry(); },
                                     [&](const Line&) { return std::numeric_limits<double>::infinity(); },
                                     [&](const Circle& k) { return kTwoPi * std::abs(k.radius); },
                                     [&](const Ellipse&) { return arc_length(c, 0.0, kTwoPi); },
                                     [&](const Polyline& p) {
                                       return p.points.empty() ? 0.0 : cumulative(p).back();
                                     },
                                     [&](const BSplineCurve&) {
                                       double t0, t1;
                                       require_freeform().curve_bounds(c, &t0, &t1);
                                       return require_freeform().curve_length(c, t0, t1);
                                     }},
                    c);
}

std::vector<Vec3> sample_curve(const Curve& c, double t0, double t1, double chordal_error) {
  std::vector<Vec3> out;
  if (const auto* p = std::get_if<Polyline>(&c)) {
    // The polyline's own vertices inside (t0, t1), in the direction of travel.
    const std::vector<double> s = cumulative(*p);
    out.push_back(evaluate(c, t0));
    if (t0 <= t1) {
      for (std::size_t i = 0; i < s.size(); ++i)
        if (s[i] > t0 && s[i] < t1) out.push_back(p->points[i]);
    } else {
      for (std::size_t i = s.size(); i-- > 0;)
        if (s[i] < t0 && s[i] > t1) out.push_back(p->points[i]);
    }
    out.push_back(evaluate(c, t1));
    return out;
  }
  if (std::holds_alternative<BSplineCurve>(c)) return require_freeform().curve_sample(c, t0, t1, chordal_error);
  if (std::holds_alternative<Line>(c)) return {evaluate(c, t0), evaluate(c, t1)};
  // At most 2^20 pieces: a full circle so sampled is within 5e-12 of its radius, finer
  // than any modelling precision we use, and a tiny error asked of a large curve cannot
  // make an unbounded allocation.
  constexpr double kMaxPieces = double(1 << 20);
  if (const auto* e = std::get_if<Ellipse>(&c)) {
    const double eps = std::max(chordal_error, 1e-15 * std::max(e->major_radius, e->minor_radius));
    return sample_ellipse(*e, t0, t1, eps, static_cast<std::size_t>(kMaxPieces));
  }
  const auto* k = std::get_if<Circle>(&c);
  if (!k) no_geometry();
  // Constant curvature: a uniform step, the one whose sagitta stays within the error
  // (a chord of length h on a circle of radius ρ has sagitta ≈ h²/(8ρ)).
  const double rho = std::abs(k->radius);
  const double eps = std::max(chordal_error, 1e-15 * rho);
  const double h = eps < rho ? std::sqrt(8.0 * eps * rho) : rho;
  const int n = static_cast<int>(std::clamp(std::ceil(std::abs(t1 - t0) * rho / h), 1.0, kMaxPieces));
  for (int i = 0; i <= n; ++i) out.push_back(evaluate(c, t0 + (t1 - t0) * i / n));
  return out;
}

}  // namespace kintsugi::geo
