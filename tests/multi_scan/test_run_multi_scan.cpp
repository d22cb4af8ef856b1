// End-to-end `dabench run` on a tiny multi-scan experiment (bearings + jpda-bp):
//  - trials.csv: one row per (point, trial, algorithm) with the multi-scan metric columns;
//    targets.csv: one row per (point, trial, algorithm, target), consistent with trials.csv's
//    n_targets, mean_hpd, max_hpd and mean_entropy; summary.csv one row per (point, algorithm);
//  - determinism: 1 vs 2 threads give identical files (time_us aside);
//  - resume: after a hard kill that leaves trials.csv and targets.csv cut anywhere (targets.csv
//    at least as far as trials.csv, the writer's order), --resume ends with the files of an
//    uninterrupted run; --resume on a finished run changes nothing;
//  - draws without targets are skipped:no_targets; configuration errors are one clear line.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "tests/support/cli_contract.hpp"
#include "tests/support/cli_runner.hpp"
#include "tests/support/run_files.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench::test::cli;
namespace fs = std::filesystem;

namespace {

// Two sweep points (4 and 12 scans), 12 trials, two jpda-bp variants (one SPEC with a comma).
const char* const kTiny =
    "scenario = bearings\n"
    "trials = 12\n"
    "seed = 3\n"
    "algorithm = jpda-bp\n"
    "algorithm = jpda-bp:delta=1e-6,max_iterations=500\n"
    "[scenario]\n"
    "particles = 300\n"
    "mean_targets = 3\n"
    "[sweep]\n"
    "scans_per_sensor = 1, 3\n";
constexpr int kTrials = 12;

// Where item `item`'s rows start in a file of this test's runs.
std::size_t item_offset(const std::string& text, long long item) { return offset_of_item(text, item, kTrials); }
constexpr int kPoints = 2;
constexpr int kSpecs = 2;

}  // namespace

TEST_CASE("run multi-scan: trials.csv and targets.csv rows and metrics agree", "[run][multi_scan]") {
  TempDir dir;
  dir.write("tiny.ini", kTiny);
  run_ok(dir, {"run", "tiny.ini", "--threads", "2", "--out", "A"});
  const CsvTable trials = parse_csv(dir.read("A/trials.csv"));
  const CsvTable targets = parse_csv(dir.read("A/targets.csv"));
  for (const char* column : {"point", "particles", "scans_per_sensor", "trial", "seed", "algorithm", "status", "n_targets",
                             "n_scans", "n_measurements", "mean_hpd", "max_hpd", "mean_entropy", "time_us",
                             "iterations", "converged", "line_search_steps", "residual", "inner_residual"}) {
    CHECK(trials.find_column(column).has_value());
  }
  REQUIRE(trials.rows.size() == static_cast<std::size_t>(kPoints * kTrials * kSpecs));
  CHECK(targets.header.back() == "hpd_likelihood");
  // targets.csv: per (point, trial, algorithm) n_targets rows, whose mean/max match trials.csv.
  std::map<std::string, std::vector<std::pair<double, double>>> by_key;
  for (std::size_t r = 0; r < targets.rows.size(); ++r) {
    const std::string key = targets.at(r, "point") + "/" + targets.at(r, "trial") + "/" + targets.at(r, "algorithm");
    by_key[key].push_back({to_double(targets.at(r, "hpd")), to_double(targets.at(r, "entropy"))});
    CHECK(std::stoi(targets.at(r, "target")) == static_cast<int>(by_key[key].size()));
    const double by_likelihood = to_double(targets.at(r, "hpd_likelihood"));
    CHECK(by_likelihood >= 0.0);
    CHECK(by_likelihood <= 1.0);
  }
  std::size_t target_rows = 0;
  for (std::size_t r = 0; r < trials.rows.size(); ++r) {
    const std::string key = trials.at(r, "point") + "/" + trials.at(r, "trial") + "/" + trials.at(r, "algorithm");
    const int n = std::stoi(trials.at(r, "n_targets"));
    CHECK(trials.at(r, "n_scans") == (trials.at(r, "scans_per_sensor") == "1" ? "4" : "12"));
    target_rows += static_cast<std::size_t>(n);
    if (n == 0) {
      CHECK(trials.at(r, "status") == "skipped:no_targets");
      CHECK(by_key.count(key) == 0);
      continue;
    }
    REQUIRE(trials.at(r, "status") == "ok");
    const auto& values = by_key.at(key);
    REQUIRE(values.size() == static_cast<std::size_t>(n));
    double hpd = 0.0, max_hpd = 0.0, entropy = 0.0;
    for (const auto& [h, e] : values) {
      CHECK(h >= 0.0);
      CHECK(h <= 1.0);
      hpd += h / n;
      max_hpd = std::max(max_hpd, h);
      entropy += e / n;
    }
    CHECK(to_double(trials.at(r, "mean_hpd")) == Approx(hpd).epsilon(1e-12));
    CHECK(to_double(trials.at(r, "max_hpd")) == Approx(max_hpd).epsilon(1e-12));
    CHECK(to_double(trials.at(r, "mean_entropy")) == Approx(entropy).epsilon(1e-12));
  }
  CHECK(targets.rows.size() == target_rows);
  const CsvTable summary = parse_csv(dir.read("A/summary.csv"));
  CHECK(summary.rows.size() == static_cast<std::size_t>(kPoints * kSpecs));
  CHECK(summary.find_column("mean_hpd_mean").has_value());
}

