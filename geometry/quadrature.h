// Gauss-Legendre rules on [-1, 1], computed once (Newton on the Legendre recurrence),
// used for ellipse arc length and other smooth 1D integrals.
#pragma once

#include <vector>

namespace kintsugi::geo::detail {

struct GaussRule {
  std::vector<double> nodes, weights;
};
// The n-point rule (exact for polynomials of degree 2n - 1).
const GaussRule& gauss_legendre(int n);

// ∫_a^b f(x) dx by composite n-point Gauss-Legendre on `pieces` equal sub-intervals.
template <class F>
double integrate(F&& f, double a, double b, int pieces, int n = 16) {
  const GaussRule& g = gauss_legendre(n);
  const double h = (b - a) / pieces;
  double sum = 0.0;
  for (int k = 0; k < pieces; ++k) {
    const double mid = a + (k + 0.5) * h;
    for (std::size_t i = 0; i < g.nodes.size(); ++i) sum += g.weights[i] * f(mid + 0.5 * h * g.nodes[i]);
  }
  return 0.5 * h * sum;
}

}  // namespace kintsugi::geo::detail
