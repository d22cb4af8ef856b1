// Tests of the χ² quantile (algorithms/tracking/chi_square.hpp): against 40-digit values
// (mpmath), against closed forms of the distribution function, and its domain.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "algorithms/tracking/chi_square.hpp"

namespace DABENCH_TEST_FILE {

using dabench::chi_square_quantile;

TEST_CASE("chi-square quantile: known quantiles to the stated accuracy", "[chi_square]") {
  struct Known {
    double p;
    int dof;
    double quantile;  // mpmath, 40 digits, rounded
    double relative;  // the header's stated bound
  };
  const Known known[] = {
      {0.99, 2, 9.2103403719761827361, 1e-13},    {0.971, 3, 9.0219855724861980, 1e-13},  // JDT-VB / MPTF gate
      {0.971, 4, 10.792313502777805, 1e-13},      {0.95, 1, 3.8414588206941245, 1e-13},
      {0.001, 1, 1.5707971492624898e-06, 1e-13},  {0.5, 100, 99.334129235988455754, 1e-12},
      {0.99, 100, 135.80672317102677474, 1e-12},  {0.001, 30, 11.587951045645056026, 1e-12},
      {1.0 - 1e-6, 1, 23.928126976879469057, 1e-9},
  };
  for (const Known& k : known) {
    INFO("p = " << k.p << ", dof = " << k.dof);
    CHECK(chi_square_quantile(k.p, k.dof) == Approx(k.quantile).epsilon(k.relative));
  }
}

TEST_CASE("chi-square quantile: inverts the closed-form distribution functions", "[chi_square]") {
  for (double p : {0.1, 0.5, 0.9, 0.971, 0.999}) {
    INFO("p = " << p);
    CHECK(chi_square_quantile(p, 2) == Approx(-2.0 * std::log1p(-p)).epsilon(1e-13));  // 2 dof: exponential
    // 1 dof: P(X ≤ x) = erf(√(x/2)); 3 dof: erf(√(x/2)) − √(2x/π) e^{−x/2}.
    const double x1 = chi_square_quantile(p, 1);
    CHECK(std::erf(std::sqrt(x1 / 2.0)) == Approx(p).epsilon(1e-13));
    const double x3 = chi_square_quantile(p, 3);
    CHECK(std::erf(std::sqrt(x3 / 2.0)) - std::sqrt(2.0 * x3 / std::numbers::pi) * std::exp(-x3 / 2.0) ==
          Approx(p).epsilon(1e-13));
  }
}

TEST_CASE("chi-square quantile: increases with p and with the degrees of freedom", "[chi_square]") {
  for (int dof = 1; dof < 100; dof += 11) {
    double previous = 0.0;
    for (double p = 0.05; p < 1.0; p += 0.05) {
      const double x = chi_square_quantile(p, dof);
      CHECK(x > previous);
      CHECK(chi_square_quantile(p, dof + 1) > x);
      previous = x;
    }
  }
}

TEST_CASE("chi-square quantile: outside its domain it throws", "[chi_square]") {
  CHECK_THROWS_AS(chi_square_quantile(0.0, 3), std::invalid_argument);
  CHECK_THROWS_AS(chi_square_quantile(1.0, 3), std::invalid_argument);
  CHECK_THROWS_AS(chi_square_quantile(std::nan(""), 3), std::invalid_argument);
  CHECK_THROWS_AS(chi_square_quantile(0.5, 0), std::invalid_argument);
  CHECK_THROWS_AS(chi_square_quantile(0.5, 101), std::invalid_argument);
}

}  // namespace DABENCH_TEST_FILE
