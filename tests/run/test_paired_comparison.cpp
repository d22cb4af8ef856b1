// Tests of `dabench compare`'s statistics (harness/run/paired_comparison.hpp): the signed-rank
// p-value counted by hand on small exact cases and checked against scipy.stats.wilcoxon's values
// for the normal approximation (ties, zeros, more than 50 differences), Holm's adjustment worked
// by hand, the t interval from its closed form at two degrees of freedom, and compare_runs on
// run folders written here (pairing, point order, refusals).
// tests/python/test_compare.py checks the same statistics against scipy on random pairs.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "harness/core/errors.hpp"
#include "harness/run/paired_comparison.hpp"
#include "tests/support/cli_runner.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench;
using namespace dabench::test::cli;

namespace {

// A run folder of `pairs` per point: algorithm a then b per trial, metric max_error (and time_us).
std::string write_run(const TempDir& dir, const std::string& name, const std::vector<std::vector<double>>& a,
                      const std::vector<std::vector<double>>& b, const std::string& fingerprint = "f00d") {
  std::string rows = "point,spacing,trial,seed,algorithm,status,max_error,time_us\n";
  for (std::size_t point = 0; point < a.size(); ++point) {
    for (std::size_t trial = 0; trial < a[point].size(); ++trial) {
      rows += fmt::format("{},{},{},7,a,ok,{},1\n", point, point, trial, a[point][trial]);
      rows += fmt::format("{},{},{},7,b,ok,{},2\n", point, point, trial, b[point][trial]);
    }
  }
  dir.write(name + "/trials.csv", rows);
  dir.write(name + "/meta.json", "{\"scenario\": \"grid\", \"fingerprint\": \"" + fingerprint + "\", \"seed\": 7}\n");
  return (dir.work() / name).string();
}

}  // namespace

TEST_CASE("paired comparison: exact signed-rank p-values counted by hand", "[paired_comparison]") {
  // Five positive differences: W+ = 15 is the largest of 2^5 equally likely sign patterns.
  CHECK(wilcoxon_signed_rank_p({1, 2, 3, 4, 5}) == Approx(2.0 / 32).epsilon(1e-14));
  // d = 1, −2, 3, 4, −5, 6: W+ = 14 of 21; 18 of the 64 subsets of {1..6} sum to 7 or less.
  CHECK(wilcoxon_signed_rank_p({1, -2, 3, 4, -5, 6}) == Approx(36.0 / 64).epsilon(1e-14));
  CHECK(wilcoxon_signed_rank_p({-1, -2, -3, -4, -5}) == Approx(2.0 / 32).epsilon(1e-14));  // symmetric
  CHECK(std::isnan(wilcoxon_signed_rank_p({0, 0, 0})));
  CHECK(std::isnan(wilcoxon_signed_rank_p({})));
}

TEST_CASE("paired comparison: the normal approximation equals scipy's: ties, zeros, n > 50", "[paired_comparison]") {
  // scipy.stats.wilcoxon(d, zero_method="wilcox", correction=False, method="approx").pvalue:
  // ties (|d| = 1, 2, 3 repeated) select the normal approximation with the tie-corrected variance.
  CHECK(wilcoxon_signed_rank_p({1, 1, 2, -2, 3, 3, 3, -4}) == Approx(0.35916920795382856).epsilon(1e-12));
  // Zero differences are dropped (Wilcoxon's convention) and, as scipy's method="auto" does,
  // send the test to the normal approximation: the five left are not tested exactly (0.0625).
  CHECK(wilcoxon_signed_rank_p({0, 1, 0, 2, 3, 4, 5}) == Approx(0.043114446783075355).epsilon(1e-12));
  // 60 untied differences (more than 50): every third one negative.
  std::vector<double> d;
  for (int k = 1; k <= 60; ++k) d.push_back(k % 3 != 0 ? k : -k);
  CHECK(wilcoxon_signed_rank_p(d) == Approx(0.03590012321587811).epsilon(1e-12));
}

