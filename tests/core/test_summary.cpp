// harness/core/summary.hpp against hand-computed values:
//  - summarize(): count, mean, standard error sd/√n with the n−1 sd, median and 5th/95th
//    percentiles by linear interpolation between order statistics ("type 7"); a single value
//    has no standard error (NaN), no values give count 0 and NaN everywhere;
//  - write_summary(): one row per (point + parameters, algorithm) in first-appearance order,
//    the ok/skipped/failed counts, metric counts that leave missing fields out, CSV quoting of
//    keys with commas and quotes, and InputError (naming file and line) for malformed input.
// The fixture tests/data/trials_small.csv is small enough to check every number by hand.
#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <cmath>
#include <map>
#include <random>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "harness/core/errors.hpp"
#include "harness/core/summary.hpp"
#include "tests/support/cli_runner.hpp"
#include "tests/support/input_error.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench;
using namespace dabench::test::cli;
using dabench::test::input_error_message;
namespace fs = std::filesystem;

namespace {

const fs::path kData = fs::path(DABENCH_SOURCE_DIR) / "tests" / "data";

double cell(const CsvTable& table, std::size_t row, const std::string& column) {
  return to_double(table.at(row, column));
}

}  // namespace

TEST_CASE("summary: percentile_sorted interpolates between order statistics", "[summary]") {
  const std::vector<double> sorted = {1, 2, 3, 4};
  CHECK(percentile_sorted(sorted, 0.0) == 1.0);
  CHECK(percentile_sorted(sorted, 1.0) == 4.0);
  CHECK(percentile_sorted(sorted, 0.5) == Approx(2.5).epsilon(1e-15));
  CHECK(percentile_sorted(sorted, 0.05) == Approx(1.15).epsilon(1e-14));  // position 0.15
  CHECK(percentile_sorted(sorted, 0.95) == Approx(3.85).epsilon(1e-14));  // position 2.85
  CHECK(percentile_sorted(sorted, 1.0 / 3.0) == Approx(2.0).epsilon(1e-14));
  CHECK(percentile_sorted({5.0}, 0.05) == 5.0);
  CHECK(percentile_sorted({5.0}, 0.95) == 5.0);
  CHECK(std::isnan(percentile_sorted({}, 0.5)));
  // Odd count: the median is the middle value.
  CHECK(percentile_sorted({1, 10, 100}, 0.5) == 10.0);
  CHECK(percentile_sorted({1, 10, 100}, 0.75) == Approx(55.0).epsilon(1e-14));
}

TEST_CASE("summary: summarize 1 2 3 4 in any order", "[summary]") {
  std::vector<double> values = {3, 1, 4, 2};
  const MetricSummary s = summarize(values);
  CHECK(s.count == 4);
  CHECK(s.mean == 2.5);
  // sd with n−1: sqrt((2.25 + 0.25 + 0.25 + 2.25) / 3) = sqrt(5/3); se = sd / sqrt(4).
  CHECK(s.standard_error == Approx(std::sqrt(5.0 / 3.0) / 2.0).epsilon(1e-14));
  CHECK(s.median == Approx(2.5).epsilon(1e-15));
  CHECK(s.p5 == Approx(1.15).epsilon(1e-14));
  CHECK(s.p95 == Approx(3.85).epsilon(1e-14));
  CHECK(values == std::vector<double>{1, 2, 3, 4});  // sorted in place, as documented
}

TEST_CASE("summary: summarize a skewed sample", "[summary]") {
  // {0, 0, 0, 0, 10}: mean 2, sd² = (4·4 + 64)/4 = 20, se = sqrt(20/5) = 2.
  std::vector<double> values = {0, 10, 0, 0, 0};
  const MetricSummary s = summarize(values);
  CHECK(s.count == 5);
  CHECK(s.mean == 2.0);
  CHECK(s.standard_error == Approx(2.0).epsilon(1e-14));
  CHECK(s.median == 0.0);
  CHECK(s.p5 == 0.0);
  CHECK(s.p95 == Approx(8.0).epsilon(1e-14));  // position 3.8: 0 + 0.8·10
}

