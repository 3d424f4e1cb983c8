// kintsugi-bench solvers: the cost of the two small least-squares solves every repair
// makes — geo::meet_point (where a vertex's faces meet) and geo::fit_surface_like (one
// surface for merged faces) — on fixed random cases, so two builds can be compared on
// one machine in one sitting (docs/benchmarks.md, "Solvers").
#include "bench/solvers_bench.h"

#include "geometry/frame.h"
#include "geometry/meet_point.h"
#include "geometry/same_geometry.h"
#include "geometry/surface.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>
#include <vector>

namespace kintsugi::bench {

using namespace kintsugi::geo;

namespace {

struct Random {
  std::mt19937_64 rng;
  std::uniform_real_distribution<double> u{-1, 1};
  explicit Random(unsigned seed) : rng(seed) {}
  double real() { return u(rng); }
  Vec3 vec(double s) { return Vec3(real(), real(), real()) * s; }
  Vec3 axis() {
    Vec3 n = vec(1);
    return n.norm() < 0.1 ? Vec3::UnitZ() : n;
  }
};

// Planes, cylinders, spheres and cones through one point, 3 or 4 of them; the guess 0.01 off.
int meet_points(int n, int repeats) {
  Random r(5);
  struct Case {
    std::vector<Surface> s;
    Vec3 guess;
  };
  std::vector<Case> cases;
  for (int i = 0; i < n; ++i) {
    const Vec3 p = r.vec(3);
    std::vector<Surface> s;
    for (int k = 0; k < 3 + (i % 2); ++k) {
      const Frame f = frame_from_axis(r.vec(3), r.axis());
      Surface x;
      switch ((i + k) % 4) {
        case 0: x = Plane{f}; break;
        case 1: x = Cylinder{f, 1.0 + std::abs(r.real())}; break;
        case 2: x = Sphere{f, 1.0 + std::abs(r.real())}; break;
        default: x = Cone{f, 1.0 + std::abs(r.real()), 0.3}; break;
      }
      const SurfacePoint c = closest_point(x, p);
      std::visit([&](auto& y) {
        if constexpr (requires { y.frame; }) y.frame.origin += p - c.point;
      }, x);
      s.push_back(x);
    }
    cases.push_back({s, p + r.vec(0.01)});
  }
  double worst = 0, moved = 0;
  int met = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (int rep = 0; rep < repeats; ++rep)
    for (const Case& c : cases) {
      const MeetPoint m = meet_point(c.s, c.guess, 1e-2, 1e-8);
      if (rep > 0) continue;
      moved += (m.point - c.guess).norm();
      if (m.status == MeetStatus::exact || m.status == MeetStatus::least_squares) met++, worst = std::max(worst, m.residual);
    }
  const double us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count() /
                    (double(repeats) * double(cases.size()));
  std::printf("meet_point: %.1f us per call; %d of %d met, largest residual %.3g, total distance moved %.10g\n", us, met,
              n, worst, moved);
  return met == n ? 0 : 1;
}

// Cylinders, spheres, cones and tori: 64 samples each with 1e-3 noise, fitted from a
// model moved 0.05 and tilted 0.03.
int surface_fits(int n) {
  Random r(7);
  struct Case {
    Surface model;
    std::vector<Vec3> pts;
  };
  std::vector<Case> cases;
  for (int i = 0; i < n; ++i) {
    const Frame f = frame_from_axis(r.vec(3), r.axis());
    Surface t;
    switch (i % 4) {
      case 0: t = Cylinder{f, 2.0 + r.real()}; break;
      case 1: t = Sphere{f, 2.0 + r.real()}; break;
      case 2: t = Cone{f, 1.5 + r.real(), 0.3 + 0.2 * r.real()}; break;
      default: t = Torus{f, 4.0 + r.real(), 1.0 + 0.3 * r.real()}; break;
    }
    std::vector<Vec3> pts;
    for (int a = 0; a < 8; ++a)
      for (int b = 0; b < 8; ++b) pts.push_back(evaluate(t, Vec2(-1.2 + 2.4 * a / 7, -1.0 + 2.0 * b / 7)) + r.vec(1e-3));
    Surface m = t;
    std::visit([&](auto& y) {
      if constexpr (requires { y.frame; })
        y.frame = frame_from_axis(y.frame.origin + r.vec(0.05), y.frame.z + r.vec(0.03), y.frame.x);
    }, m);
    cases.push_back({m, pts});
  }
  double rms = 0, worst = 0;
  int ok = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (const Case& c : cases) {
    const SurfaceFit f = fit_surface_like(c.model, c.pts);
    if (!f.converged) continue;
    ok++;
    rms += f.rms;
    worst = std::max(worst, f.max_deviation);
  }
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count() / n;
  std::printf("fit_surface_like: %.3f ms per fit; %d of %d fitted, sum of rms %.9g, largest deviation %.3g\n", ms, ok, n,
              rms, worst);
  return ok == n ? 0 : 1;
}

}  // namespace

int bench_solvers() {
  const int a = meet_points(2000, 5);
  const int b = surface_fits(400);
  return a | b;
}

}  // namespace kintsugi::bench
