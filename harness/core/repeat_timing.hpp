#pragma once
// Times a kernel by repeating it until the measurement is stable (`dabench solve --time`).
//
// A sample is one batch of calls timed as a whole; batches are made at least
// `min_sample_seconds` long (the batch size doubles until one is), so the clock's resolution and
// the timing overhead are negligible even for sub-microsecond kernels. A sample's time per call
// is its duration over the batch size. Samples are taken until the median is pinned down — its
// distribution-free 95 % confidence interval, the order statistics at n/2 ± 0.98·√n of the n
// sorted samples, lies within ±`tolerance` of it — or the budget of measured time is spent,
// and never fewer than `min_samples`. The spread reported (10th/90th percentiles) is of the
// samples: of single calls when a call lasts longer than `min_sample_seconds`, of batch means
// otherwise. The calibration batches are not samples but count towards the budget.
#include <functional>
#include <string>

namespace dabench {

struct RepeatTimingOptions {
  double budget_seconds = 2.0;       // stop once this much time was measured, stable or not
  double tolerance = 0.01;           // stable: the median's 95 % interval within ±1 % of it
  int min_samples = 10;              // samples taken before stopping, even past the budget
  double min_sample_seconds = 1e-3;  // shortest batch
  std::string validate() const;      // "" if valid, else the field and the rule it broke
};

struct RepeatTiming {
  long long calls = 0;    // timed calls in all samples (samples × batch)
  long long samples = 0;  // batches timed
  long long batch = 0;    // calls per sample
  double median = 0.0, p10 = 0.0, p90 = 0.0;  // seconds per call, over the samples
  double median_interval = 0.0;  // half-width of the median's 95 % interval, relative to the median
  bool stable = false;           // median_interval ≤ tolerance when the timing stopped
};

// `run_batch(k)` makes k calls and returns their wall time in seconds.
RepeatTiming time_repeatedly(const std::function<double(long long)>& run_batch, const RepeatTimingOptions& options);

}  // namespace dabench