TEST_CASE("summary: a single value has no standard error", "[summary]") {
  std::vector<double> values = {7.25};
  const MetricSummary s = summarize(values);
  CHECK(s.count == 1);
  CHECK(s.mean == 7.25);
  CHECK(std::isnan(s.standard_error));
  CHECK(s.median == 7.25);
  CHECK(s.p5 == 7.25);
  CHECK(s.p95 == 7.25);
}

TEST_CASE("summary: constant values have zero standard error", "[summary]") {
  std::vector<double> values(10, 0.1);
  const MetricSummary s = summarize(values);
  CHECK(s.count == 10);
  CHECK(s.mean == Approx(0.1).epsilon(1e-14));
  CHECK(s.standard_error == Approx(0.0).margin(1e-16));
  CHECK(s.median == 0.1);
  CHECK(s.p5 == 0.1);
  CHECK(s.p95 == 0.1);
}

TEST_CASE("summary: no values gives count 0 and NaN statistics", "[summary]") {
  std::vector<double> values;
  const MetricSummary s = summarize(values);
  CHECK(s.count == 0);
  CHECK(std::isnan(s.mean));
  CHECK(std::isnan(s.standard_error));
  CHECK(std::isnan(s.median));
  CHECK(std::isnan(s.p5));
  CHECK(std::isnan(s.p95));
}

TEST_CASE("summary: write_summary on a hand-written trials.csv", "[summary]") {
  TempDir dir;
  const fs::path out = dir.work() / "summary.csv";
  write_summary((kData / "trials_small.csv").string(), out.string(), {"max_error", "time_us", "iterations"});
  const std::string text = read_text(out);
  const CsvTable table = parse_csv(text);

  std::vector<std::string> header = {"point", "rows", "spacing", "algorithm", "trials", "ok", "skipped", "failed"};
  for (const char* metric : {"max_error", "time_us", "iterations"}) {
    for (const char* stat : {"count", "mean", "se", "median", "p5", "p95"}) header.push_back(std::string(metric) + "_" + stat);
  }
  CHECK(table.header == header);
  REQUIRE(table.rows.size() == 4);
  const std::string spec = "bp:delta=1e-6,check_every=10";

  // Keys in first-appearance order; fields with commas quoted again.
  CHECK(table.at(0, "algorithm") == "exact");
  CHECK(table.at(1, "algorithm") == spec);
  CHECK(table.at(2, "algorithm") == "exact");
  CHECK(table.at(3, "algorithm") == spec);
  CHECK(table.at(2, "spacing") == "1,5");
  CHECK(table.at(3, "point") == "1");
  CHECK(contains(text, "\n1,2,\"1,5\",\"bp:delta=1e-6,check_every=10\",1,0,1,0,"));

  SECTION("point 0, exact: one skipped row, its max_error missing") {
    CHECK(table.at(0, "trials") == "4");
    CHECK(table.at(0, "ok") == "3");
    CHECK(table.at(0, "skipped") == "1");
    CHECK(table.at(0, "failed") == "0");
    CHECK(table.at(0, "max_error_count") == "3");
    CHECK(cell(table, 0, "max_error_mean") == 0.0);
    CHECK(cell(table, 0, "max_error_se") == 0.0);
    CHECK(cell(table, 0, "max_error_median") == 0.0);
    // time_us {10, 30, 50, 20}: mean 27.5, squares 875, se = sqrt(875/3/4).
    CHECK(table.at(0, "time_us_count") == "4");
    CHECK(cell(table, 0, "time_us_mean") == 27.5);
    CHECK(cell(table, 0, "time_us_se") == Approx(std::sqrt(875.0 / 12.0)).epsilon(1e-14));
    CHECK(cell(table, 0, "time_us_median") == Approx(25.0).epsilon(1e-14));
    CHECK(cell(table, 0, "time_us_p5") == Approx(11.5).epsilon(1e-14));
    CHECK(cell(table, 0, "time_us_p95") == Approx(47.0).epsilon(1e-14));
    // No iterations at all: count 0, empty statistics.
    CHECK(table.at(0, "iterations_count") == "0");
    for (const char* stat : {"mean", "se", "median", "p5", "p95"}) CHECK(table.at(0, std::string("iterations_") + stat).empty());
  }
  SECTION("point 0, bp: a failed row and a missing max_error") {
    CHECK(table.at(1, "trials") == "4");
    CHECK(table.at(1, "ok") == "3");
    CHECK(table.at(1, "skipped") == "0");
    CHECK(table.at(1, "failed") == "1");
    // max_error {0.25, 0.5}: mean 0.375, sd = 0.125·√2, se = 0.125.
    CHECK(table.at(1, "max_error_count") == "2");
    CHECK(cell(table, 1, "max_error_mean") == 0.375);
    CHECK(cell(table, 1, "max_error_se") == Approx(0.125).epsilon(1e-14));
    CHECK(cell(table, 1, "max_error_median") == 0.375);
    CHECK(cell(table, 1, "max_error_p5") == Approx(0.2625).epsilon(1e-14));
    CHECK(cell(table, 1, "max_error_p95") == Approx(0.4875).epsilon(1e-14));
    // time_us {4, 6, 8, 2}: the failed row's time still counts.
    CHECK(table.at(1, "time_us_count") == "4");
    CHECK(cell(table, 1, "time_us_mean") == 5.0);
    CHECK(cell(table, 1, "time_us_se") == Approx(std::sqrt(20.0 / 12.0)).epsilon(1e-14));
    CHECK(cell(table, 1, "time_us_p5") == Approx(2.3).epsilon(1e-14));
    CHECK(cell(table, 1, "time_us_p95") == Approx(7.7).epsilon(1e-14));
    // iterations {10, 20, 30}: se = 10/√3, p5 at position 0.1, p95 at 1.9.
    CHECK(table.at(1, "iterations_count") == "3");
    CHECK(cell(table, 1, "iterations_mean") == 20.0);
    CHECK(cell(table, 1, "iterations_se") == Approx(10.0 / std::sqrt(3.0)).epsilon(1e-14));
    CHECK(cell(table, 1, "iterations_median") == 20.0);
    CHECK(cell(table, 1, "iterations_p5") == Approx(11.0).epsilon(1e-14));
    CHECK(cell(table, 1, "iterations_p95") == Approx(29.0).epsilon(1e-14));
  }
  SECTION("point 1: single values have an empty standard error") {
    CHECK(table.at(2, "trials") == "1");
    CHECK(table.at(2, "ok") == "1");
    CHECK(table.at(2, "max_error_count") == "1");
    CHECK(cell(table, 2, "max_error_mean") == 0.0);
    CHECK(table.at(2, "max_error_se").empty());
    CHECK(cell(table, 2, "time_us_median") == 1.0);
    // A quoted status with quotes inside is a skip.
    CHECK(table.at(3, "skipped") == "1");
    CHECK(table.at(3, "ok") == "0");
    CHECK(table.at(3, "max_error_count") == "0");
    CHECK(table.at(3, "max_error_mean").empty());
    CHECK(table.at(3, "time_us_count") == "1");
    CHECK(cell(table, 3, "time_us_p95") == 3.0);
  }
}