TEST_CASE("run multi-scan: 1 and 2 threads give identical files", "[run][multi_scan][determinism]") {
  TempDir dir;
  dir.write("tiny.ini", kTiny);
  run_ok(dir, {"run", "tiny.ini", "--threads", "1", "--out", "one"});
  run_ok(dir, {"run", "tiny.ini", "--threads", "2", "--out", "two"});
  check_same(without_timing(dir, "one/trials.csv"), without_timing(dir, "two/trials.csv"));
  CHECK(dir.read("one/targets.csv") == dir.read("two/targets.csv"));
  check_same(without_timing(dir, "one/summary.csv"), without_timing(dir, "two/summary.csv"));
  run_ok(dir, {"run", "tiny.ini", "--threads", "2", "--out", "other", "--seed", "4"});
  CHECK(dir.read("one/targets.csv") != dir.read("other/targets.csv"));
}

TEST_CASE("run multi-scan: --resume after a hard kill finishes identically", "[run][multi_scan][resume]") {
  TempDir dir;
  dir.write("tiny.ini", kTiny);
  run_ok(dir, {"run", "tiny.ini", "--threads", "2", "--out", "A"});
  const std::string trials = dir.read("A/trials.csv");
  const std::string targets = dir.read("A/targets.csv");
  const std::string meta = dir.read("A/meta.json");
  const CsvTable reference = without_timing(dir, "A/trials.csv");
  const std::size_t trials_header = trials.find('\n') + 1, targets_header = targets.find('\n') + 1;
  // (what, trials.csv length, targets.csv length); targets.csv always reaches at least as far.
  const std::vector<std::tuple<std::string, std::size_t, std::size_t>> cuts = {
      {"both at the same item boundary", item_offset(trials, 5), item_offset(targets, 5)},
      {"trials mid-line, targets three items further mid-line", item_offset(trials, 7) + 9,
       item_offset(targets, 10) + 11},
      {"trials header only, targets with rows", trials_header, item_offset(targets, 2)},
      {"targets header only", trials_header, targets_header},
      {"trials cut, targets complete", item_offset(trials, 13) + 4, targets.size()},
      {"second point, block boundary", item_offset(trials, 16), item_offset(targets, 16) + 3},
  };
  for (const auto& [what, trials_length, targets_length] : cuts) {
    DYNAMIC_SECTION("cut: " << what) {
      write_run_files(dir, "K", {{"trials.csv", trials.substr(0, trials_length)},
                                 {"targets.csv", targets.substr(0, targets_length)}, {"meta.json", meta}});
      run_ok(dir, {"run", "tiny.ini", "--threads", "2", "--out", "K", "--resume"});
      check_same(reference, without_timing(dir, "K/trials.csv"));
      CHECK(dir.read("K/targets.csv") == targets);
    }
  }
  SECTION("--resume refuses targets.csv rows out of item order") {
    // Items 1 and 2's rows exchanged: each row is whole, but not in the plan's order.
    const std::string swapped = targets.substr(0, item_offset(targets, 1)) +
                                targets.substr(item_offset(targets, 2), item_offset(targets, 3) - item_offset(targets, 2)) +
                                targets.substr(item_offset(targets, 1), item_offset(targets, 2) - item_offset(targets, 1)) +
                                targets.substr(item_offset(targets, 3), item_offset(targets, 8) - item_offset(targets, 3));
    REQUIRE(swapped != targets.substr(0, swapped.size()));
    write_run_files(dir, "K", {{"trials.csv", trials.substr(0, item_offset(trials, 5))}, {"targets.csv", swapped},
                               {"meta.json", meta}});
    const CliResult result = run_dabench(dir, {"run", "tiny.ini", "--threads", "2", "--out", "K", "--resume"});
    INFO(result.err);
    CHECK(result.status == 2);
    CHECK(contains(result.err, "targets.csv:"));
    CHECK(contains(result.err, "where this run has its item"));
    CHECK(contains(result.err, "cannot resume (use --force to start over)"));
    CHECK(dir.read("K/targets.csv") == swapped);
  }
  SECTION("--resume on a finished run changes nothing") {
    run_ok(dir, {"run", "tiny.ini", "--threads", "1", "--out", "A", "--resume"});
    CHECK(dir.read("A/targets.csv") == targets);
    check_same(reference, without_timing(dir, "A/trials.csv"));
  }
}

