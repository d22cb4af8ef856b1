#pragma once
// `dabench compare`: paired comparison of two algorithms on the same trials. Every trial of a
// run is one problem for every algorithm, so per sweep point the pairs (A's metric, B's metric)
// of each trial give the differences d = A − B, and:
//   mean_diff ± t_{0.975, n−1} · sd / √n   the mean paired difference and its 95 % interval;
//   wilcoxon_p   the two-sided Wilcoxon signed-rank test of "d is symmetric about 0" (zero
//                differences dropped, Wilcoxon's convention): the exact null distribution when
//                at most 50 differences remain, none was zero and no two |d| tie, else the
//                normal approximation with the tie correction of the variance, without
//                continuity correction — the
//                conventions of scipy.stats.wilcoxon (zero_method="wilcox", correction=False;
//                its method="auto" picks the same, except that with ties and n ≤ 50 scipy 1.10
//                truncates a half-integer rank sum into its exact table, which we do not);
//   holm_p       Holm's step-down adjustment of wilcoxon_p over the points of one metric;
//   a_better     the share of trials with d < 0 (A lower: better for errors and times), ties
//                the share with d = 0.
// A trial where either row has no value (skipped, failed) is left out of that metric's pairs.
// trials.csv is read point by point (rows in point order, as dabench writes them): memory holds
// one point's values of the compared algorithms.
#include <optional>
#include <string>
#include <vector>

namespace dabench {

struct PairedStatistics {
  long long n = 0;          // pairs with both values
  double mean_diff = 0.0, ci_low = 0.0, ci_high = 0.0;
  double wilcoxon_p = 1.0;  // 1 when every difference is 0 (nothing to test); NaN for n = 0
  double a_better = 0.0, ties = 0.0;
};

// Statistics of the differences d = A − B.
PairedStatistics paired_statistics(const std::vector<double>& differences);
// The two-sided signed-rank p-value of d (zeros dropped); NaN when no difference is left.
double wilcoxon_signed_rank_p(const std::vector<double>& differences);
// Holm-adjusted p-values, in the input's order (NaN entries stay NaN and do not count).
std::vector<double> holm_adjust(const std::vector<double>& p_values);

struct CompareOptions {
  std::string run_a, run_b;            // run_b empty: both algorithms from run_a
  std::vector<std::string> algorithms; // A, B (one run); A (two runs: A in each)
  std::vector<std::string> metrics;    // default max_error, time_us (or the kind's)
};

struct ComparisonRow {
  std::string point_fields;  // "point,param values" as trials.csv writes them
  std::string metric;
  PairedStatistics stats;
  double holm_p = 1.0;
};

struct Comparison {
  std::string header;  // point and parameter column names
  std::string label_a, label_b;
  std::vector<ComparisonRow> rows;
};

// Reads the run folder(s) and compares; InputError (one line) for a missing run, an unknown
// algorithm or metric, two runs of different plans (fingerprint) or seeds.
Comparison compare_runs(const CompareOptions& options);
std::string comparison_csv(const Comparison& comparison);
std::string comparison_table(const Comparison& comparison);

}  // namespace dabench
