#include "geometry/parameter_domain.h"

#include "geometry/frame.h"
#include "geometry/freeform.h"
#include "geometry/surface.h"

#include <algorithm>
#include <cmath>
#include <optional>

namespace kintsugi::geo {

namespace {

// A loop in parameter space: `pts` unwrapped continuously; the loop closes onto
// pts[0] + 2π·(wu, wv).
struct Unwrapped {
  std::vector<Vec2> pts;
  int wu = 0, wv = 0;
};

// v of the pole / apex a point sits on, if it sits on one.
std::optional<double> pole_at(const Surface& s, const Vec3& p) {
  if (const auto* sp = std::get_if<Sphere>(&s)) {
    const Vec3 l = to_local(sp->frame, p);
    if (std::hypot(l.x(), l.y()) <= 1e-9 * sp->radius) return l.z() >= 0 ? kPi / 2 : -kPi / 2;
  } else if (const auto* c = std::get_if<Cone>(&s)) {
    const Vec3 l = to_local(c->frame, p);
    if ((p - apex(*c)).norm() <= 1e-9 * std::max(c->radius, l.norm())) return apex_parameter(*c);
  }
  return std::nullopt;
}

// Which way along the pole line the boundary runs so that the region stays on its left
// (+1: increasing u). At a sphere's north pole the region lies below the line, so the
// boundary runs towards -u; at the south pole towards +u. A cone's region lies on the
// side of the apex line where the radius grows with t... on either nappe, which gives
// the same sense sign(sin α) (the far nappe's parameter orientation is reversed).
int pole_turn(const Surface& s, double v_pole, bool reversed) {
  int turn = 1;
  if (std::holds_alternative<Sphere>(s)) turn = v_pole > 0 ? -1 : 1;
  if (const auto* c = std::get_if<Cone>(&s)) turn = std::sin(c->half_angle) > 0 ? 1 : -1;
  return reversed ? -turn : turn;
}

std::optional<Unwrapped> unwrap(const Surface& s, std::vector<Vec3> loop, bool reversed, std::string& problem) {
  if (loop.size() >= 2 && loop.front() == loop.back()) loop.pop_back();
  const std::size_t n = loop.size();
  if (n < 2) {
    problem = "a boundary loop has fewer than 2 distinct points";
    return std::nullopt;
  }
  std::vector<Vec2> uv(n);
  std::vector<std::optional<double>> pole(n);
  for (std::size_t i = 0; i < n; ++i) {
    uv[i] = parameters(s, loop[i]);
    pole[i] = pole_at(s, loop[i]);
  }
  std::size_t k0 = 0;
  while (k0 < n && pole[k0]) ++k0;
  if (k0 == n) {
    problem = "a boundary loop lies entirely at a pole or apex";
    return std::nullopt;
  }
  const bool pu = periodic_u(s), pv = periodic_v(s);
  Unwrapped out;
  out.pts.push_back(uv[k0]);
  Vec2 at = uv[k0];
  // The pole the loop is passing through, if any (a flag rather than std::optional:
  // g++ 12 warns spuriously about the optional's storage here).
  bool at_pole = false;
  double pole_v = 0.0;
  for (std::size_t step = 1; step <= n; ++step) {
    const std::size_t i = (k0 + step) % n;
    if (pole[i]) {
      at_pole = true;
      pole_v = *pole[i];
      continue;
    }
    double du = pu ? wrap_angle(uv[i].x() - at.x()) : uv[i].x() - at.x();
    const double dv = pv ? wrap_angle(uv[i].y() - at.y()) : uv[i].y() - at.y();
    if (at_pole) {
      // Through the pole: turn by the angle that keeps the region on the left.
      if (pole_turn(s, pole_v, reversed) > 0) {
        while (du <= 1e-9) du += kTwoPi;
        while (du > kTwoPi + 1e-9) du -= kTwoPi;
      } else {
        while (du >= -1e-9) du -= kTwoPi;
        while (du < -kTwoPi - 1e-9) du += kTwoPi;
      }
      out.pts.push_back(Vec2(at.x(), pole_v));
      out.pts.push_back(Vec2(at.x() + du, pole_v));
      at_pole = false;
    }
    const Vec2 next = at + Vec2(du, dv);
    if (step == n) {
      out.wu = static_cast<int>(std::lround((next.x() - out.pts[0].x()) / kTwoPi));
      out.wv = static_cast<int>(std::lround((next.y() - out.pts[0].y()) / kTwoPi));
    } else {
      out.pts.push_back(next);
      at = next;
    }
  }
  return out;
}

double signed_area(const std::vector<Vec2>& p) {
  double a = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec2& q = p[i];
    const Vec2& r = p[(i + 1) % p.size()];
    a += q.x() * r.y() - q.y() * r.x();
  }
  return 0.5 * a;
}

bool inside(const std::vector<Vec2>& poly, const Vec2& p) {
  bool in = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Vec2 &a = poly[i], &b = poly[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      in = !in;
  }
  return in;
}

Vec2 centroid(const std::vector<Vec2>& p) {
  Vec2 c = Vec2::Zero();
  for (const Vec2& q : p) c += q;
  return c / double(p.size());
}

// The loop as an open path of n + 1 points from pts[s] round to pts[s] + 2π·w.
std::vector<Vec2> path_from(const Unwrapped& u, std::size_t s) {
  const Vec2 period(kTwoPi * u.wu, kTwoPi * u.wv);
  std::vector<Vec2> out;
  for (std::size_t i = s; i < u.pts.size(); ++i) out.push_back(u.pts[i]);
  for (std::size_t i = 0; i <= s; ++i) out.push_back(u.pts[i] + period);
  return out;
}

Unwrapped reversed_loop(Unwrapped u) {
  std::reverse(u.pts.begin(), u.pts.end());
  u.wu = -u.wu;
  u.wv = -u.wv;
  return u;
}

void shift(std::vector<Vec2>& p, const Vec2& d) {
  for (Vec2& q : p) q += d;
}

// Index of the point whose coordinate k is nearest the angle c (mod 2π).
std::size_t nearest_index(const std::vector<Vec2>& p, int k, double c) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < p.size(); ++i)
    if (std::abs(wrap_angle(p[i][k] - c)) < std::abs(wrap_angle(p[best][k] - c))) best = i;
  return best;
}

