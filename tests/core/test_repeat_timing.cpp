// harness/core/repeat_timing.hpp with a fake kernel whose batch times are given, so every count
// and statistic is known in advance:
//  - calibration doubles the batch until one lasts min_sample_seconds, and is not a sample;
//  - a constant kernel is stable at min_samples with zero spread;
//  - the median's interval uses the order statistics at n/2 ± 0.98·√n (a kernel whose median
//    is pinned down after a known number of samples);
//  - an unstable kernel stops once the budget is spent, and never before min_samples;
//  - validate() names the broken field.
#include <catch2/catch.hpp>

#include <vector>

#include "harness/core/repeat_timing.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench;

namespace {

// Batch b (counting from 0, calibration included) of k calls lasts k · per_call[b mod size].
struct FakeKernel {
  std::vector<double> per_call;
  long long batches = 0, calls = 0;
  double seconds = 0.0;
  double operator()(long long k) {
    const double time = static_cast<double>(k) * per_call[static_cast<std::size_t>(batches) % per_call.size()];
    ++batches;
    calls += k;
    seconds += time;
    return time;
  }
};

RepeatTiming time_fake(FakeKernel& kernel, const RepeatTimingOptions& options) {
  return time_repeatedly([&kernel](long long k) { return kernel(k); }, options);
}

}  // namespace

TEST_CASE("repeat timing: a constant kernel is stable at min_samples, batches of >= 1 ms", "[repeat_timing]") {
  FakeKernel kernel{{2e-6}};
  const RepeatTiming timing = time_fake(kernel, RepeatTimingOptions{});
  // 256 calls last 0.512 ms, 512 calls 1.024 ms: calibration runs 1 + 2 + ... + 512 calls.
  CHECK(timing.batch == 512);
  CHECK(timing.samples == 10);
  CHECK(timing.calls == 5120);
  CHECK(kernel.calls == 1023 + 5120);
  CHECK(timing.stable);
  CHECK(timing.median_interval == 0.0);
  CHECK(timing.median == Approx(2e-6).epsilon(1e-12));
  CHECK(timing.p10 == Approx(2e-6).epsilon(1e-12));
  CHECK(timing.p90 == Approx(2e-6).epsilon(1e-12));
}

TEST_CASE("repeat timing: stops as soon as the median's 95% interval is within tolerance", "[repeat_timing]") {
  // Samples (after the calibration batch) cycle 2,2,2,3,1 µs. Sorted, n = 16 holds three 1s,
  // ten 2s (indices 3..12) and three 3s; its interval indices floor(8 − 3.92) = 4 and
  // ceil(8 + 3.92) = 12 both hold 2. For n = 10..15 one end still reaches a 1 or a 3.
  FakeKernel kernel{{1e-6, 2e-6, 2e-6, 2e-6, 3e-6}};
  RepeatTimingOptions options;
  options.min_sample_seconds = 0.0;  // batches of one call
  const RepeatTiming timing = time_fake(kernel, options);
  CHECK(timing.batch == 1);
  CHECK(timing.samples == 16);
  CHECK(timing.stable);
  CHECK(timing.median == 2e-6);
  CHECK(timing.p10 == 1e-6);  // position 1.5 of 1,1,1,2,...
  CHECK(timing.p90 == 3e-6);  // position 13.5 of ...,2,3,3,3
}

TEST_CASE("repeat timing: an unstable kernel stops when the budget is spent", "[repeat_timing]") {
  // Samples alternate 3 µs, 1 µs after a 1 µs calibration call: n samples (n even) take
  // 1 + 2n µs, so a budget of 1000.5 µs ends at n = 500 with half 1s and half 3s.
  FakeKernel kernel{{1e-6, 3e-6}};
  RepeatTimingOptions options;
  options.min_sample_seconds = 0.0;
  options.budget_seconds = 1000.5e-6;
  const RepeatTiming timing = time_fake(kernel, options);
  CHECK(timing.samples == 500);
  CHECK(kernel.seconds == Approx(1001e-6).epsilon(1e-9));
  CHECK_FALSE(timing.stable);
  CHECK(timing.median == Approx(2e-6).epsilon(1e-12));
  CHECK(timing.median_interval == Approx(0.5).epsilon(1e-12));  // (3 − 1) / 2 over 2
  CHECK(timing.p10 == Approx(1e-6).epsilon(1e-12));
  CHECK(timing.p90 == Approx(3e-6).epsilon(1e-12));
}

TEST_CASE("repeat timing: a slow kernel still gets min_samples samples past the budget", "[repeat_timing]") {
  FakeKernel kernel{{0.4, 0.6}};  // one call already outlasts a 1 ms batch
  const RepeatTiming timing = time_fake(kernel, RepeatTimingOptions{});  // budget 2 s
  CHECK(timing.batch == 1);
  CHECK(timing.samples == 10);
  CHECK(kernel.batches == 11);
  CHECK(kernel.seconds == Approx(5.4));  // 0.4 calibration, then 5 × 0.6 + 5 × 0.4
  CHECK_FALSE(timing.stable);
  CHECK(timing.median == Approx(0.5));
}

TEST_CASE("repeat timing: validate names the broken field", "[repeat_timing]") {
  CHECK(RepeatTimingOptions{}.validate().empty());
  RepeatTimingOptions options;
  options.budget_seconds = 0.0;
  CHECK(options.validate().find("budget_seconds") != std::string::npos);
  options = {};
  options.tolerance = -1.0;
  CHECK(options.validate().find("tolerance") != std::string::npos);
  options = {};
  options.min_samples = 0;
  CHECK(options.validate().find("min_samples") != std::string::npos);
  options = {};
  options.min_sample_seconds = -1e-3;
  CHECK(options.validate().find("min_sample_seconds") != std::string::npos);
}

}  // namespace DABENCH_TEST_FILE