TEST_CASE("summary: write_summary on a header-only trials.csv", "[summary]") {
  TempDir dir;
  const fs::path trials = dir.work() / "trials.csv";
  write_text(trials, "point,spacing,trial,seed,algorithm,status,max_error\n");
  write_summary(trials.string(), (dir.work() / "summary.csv").string(), {"max_error"});
  CHECK(read_text(dir.work() / "summary.csv") ==
        "point,spacing,algorithm,trials,ok,skipped,failed,max_error_count,max_error_mean,max_error_se,"
        "max_error_median,max_error_p5,max_error_p95\n");
}

TEST_CASE("summary: write_summary rejects malformed trials.csv naming file and line", "[summary]") {
  TempDir dir;
  const fs::path trials = dir.work() / "trials.csv";
  const fs::path summary = dir.work() / "summary.csv";
  const std::string header = "point,spacing,trial,seed,algorithm,status,max_error\n";
  const std::string good = "0,1,0,7,bp,ok,0.5\n";
  const auto error_for = [&](const std::string& text, const std::vector<std::string>& metrics) {
    write_text(trials, text);
    const std::string message =
        input_error_message([&] { write_summary(trials.string(), summary.string(), metrics); });
    CHECK(contains(message, trials.string()));
    CHECK_FALSE(fs::exists(summary));
    return message;
  };
  SECTION("a row with a missing field") {
    CHECK(contains(error_for(header + good + "0,1,1,7,bp,ok\n", {"max_error"}), ":3"));
  }
  SECTION("a row with an extra field") {
    CHECK(contains(error_for(header + good + good + "0,1,1,7,bp,ok,1,2\n", {"max_error"}), ":4"));
  }
  SECTION("an unterminated quote") {
    CHECK(contains(error_for(header + "0,1,0,7,\"bp,ok,0.5\n", {"max_error"}), ":2"));
  }
  SECTION("a metric that is not a number") {
    const std::string message = error_for(header + good + "0,1,1,7,bp,ok,abc\n", {"max_error"});
    CHECK(contains(message, ":3"));
    CHECK(contains(message, "abc"));
  }
  SECTION("a metric column that does not exist") {
    CHECK(contains(error_for(header + good, {"w_star"}), "w_star"));
  }
  SECTION("no header") {
    error_for("", {"max_error"});
  }
  SECTION("missing file") {
    const std::string message = input_error_message(
        [&] { write_summary((dir.work() / "absent.csv").string(), summary.string(), {"max_error"}); });
    CHECK(contains(message, "absent.csv"));
  }
}

