#include "harness/core/repeat_timing.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <fmt/format.h>

#include "harness/core/summary.hpp"

namespace dabench {

namespace {

// Batches never grow past this, even if the clock reports no time at all.
constexpr long long kLargestBatch = 1LL << 30;

// Half-width of the distribution-free 95 % interval of the median of `sorted`, over the median.
double median_interval(const std::vector<double>& sorted, double median) {
  const double n = static_cast<double>(sorted.size());
  const double reach = 0.98 * std::sqrt(n);  // 1.96 standard deviations of Binomial(n, 1/2), in ranks
  const auto last = static_cast<double>(sorted.size() - 1);
  const auto low = static_cast<std::size_t>(std::clamp(std::floor(0.5 * n - reach), 0.0, last));
  const auto high = static_cast<std::size_t>(std::clamp(std::ceil(0.5 * n + reach), 0.0, last));
  if (!(median > 0.0)) return sorted[high] > sorted[low] ? std::numeric_limits<double>::infinity() : 0.0;
  return 0.5 * (sorted[high] - sorted[low]) / median;
}

}  // namespace

std::string RepeatTimingOptions::validate() const {
  if (!(budget_seconds > 0.0) || !std::isfinite(budget_seconds)) return fmt::format("budget_seconds {} must be > 0", budget_seconds);
  if (!(tolerance > 0.0) || !std::isfinite(tolerance)) return fmt::format("tolerance {} must be > 0", tolerance);
  if (min_samples < 1) return fmt::format("min_samples {} must be >= 1", min_samples);
  if (!(min_sample_seconds >= 0.0) || !std::isfinite(min_sample_seconds)) {
    return fmt::format("min_sample_seconds {} must be >= 0", min_sample_seconds);
  }
  return {};
}

RepeatTiming time_repeatedly(const std::function<double(long long)>& run_batch, const RepeatTimingOptions& options) {
  RepeatTiming timing;
  double spent = 0.0;
  long long batch = 1;
  for (;;) {  // calibration: the smallest power of two whose batch lasts min_sample_seconds
    const double seconds = run_batch(batch);
    spent += seconds;
    if (seconds >= options.min_sample_seconds || batch >= kLargestBatch) break;
    batch *= 2;
  }
  std::vector<double> per_call, sorted;
  for (;;) {
    const double seconds = run_batch(batch);
    spent += seconds;
    per_call.push_back(seconds / static_cast<double>(batch));
    if (static_cast<long long>(per_call.size()) < options.min_samples) continue;
    sorted = per_call;
    std::sort(sorted.begin(), sorted.end());
    timing.median = percentile_sorted(sorted, 0.5);
    timing.median_interval = median_interval(sorted, timing.median);
    timing.stable = timing.median_interval <= options.tolerance;
    if (timing.stable || spent >= options.budget_seconds) break;
  }
  timing.samples = static_cast<long long>(sorted.size());
  timing.batch = batch;
  timing.calls = timing.samples * batch;
  timing.p10 = percentile_sorted(sorted, 0.1);
  timing.p90 = percentile_sorted(sorted, 0.9);
  return timing;
}

}  // namespace dabench
