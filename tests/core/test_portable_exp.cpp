// Tests of portable_exp (harness/core/portable_exp.hpp) against std::exp: relative error over
// the whole normal range, the subnormal range, and the special values.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>

#include "harness/core/portable_exp.hpp"

namespace DABENCH_TEST_FILE {

using dabench::portable_exp;

namespace {

double relative_error(double x) {
  const double reference = std::exp(x);
  return std::abs(portable_exp(x) - reference) / reference;
}

}  // namespace

TEST_CASE("portable_exp: within 2 ulp of std::exp wherever e^x is a normal number", "[portable_exp]") {
  // Both are within about 1 ulp of e^x, so they differ by at most ~2 ulp = 4.4e-16.
  constexpr double kTolerance = 4.5e-16;
  std::mt19937_64 engine(15);
  double worst = 0.0;
  std::uniform_real_distribution<double> wide(-708.3, 709.7), unit(-1.0, 1.0);
  for (int i = 0; i < 200000; ++i) {
    worst = std::max(worst, relative_error(wide(engine)));
    worst = std::max(worst, relative_error(unit(engine)));
    worst = std::max(worst, relative_error(1e-10 * unit(engine)));
  }
  // Around the reduction's half-integer multiples of ln 2 (where n changes) and the range ends.
  for (int n = -1021; n <= 1023; ++n) {
    for (const double offset : {-1e-12, 0.0, 1e-12}) worst = std::max(worst, relative_error((n + 0.5) * std::log(2.0) + offset));
  }
  for (const double x : {-708.39, -700.0, -1.0, -1e-300, 0.5, 1.0, 2.0, 100.0, 709.78}) worst = std::max(worst, relative_error(x));
  CHECK(worst < kTolerance);
  CHECK(worst > 0.0);  // the comparison sees the last bits
  CHECK(portable_exp(0.0) == 1.0);
  CHECK(portable_exp(-0.0) == 1.0);
  CHECK(portable_exp(1.0) == Approx(2.718281828459045).epsilon(1e-15));
}

TEST_CASE("portable_exp: subnormal results, underflow, overflow, infinities and NaN", "[portable_exp]") {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  const double step = std::numeric_limits<double>::denorm_min();
  // Subnormal range: within one subnormal step of std::exp.
  for (double x = -745.1; x < -708.0; x += 0.0173) CHECK(std::abs(portable_exp(x) - std::exp(x)) <= step);
  CHECK(portable_exp(-745.0) > 0.0);
  CHECK(portable_exp(-745.2) == 0.0);
  CHECK(portable_exp(-1000.0) == 0.0);
  CHECK(portable_exp(-1e300) == 0.0);
  CHECK(portable_exp(-kInfinity) == 0.0);
  CHECK(portable_exp(709.7) == Approx(std::exp(709.7)).epsilon(1e-15));
  CHECK(portable_exp(709.79) == kInfinity);
  CHECK(portable_exp(1e300) == kInfinity);
  CHECK(portable_exp(kInfinity) == kInfinity);
  CHECK(std::isnan(portable_exp(std::numeric_limits<double>::quiet_NaN())));
}

}  // namespace DABENCH_TEST_FILE
