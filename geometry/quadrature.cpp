#include "geometry/quadrature.h"

#include <cmath>
#include <map>
#include <mutex>
#include <numbers>

namespace kintsugi::geo::detail {

namespace {
GaussRule make_rule(int n) {
  GaussRule r;
  r.nodes.resize(n);
  r.weights.resize(n);
  for (int i = 0; i < n; ++i) {
    double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));  // Tricomi's initial guess
    double dp = 0.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (x * p1 - p0) / (x * x - 1.0);
      const double dx = p1 / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    r.nodes[i] = x;
    r.weights[i] = 2.0 / ((1.0 - x * x) * dp * dp);
  }
  return r;
}
}  // namespace

const GaussRule& gauss_legendre(int n) {
  static std::mutex mutex;
  static std::map<int, GaussRule> rules;
  std::lock_guard<std::mutex> lock(mutex);
  auto it = rules.find(n);
  if (it == rules.end()) it = rules.emplace(n, make_rule(n)).first;
  return it->second;  // std::map nodes are stable: the reference stays valid
}

}  // namespace kintsugi::geo::detail