TEST_CASE("run multi-scan: the column-dual solver's diagnostics, identical for 1 and 2 threads", "[run][multi_scan]") {
  // cv and cvs (column-dual Newton) report line-search steps and final residuals; msbp
  // (Algorithm 2) leaves those columns empty.
  TempDir dir;
  dir.write("convex.ini",
            "scenario = bearings\ntrials = 4\nseed = 5\nalgorithm = cv\nalgorithm = cvs:gamma=0.95\nalgorithm = msbp\n"
            "[scenario]\nparticles = 60\nmean_targets = 3\n");
  run_ok(dir, {"run", "convex.ini", "--threads", "1", "--out", "one"});
  run_ok(dir, {"run", "convex.ini", "--threads", "2", "--out", "two"});
  check_same(without_timing(dir, "one/trials.csv"), without_timing(dir, "two/trials.csv"));
  CHECK(dir.read("one/targets.csv") == dir.read("two/targets.csv"));
  const CsvTable trials = parse_csv(dir.read("one/trials.csv"));
  int solved = 0;
  for (std::size_t r = 0; r < trials.rows.size(); ++r) {
    if (trials.at(r, "status") != "ok") continue;
    INFO(trials.at(r, "algorithm") << " trial " << trials.at(r, "trial"));
    if (trials.at(r, "algorithm") == "msbp") {
      CHECK(trials.at(r, "residual").empty());
      CHECK(trials.at(r, "line_search_steps").empty());
      continue;
    }
    ++solved;
    CHECK(trials.at(r, "converged") == "1");
    CHECK(to_double(trials.at(r, "residual")) <= 1e-12);
    CHECK(to_double(trials.at(r, "inner_residual")) <= 1e-13);
    CHECK(to_double(trials.at(r, "line_search_steps")) >= 0.0);
    CHECK(to_double(trials.at(r, "iterations")) >= 1.0);
  }
  CHECK(solved >= 6);
}

TEST_CASE("run multi-scan: draws without targets are skipped", "[run][multi_scan]") {
  TempDir dir;
  dir.write("none.ini", "scenario = bearings\ntrials = 3\nalgorithm = jpda-bp\n[scenario]\nmean_targets = 0\nparticles = 10\n");
  run_ok(dir, {"run", "none.ini", "--out", "N"});
  const CsvTable trials = parse_csv(dir.read("N/trials.csv"));
  REQUIRE(trials.rows.size() == 3);
  for (std::size_t r = 0; r < 3; ++r) {
    CHECK(trials.at(r, "status") == "skipped:no_targets");
    CHECK(trials.at(r, "mean_hpd").empty());
  }
  CHECK(split_lines(dir.read("N/targets.csv")).size() == 1);
}

TEST_CASE("run multi-scan: configuration errors are one clear line", "[run][multi_scan]") {
  TempDir dir;
  check_refused_on_command_line(dir, "scenario = bearings\ntrials = 2\nalgorithm = no-such-method\n",
                                {"bad.ini", "unknown multi-scan algorithm 'no-such-method'", "known: ", "jpda-bp"});
  check_refused_on_command_line(dir, "scenario = bearings\ntrials = 2\nalgorithm = bp\n",
                                {"'bp' is a single-scan algorithm", "multi-scan"});
  check_refused_on_command_line(dir, "scenario = grid\ntrials = 2\nalgorithm = jpda-bp\n",
                                {"'jpda-bp' is a multi-scan algorithm"});
  check_refused_on_command_line(dir, "scenario = bearings\ntrials = 2\nreference = jpda-bp\nalgorithm = jpda-bp\n",
                                {"'reference' lines are not used"});
  check_refused_on_command_line(
      dir, "scenario = bearings\ntrials = 2\nalgorithm = jpda-bp\n[scenario]\nparticles = 0\n", {"particles = 0"});
}

}  // namespace DABENCH_TEST_FILE