TEST_CASE("paired comparison: t interval, shares and Holm's adjustment", "[paired_comparison]") {
  // d = 1, 2, 3: mean 2, sd 1; with two degrees of freedom the t quantile has the closed form
  // t_p = (2p − 1) / √(2p(1 − p)): t_{0.975} = 0.95 / √0.04875.
  const double t = 0.95 / std::sqrt(2.0 * 0.975 * 0.025);
  const PairedStatistics three = paired_statistics({1, 2, 3});
  CHECK(three.n == 3);
  CHECK(three.mean_diff == Approx(2.0).epsilon(1e-15));
  CHECK(three.ci_low == Approx(2.0 - t / std::sqrt(3.0)).epsilon(1e-13));
  CHECK(three.ci_high == Approx(2.0 + t / std::sqrt(3.0)).epsilon(1e-13));
  CHECK(three.a_better == 0.0);
  const PairedStatistics mixed = paired_statistics({-1, 0, 2, 3});
  CHECK(mixed.a_better == 0.25);  // A lower in one trial of four
  CHECK(mixed.ties == 0.25);
  CHECK(paired_statistics({0, 0}).wilcoxon_p == 1.0);  // nothing to test
  CHECK(paired_statistics({}).n == 0);

  // Holm: sorted 0.01 · 3, 0.03 · 2, 0.04 · 1, each at least the one before: 0.03, 0.06, 0.06.
  const std::vector<double> holm = holm_adjust({0.01, 0.04, 0.03});
  REQUIRE(holm.size() == 3);
  CHECK(holm[0] == Approx(0.03).epsilon(1e-14));
  CHECK(holm[1] == Approx(0.06).epsilon(1e-14));
  CHECK(holm[2] == Approx(0.06).epsilon(1e-14));
  // A NaN (a point without pairs) stays NaN and does not count; adjusted values stop at 1.
  const std::vector<double> with_nan = holm_adjust({0.01, std::nan(""), 0.04});
  CHECK(with_nan[0] == Approx(0.02).epsilon(1e-14));
  CHECK(std::isnan(with_nan[1]));
  CHECK(with_nan[2] == Approx(0.04).epsilon(1e-14));
  const std::vector<double> capped = holm_adjust({0.5, 0.6});
  CHECK(capped[0] == 1.0);
  CHECK(capped[1] == 1.0);
}

TEST_CASE("paired comparison: compare_runs pairs trials by point, in one run or two", "[paired_comparison]") {
  const TempDir dir;
  const std::vector<std::vector<double>> a = {{1, 2, 3, 4, 5}, {0.5, 0.25, 0.125}};
  const std::vector<std::vector<double>> b = {{2, 2, 4, 3, 7}, {0.5, 0.5, 0.5}};
  const std::string run = write_run(dir, "run", a, b);
  CompareOptions options;
  options.run_a = run;
  options.algorithms = {"a", "b"};
  options.metrics = {"max_error"};
  const Comparison one = compare_runs(options);
  REQUIRE(one.rows.size() == 2);
  CHECK(one.rows[0].point_fields == "0,0");
  CHECK(one.rows[0].stats.n == 5);
  CHECK(one.rows[0].stats.mean_diff == Approx((-1.0 + 0 - 1 + 1 - 2) / 5).epsilon(1e-14));
  CHECK(one.rows[0].stats.a_better == Approx(3.0 / 5).epsilon(1e-14));
  CHECK(one.rows[1].point_fields == "1,1");
  CHECK(one.rows[1].stats.ties == Approx(1.0 / 3).epsilon(1e-14));

  // Without --metric: the kind's error and time columns (meta.json's scenario is single-scan).
  options.metrics.clear();
  const Comparison defaults = compare_runs(options);
  REQUIRE(defaults.rows.size() == 4);
  CHECK(defaults.rows[0].metric == "max_error");  // metric by metric, each over the points
  CHECK(defaults.rows[2].metric == "time_us");
  options.metrics = {"max_error"};

  // Two runs of one plan: algorithm a in each; the differences are run A's minus run B's.
  const std::string other = write_run(dir, "other", b, a);
  options.run_b = other;
  options.algorithms = {"a"};
  const Comparison two = compare_runs(options);
  REQUIRE(two.rows.size() == 2);
  CHECK(two.rows[0].stats.mean_diff == Approx(one.rows[0].stats.mean_diff).epsilon(1e-14));

  // Refusals, one line each.
  const std::string foreign = write_run(dir, "foreign", a, b, "beef");
  options.run_b = foreign;
  CHECK_THROWS_WITH(compare_runs(options), Catch::Contains("not runs of the same plan"));
  options.run_b.clear();
  options.algorithms = {"a", "zz"};
  CHECK_THROWS_WITH(compare_runs(options), Catch::Contains("no rows of algorithm 'zz'"));
  options.algorithms = {"a", "b"};
  options.metrics = {"nope"};
  CHECK_THROWS_WITH(compare_runs(options), Catch::Contains("no metric column 'nope'"));
}

}  // namespace DABENCH_TEST_FILE