// A cut angle in coordinate k as far as possible from every hole.
double cut_angle(const std::vector<Unwrapped>& holes, int k, double fallback) {
  if (holes.empty()) return fallback;
  double best = fallback, best_gap = -1.0;
  for (int i = 0; i < 128; ++i) {
    const double c = -kPi + kTwoPi * i / 128;
    double gap = kPi;
    for (const Unwrapped& h : holes)
      for (const Vec2& q : h.pts) gap = std::min(gap, std::abs(wrap_angle(q[k] - c)));
    if (gap > best_gap) best_gap = gap, best = c;
  }
  return best;
}

}  // namespace

ParameterDomain parameter_domain(const Surface& s, const std::vector<std::vector<Vec3>>& loops, bool reversed) {
  ParameterDomain d;
  if (const std::string p = surface_problem(s); !p.empty()) {
    d.problem = p;
    return d;
  }
  if (is_freeform(s)) require_freeform().surface_forget(s);
  const bool closed = std::holds_alternative<Sphere>(s) || std::holds_alternative<Torus>(s);
  auto full_rectangle = [&](const Vec2& c) {
    const double hv = std::holds_alternative<Sphere>(s) ? kPi / 2 : kPi;
    const double cv = std::holds_alternative<Sphere>(s) ? 0.0 : c.y();
    return std::vector<Vec2>{Vec2(c.x() - kPi, cv - hv), Vec2(c.x() + kPi, cv - hv), Vec2(c.x() + kPi, cv + hv),
                             Vec2(c.x() - kPi, cv + hv)};
  };
  if (loops.empty()) {
    if (!closed) {
      d.problem = std::string("an unbounded ") + surface_type_name(s) + " needs at least one boundary loop";
      return d;
    }
    d.polygons.push_back(full_rectangle(Vec2::Zero()));
    return d;
  }
  std::vector<Unwrapped> winding, plain;
  for (const auto& loop : loops) {
    auto u = unwrap(s, loop, reversed, d.problem);
    if (!u) return d;
    if (u->wu != 0 && u->wv != 0) {
      d.problem = "a boundary loop winds around both directions of the torus (unsupported)";
      return d;
    }
    if (std::abs(u->wu) > 1 || std::abs(u->wv) > 1) {
      d.problem = "a boundary loop winds around more than once";
      return d;
    }
    (u->wu != 0 || u->wv != 0 ? winding : plain).push_back(std::move(*u));
  }
  std::vector<Unwrapped> holes;
  if (winding.empty()) {
    const Unwrapped& outer = plain.front();
    holes.assign(plain.begin() + 1, plain.end());
    // Orientation seen from the normal: the parameter plane is positively oriented
    // except on a cone's far nappe (negative radius).
    double sense = reversed ? -1.0 : 1.0;
    if (const auto* c = std::get_if<Cone>(&s))
      if (c->radius + outer.pts[0].y() * std::sin(c->half_angle) < 0) sense = -sense;
    if (closed && sense * signed_area(outer.pts) < 0) {
      d.polygons.push_back(full_rectangle(centroid(outer.pts)));
      holes.insert(holes.begin(), outer);  // the complement of the loop's inside
    } else {
      d.polygons.push_back(outer.pts);
    }
  } else {
    const int k = winding[0].wu != 0 ? 0 : 1;  // the coordinate the loops wind in
    for (const Unwrapped& w : winding)
      if ((k == 0 ? w.wu : w.wv) == 0) {
        d.problem = "boundary loops wind around the torus in different directions (unsupported)";
        return d;
      }
    holes = plain;
    const double c = cut_angle(holes, k, winding[0].pts[0][k]);
    const Vec2 e = k == 0 ? Vec2(kTwoPi, 0) : Vec2(0, kTwoPi);
    Unwrapped a = (k == 0 ? winding[0].wu : winding[0].wv) > 0 ? winding[0] : reversed_loop(winding[0]);
    std::vector<Vec2> pa = path_from(a, nearest_index(a.pts, k, c));
    shift(pa, e * std::round((c - pa.front()[k]) / kTwoPi));
    if (winding.size() == 1) {
      const bool cap = std::holds_alternative<Sphere>(s) || std::holds_alternative<Cone>(s);
      if (!cap || k != 0) {
        d.problem = std::string("a single loop winding around a ") + surface_type_name(s) +
                    " does not bound a region (a band needs two)";
        return d;
      }
      double vp = 0.0;
      if (const auto* cone = std::get_if<Cone>(&s)) {
        vp = apex_parameter(*cone);
      } else {
        // The pole on the region's side: left of the direction of travel.
        const bool eastwards = winding[0].wu > 0;
        vp = eastwards != reversed ? kPi / 2 : -kPi / 2;
      }
      pa.push_back(Vec2(pa.back().x(), vp));
      pa.push_back(Vec2(pa.front().x(), vp));
      d.polygons.push_back(pa);
    } else if (winding.size() == 2) {
      // Band: A forwards, B backwards, joined by two copies of one seam segment.
      Unwrapped b = (k == 0 ? winding[1].wu : winding[1].wv) < 0 ? winding[1] : reversed_loop(winding[1]);
      std::vector<Vec2> pb = path_from(b, nearest_index(b.pts, k, c));
      shift(pb, e * std::round((pa.back()[k] - pb.front()[k]) / kTwoPi));
      pa.insert(pa.end(), pb.begin(), pb.end());
      d.polygons.push_back(pa);
    } else {
      d.problem = std::to_string(winding.size()) + " loops wind around the " + surface_type_name(s) +
                  ": at most two (a band) are supported";
      return d;
    }
  }
  // Holes: lift each into the outer polygon by whole periods.
  // A copy: pushing holes into d.polygons below may reallocate it.
  const std::vector<Vec2> outer = d.polygons.front();
  for (Unwrapped h : holes) {
    bool placed = false;
    for (int i = -2; i <= 2 && !placed; ++i)
      for (int j = -2; j <= 2 && !placed; ++j) {
        if ((i != 0 && !periodic_u(s)) || (j != 0 && !periodic_v(s))) continue;
        std::vector<Vec2> p = h.pts;
        shift(p, Vec2(kTwoPi * i, kTwoPi * j));
        if (inside(outer, centroid(p))) {
          d.polygons.push_back(std::move(p));
          placed = true;
        }
      }
    if (!placed) {
      d.problem = "an inner loop does not lie inside the outer boundary";
      return d;
    }
  }
  return d;
}

}  // namespace kintsugi::geo
