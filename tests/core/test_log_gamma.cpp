// log_gamma (harness/core/log_gamma.hpp): the thread-safe ln Γ gives std::lgamma's values bit for
// bit (the Poisson sampler and the likelihoods that use it keep their results), and known ones.
#include <catch2/catch.hpp>

#include <cmath>

#include "harness/core/log_gamma.hpp"

namespace DABENCH_TEST_FILE {

TEST_CASE("log_gamma: equals std::lgamma bit for bit, and ln (n-1)! at integers", "[core]") {
  for (double x = 0.01; x < 1e6; x *= 1.37) CHECK(dabench::log_gamma(x) == std::lgamma(x));
  CHECK(dabench::log_gamma(1.0) == 0.0);
  CHECK(dabench::log_gamma(2.0) == 0.0);
  CHECK(dabench::log_gamma(5.0) == Approx(std::log(24.0)).epsilon(1e-15));
  CHECK(dabench::log_gamma(0.5) == Approx(0.5 * std::log(3.14159265358979323846)).epsilon(1e-15));
}

}  // namespace DABENCH_TEST_FILE
