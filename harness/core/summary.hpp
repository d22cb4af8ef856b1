#pragma once
// summary.csv: one row per (point, algorithm) with, for each metric, the count of non-missing
// values, mean, standard error (sd/√count, sd with n−1), median and 5th/95th percentiles
// (linear interpolation between order statistics, "type 7"). Computed from trials.csv after
// every run, so a resumed run summarises exactly what an uninterrupted one would.
#include <cstddef>
#include <string>
#include <vector>

namespace dabench {

struct MetricSummary {
  long long count = 0;
  double mean = 0.0, standard_error = 0.0, median = 0.0, p5 = 0.0, p95 = 0.0;  // NaN if count = 0
};

// Sorts `values` (non-missing only) in place.
MetricSummary summarize(std::vector<double>& values);
double percentile_sorted(const std::vector<double>& sorted, double fraction);

// Values held in memory while summarising; more are sorted through temporary files beside
// summary.csv (harness/core/spill_sort.hpp): 16 MiB whatever the number of trials.
constexpr std::size_t kSummarySortBuffer = std::size_t{1} << 20;

// Streams trials.csv twice (counts and sums, then squares about the means, both in file order
// as summarize() adds them) and sorts the values for the quantiles with bounded memory, so its
// numbers are summarize()'s bit for bit. Memory: sort_buffer_values × 16 bytes, plus per
// (point, algorithm) its key fields and 40 bytes per metric. Throws InputError if trials.csv is
// unreadable or malformed, WriteError if a file cannot be written.
void write_summary(const std::string& trials_path, const std::string& summary_path,
                   const std::vector<std::string>& metric_columns, std::size_t sort_buffer_values = kSummarySortBuffer);

}  // namespace dabench
