#include "algorithms/tracking/chi_square.hpp"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "harness/core/log_gamma.hpp"

namespace dabench {

namespace {

// P(a, x) by its power series (see the header), summed until a term no longer changes the sum.
double lower_gamma_regularised(double a, double x) {
  double term = 1.0 / a, sum = term;
  for (int n = 1; n < 1000 && term > 1e-17 * sum; ++n) {
    term *= x / (a + n);
    sum += term;
  }
  return std::exp(a * std::log(x) - x - log_gamma(a)) * sum;
}

}  // namespace

double chi_square_quantile(double probability, int dof) {
  if (!(probability > 0.0 && probability < 1.0) || dof < 1 || dof > 100) {
    throw std::invalid_argument(
        fmt::format("chi_square_quantile: probability {} must be in (0, 1) and dof {} in 1..100", probability, dof));
  }
  // Invariant: P(lo) < p ≤ P(hi); the χ²_n tail beyond 10n + 100 is far below 1e-16.
  double lo = 0.0, hi = 10.0 * dof + 100.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;  // adjacent doubles: further steps change nothing
    (lower_gamma_regularised(0.5 * dof, 0.5 * mid) < probability ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace dabench
