// docs/extending.md, "Adding a kind": the example kind of tests/support/example_kind.cpp (one file: problem,
// estimators, scenario, execution, descriptor), built into the program dabench_example_kind, runs
// through `dabench list`, `run` (any thread count, the same rows), `run --shard` and `merge`
// (the whole run's rows), `compare` (the kind's error and time columns by default) and `schedule`
// (the kind's time column) — while the dabench program, which does not link the file, knows no
// such scenario. Its numbers are checked against what they must be: error = |estimate − truth|
// row by row, the residuals of the mean summing to zero and those of the median balanced, and the
// mean's error without clutter near its closed form σ·sqrt(2 / (π m)).
#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "tests/support/cli_runner.hpp"
#include "tests/support/run_files.hpp"

#ifndef DABENCH_EXAMPLE_KIND_BINARY
#error "DABENCH_EXAMPLE_KIND_BINARY (path of the dabench_example_kind program) must be defined by the build"
#endif

namespace DABENCH_TEST_FILE {

using namespace dabench::test::cli;

namespace {

const std::string kProgram = DABENCH_EXAMPLE_KIND_BINARY;

const char* const kExperiment =
    "scenario = example-line\n"
    "trials = 40\n"
    "seed = 5\n"
    "algorithm = example-mean\n"
    "algorithm = example-mean:trim=0.25\n"
    "algorithm = example-median\n"
    "[scenario]\n"
    "measurements = 9\n"
    "[sweep]\n"
    "clutter = 0, 0.3\n";

CliResult run_example(const TempDir& dir, const std::vector<std::string>& args) {
  CliResult result = run_dabench(dir, args, kProgram);
  INFO(result.err);
  REQUIRE(result.status == 0);
  return result;
}

}  // namespace

TEST_CASE("adding a kind: the example kind runs through run, merge, compare and schedule", "[run][kind]") {
  TempDir dir;
  dir.write("line.ini", kExperiment);

  const CliResult list = run_example(dir, {"list"});
  CHECK(contains(list.out, "Location estimators (the example kind):\n  example-mean "));
  CHECK(contains(list.out, "Location scenarios (the example kind):\n  example-line "));
  const CliResult unknown = run_dabench(dir, {"run", "line.ini", "--out", "plain"});  // the dabench program
  CHECK(unknown.status == 2);
  CHECK(contains(unknown.err, "unknown scenario 'example-line'"));

  run_example(dir, {"run", "line.ini", "--out", "whole", "--threads", "3"});
  const CsvTable trials = parse_csv(dir.read("whole/trials.csv"));
  CHECK(trials.header == std::vector<std::string>{"point", "measurements", "clutter", "sigma", "length", "trial", "seed",
                                                  "algorithm", "status", "n_measurements", "truth", "estimate", "error",
                                                  "time_us"});
  REQUIRE(trials.rows.size() == 2 * 40 * 3);
  const CsvTable residuals = parse_csv(dir.read("whole/residuals.csv"));
  REQUIRE(residuals.rows.size() == 2 * 40 * 3 * 9);

  // Row by row: error = |estimate − truth|; the item's 9 residuals z_j − x̂ follow in the same
  // order (point, trial, algorithm); the mean's sum to zero, the median's are 4 below, 4 above, 1 zero.
  std::map<std::string, std::vector<double>> clutter_free_errors;
  for (std::size_t r = 0; r < trials.rows.size(); ++r) {
    INFO("row " << r);
    REQUIRE(trials.at(r, "status") == "ok");
    const double estimate = number(trials, r, "estimate"), error = number(trials, r, "error");
    CHECK(error == std::abs(estimate - number(trials, r, "truth")));
    const std::string algorithm = trials.at(r, "algorithm");
    double sum = 0.0;
    int below = 0, above = 0;
    for (std::size_t j = 0; j < 9; ++j) {
      const std::size_t at = 9 * r + j;
      REQUIRE(residuals.at(at, "trial") == trials.at(r, "trial"));
      REQUIRE(residuals.at(at, "algorithm") == algorithm);
      CHECK(residuals.at(at, "measurement") == std::to_string(j + 1));
      const double residual = number(residuals, at, "residual");
      sum += residual;
      below += residual < 0.0;
      above += residual > 0.0;
    }
    if (algorithm == "example-mean") CHECK(std::abs(sum) < 1e-11);
    if (algorithm == "example-median") CHECK((below == 4 && above == 4));
    if (trials.at(r, "clutter") == "0") clutter_free_errors[algorithm].push_back(error);
  }
  // E|x̄ − x| = σ sqrt(2 / (π m)) without clutter; its SE over 40 trials is σ sqrt((1 − 2/π) / m / 40).
  const std::vector<double>& mean_errors = clutter_free_errors["example-mean"];
  REQUIRE(mean_errors.size() == 40);
  double mean_error = 0.0;
  for (const double e : mean_errors) mean_error += e / 40.0;
  const double expected = std::sqrt(2.0 / (M_PI * 9.0)), se = std::sqrt((1.0 - 2.0 / M_PI) / 9.0 / 40.0);
  CHECK(std::abs(mean_error - expected) < 4.0 * se);

  // Any thread count, the same rows; shards merged, the same rows again.
  run_example(dir, {"run", "line.ini", "--out", "one", "--threads", "1"});
  check_same(without_timing(dir, "whole/trials.csv"), without_timing(dir, "one/trials.csv"));
  CHECK(dir.read("one/residuals.csv") == dir.read("whole/residuals.csv"));
  run_example(dir, {"run", "line.ini", "--shard", "1/2", "--out", "s1"});
  run_example(dir, {"run", "line.ini", "--shard", "2/2", "--out", "s2", "--threads", "2"});
  run_example(dir, {"merge", "merged", "s1", "s2"});
  check_same(without_timing(dir, "whole/trials.csv"), without_timing(dir, "merged/trials.csv"));
  check_same(without_timing(dir, "whole/summary.csv"), without_timing(dir, "merged/summary.csv"));
  CHECK(dir.read("merged/residuals.csv") == dir.read("whole/residuals.csv"));

  // compare: the kind's error and time columns; with 30 % clutter the median beats the mean.
  const CliResult compared = run_example(dir, {"compare", "merged", "--algorithms", "example-mean,example-median"});
  const std::vector<std::string> lines = split_lines(compared.out);
  REQUIRE(lines.size() == 6);  // title, header, error at 2 points, time_us at 2 points
  CHECK(contains(lines[2], "0 clutter=0") & contains(lines[2], " error "));
  CHECK(contains(lines[5], "1 clutter=0.3") & contains(lines[5], " time_us "));
  const CliResult error_only =
      run_example(dir, {"compare", "merged", "--algorithms", "example-mean,example-median", "--metric", "error", "--format", "csv"});
  const CsvTable comparison = parse_csv(error_only.out);
  REQUIRE(comparison.rows.size() == 2);
  CHECK(number(comparison, 1, "mean_diff") > 0.0);

  // schedule: one unit per (item, estimator), each costing its row's time_us.
  const CliResult scheduled = run_example(dir, {"schedule", "whole", "--workers", "1,4", "--format", "csv"});
  const CsvTable schedule = parse_csv(scheduled.out);
  REQUIRE(schedule.rows.size() == 2);
  CHECK(schedule.at(0, "units") == "240");
  double total = 0.0;
  for (std::size_t r = 0; r < trials.rows.size(); ++r) total += 1e-6 * number(trials, r, "time_us");
  CHECK(number(schedule, 0, "total_s") == Approx(total).epsilon(1e-12));
  CHECK(number(schedule, 0, "wall_s") == Approx(total).epsilon(1e-12));
}

TEST_CASE("adding a kind: the example kind's bad input is one error line", "[run][kind]") {
  TempDir dir;
  for (const auto& [text, mention] : std::vector<std::pair<std::string, std::string>>{
           {"scenario = example-line\ntrials = 2\nalgorithm = example-mode\n", "unknown location estimator 'example-mode'"},
           {"scenario = example-line\ntrials = 2\nalgorithm = example-mean:trim=0.5\n", "trim must be in [0, 0.5)"},
           {"scenario = example-line\ntrials = 2\nalgorithm = example-mean\n[scenario]\nclutter = 2\n", "clutter must be in [0, 1]"},
           {"scenario = example-line\ntrials = 2\nreference = example-median\nalgorithm = example-mean\n", "reference"}}) {
    dir.write("bad.ini", text);
    const CliResult result = run_dabench(dir, {"run", "bad.ini", "--out", "B"}, kProgram);
    INFO(text << "\n" << result.err);
    CHECK(result.status == 2);
    CHECK(contains(result.err, mention));
    CHECK(std::count(result.err.begin(), result.err.end(), '\n') == 1);
    CHECK_FALSE(dir.exists("B"));
  }
}

}  // namespace DABENCH_TEST_FILE