// write_summary streams trials.csv and sorts through temporary files when the values exceed its
// buffer; its numbers are summarize()'s on the same values, bit for bit, whatever the buffer
// (here 100 000, 1 000 and 97 values: of the 19 098 values none, 20 or 197 sorted runs in files).
TEST_CASE("summary: the streamed summary is summarize()'s, bit for bit, for any sort buffer", "[summary]") {
  TempDir dir;
  std::mt19937_64 random(7);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::string trials = "point,spacing,trial,seed,algorithm,status,a,b\n";
  std::map<std::pair<int, int>, std::vector<std::vector<double>>> values;  // (point, algorithm) → per metric
  for (int point = 0; point < 3; ++point) {
    for (int trial = 0; trial < 1600; ++trial) {
      for (int algorithm = 0; algorithm < 2; ++algorithm) {
        auto& metrics = values[{point, algorithm}];
        metrics.resize(2);
        // Ties (rounded values), a negative zero, and a missing value now and then.
        const double a = std::round(normal(random) * 4.0) / 4.0 + (trial == 5 ? -0.0 : 0.0);
        const double b = std::exp(normal(random) + point);
        const bool missing = trial % 97 == 3;
        if (!missing) metrics[0].push_back(a);
        metrics[1].push_back(b);
        trials += fmt::format("{},{},{},7,alg{},ok,{},{}\n", point, point * 0.5, trial, algorithm,
                              missing ? std::string() : fmt::format("{}", a), b);
      }
    }
  }
  write_text(dir.work() / "trials.csv", trials);
  std::vector<std::string> expected_rows;
  for (int point = 0; point < 3; ++point) {
    for (int algorithm = 0; algorithm < 2; ++algorithm) {
      std::string row = fmt::format("{},{},alg{},1600,1600,0,0", point, point * 0.5, algorithm);
      for (std::vector<double> metric : values[{point, algorithm}]) {
        const MetricSummary s = summarize(metric);
        row += fmt::format(",{},{},{},{},{},{}", s.count, s.mean, s.standard_error, s.median, s.p5, s.p95);
      }
      expected_rows.push_back(row);
    }
  }
  for (const std::size_t buffer : {std::size_t{100000}, std::size_t{1000}, std::size_t{97}}) {
    INFO("sort buffer " << buffer);
    const fs::path out = dir.work() / "summary.csv";
    write_summary((dir.work() / "trials.csv").string(), out.string(), {"a", "b"}, buffer);
    const auto lines = split_lines(read_text(out));
    REQUIRE(lines.size() == expected_rows.size() + 1);
    for (std::size_t r = 0; r < expected_rows.size(); ++r) CHECK(lines[r + 1] == expected_rows[r]);
    std::size_t files = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir.work())) ++files;
    CHECK(files == 2);  // trials.csv and summary.csv: the sort's files are gone
  }
}

}  // namespace DABENCH_TEST_FILE
