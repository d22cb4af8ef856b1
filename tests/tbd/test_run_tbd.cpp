// End-to-end `dabench run` on a tiny track-before-detect experiment (scenario `tbd`, 12 × 12
// cells, 6 steps, tracker tbd-bp with few particles):
//  - trials.csv: one row per (trial, tracker) with the TBD metric columns, equal to the means
//    over that run's steps.csv rows; steps.csv one row per (trial, tracker, k = 1..K);
//    estimates.csv and frames.csv for trial 0 only (truth rows, J cells per step);
//  - GOSPA of each step equals a brute-force GOSPA of that step's estimates.csv rows (trial 0);
//  - determinism: 1 vs 2 threads give identical files (timings aside);
//  - [metrics]: recorded in meta.json, unknown keys and bad values are one-line errors, and
//    the section is refused for other kinds.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "tests/support/cli_contract.hpp"
#include "tests/support/cli_runner.hpp"
#include "tests/support/run_files.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench::test::cli;

namespace {

const char* const kTiny =
    "scenario = tbd\n"
    "trials = 3\n"
    "seed = 5\n"
    "algorithm = tbd-bp:particles=300\n"
    "algorithm = tbd-bp:iterations=1,particles=300,seed=2\n"
    "[scenario]\n"
    "layout = persistent\n"
    "objects = 2\n"
    "steps = 6\n"
    "columns = 12\n"
    "rows = 12\n"
    "[metrics]\n"
    "gospa_cutoff = 2\n";
constexpr int kTrials = 3, kSpecs = 2, kSteps = 6, kCells = 144;

bool is_timing(const std::string& name) { return name == "time_us" || name.rfind("step_time_us", 0) == 0; }

// GOSPA (c = 2, p = 1, α = 2) by enumerating every partial assignment of the smaller set.
double brute_gospa(const std::vector<std::pair<double, double>>& x, const std::vector<std::pair<double, double>>& y) {
  const double c = 2.0;
  std::vector<bool> used(y.size(), false);
  double best = 1e300;
  std::vector<int> assign(x.size(), -1);
  const auto recurse = [&](auto&& self, std::size_t i, double cost, int pairs) -> void {
    if (i == x.size()) {
      best = std::min(best, cost + 0.5 * c * (static_cast<double>(x.size() + y.size()) - 2.0 * pairs));
      return;
    }
    self(self, i + 1, cost, pairs);  // x_i missed
    for (std::size_t j = 0; j < y.size(); ++j) {
      if (used[j]) continue;
      const double d = std::hypot(x[i].first - y[j].first, x[i].second - y[j].second);
      if (d >= c) continue;
      used[j] = true;
      self(self, i + 1, cost + d, pairs + 1);
      used[j] = false;
    }
  };
  recurse(recurse, 0, 0.0, 0);
  return best;
}

}  // namespace

TEST_CASE("run tbd: trials.csv, steps.csv, estimates.csv and frames.csv agree", "[run][tbd]") {
  TempDir dir;
  dir.write("tiny.ini", kTiny);
  run_ok(dir, {"run", "tiny.ini", "--threads", "2", "--out", "A"});
  const CsvTable trials = parse_csv(dir.read("A/trials.csv"));
  const CsvTable steps = parse_csv(dir.read("A/steps.csv"));
  const CsvTable estimates = parse_csv(dir.read("A/estimates.csv"));
  const CsvTable frames = parse_csv(dir.read("A/frames.csv"));
  REQUIRE(trials.rows.size() == static_cast<std::size_t>(kTrials * kSpecs));
  REQUIRE(steps.rows.size() == static_cast<std::size_t>(kTrials * kSpecs * kSteps));
  CHECK(frames.rows.size() == static_cast<std::size_t>(kSteps * kCells));
  for (std::size_t r = 0; r < frames.rows.size(); ++r) CHECK(frames.at(r, "trial") == "0");
  CHECK(dir.read("A/meta.json").find(R"("tbd_metrics": {"gospa_cutoff": 2, "gospa_order": 1, "gospa_alpha": 2})") !=
        std::string::npos);

  // trials.csv = means over the run's steps.
  for (std::size_t t = 0; t < trials.rows.size(); ++t) {
    CHECK(trials.at(t, "status") == "ok");
    CHECK(trials.at(t, "n_steps") == std::to_string(kSteps));
    for (const char* metric : {"gospa", "gospa_p2", "missed", "false", "n_objects", "n_estimates"}) {
      double sum = 0.0;
      int count = 0;
      for (std::size_t r = 0; r < steps.rows.size(); ++r) {
        if (steps.at(r, "trial") != trials.at(t, "trial") || steps.at(r, "algorithm") != trials.at(t, "algorithm")) continue;
        sum += number(steps, r, metric);
        ++count;
      }
      REQUIRE(count == kSteps);
      INFO(metric);
      CHECK(number(trials, t, metric) == Approx(sum / kSteps).epsilon(1e-12));
    }
  }

  // Each step's GOSPA from the positions in estimates.csv (trial 0).
  std::map<std::string, std::vector<std::pair<double, double>>> points;  // "algorithm/k"
  for (std::size_t r = 0; r < estimates.rows.size(); ++r) {
    REQUIRE(estimates.at(r, "trial") == "0");
    points[estimates.at(r, "algorithm") + "/" + estimates.at(r, "k")].push_back(
        {number(estimates, r, "x"), number(estimates, r, "y")});
  }
  int checked = 0;
  for (std::size_t r = 0; r < steps.rows.size(); ++r) {
    if (steps.at(r, "trial") != "0") continue;
    const std::string k = steps.at(r, "k");
    const auto& truth = points["truth/" + k];
    const auto& reported = points[steps.at(r, "algorithm") + "/" + k];
    CHECK(number(steps, r, "n_objects") == static_cast<double>(truth.size()));
    CHECK(number(steps, r, "n_estimates") == static_cast<double>(reported.size()));
    CHECK(number(steps, r, "gospa") == Approx(brute_gospa(truth, reported)).margin(1e-9));
    ++checked;
  }
  CHECK(checked == kSpecs * kSteps);
}

TEST_CASE("run tbd: 1 and 2 threads give identical files, timings aside", "[run][tbd]") {
  TempDir dir;
  dir.write("tiny.ini", kTiny);
  run_ok(dir, {"run", "tiny.ini", "--threads", "1", "--out", "one"});
  run_ok(dir, {"run", "tiny.ini", "--threads", "2", "--out", "two"});
  for (const char* file : {"trials.csv", "steps.csv", "estimates.csv", "frames.csv", "summary.csv"}) {
    INFO(file);
    check_same(parse_csv(dir.read(std::string("one/") + file)).without(is_timing),
               parse_csv(dir.read(std::string("two/") + file)).without(is_timing));
  }
}

TEST_CASE("run tbd: [metrics] errors are one line, and other kinds refuse the section", "[run][tbd]") {
  TempDir dir;
  const auto fails_with = [&](const std::string& text, const std::string& expected) {
    dir.write("bad.ini", text);
    const CliResult result = run_dabench(dir, {"run", "bad.ini", "--out", "B"});
    INFO("stderr: " << result.err);
    CHECK(result.status != 0);
    CHECK(result.err.find(expected) != std::string::npos);
    CHECK(std::count(result.err.begin(), result.err.end(), '\n') == 1);
    CHECK_FALSE(dir.exists("B/trials.csv"));
  };
  const std::string base = "scenario = tbd\ntrials = 1\nalgorithm = tbd-bp\n[metrics]\n";
  fails_with(base + "gospa_cutof = 2\n", "gospa_cutof");
  fails_with(base + "gospa_cutoff = -1\n", "gospa_cutoff");
  fails_with(base + "gospa_alpha = 3\n", "gospa_alpha");
  fails_with("scenario = grid\ntrials = 1\nalgorithm = bp\n[metrics]\ngospa_cutoff = 2\n", "[metrics]");
}

TEST_CASE("run tbd: beliefs = true writes trial 0's final beliefs, normalised per object", "[run][tbd]") {
  TempDir dir;
  dir.write("toy.ini",
            "scenario = tbd\ntrials = 2\nseed = 3\nbeliefs = true\n"
            "algorithm = tbd-bp:iterations=1,particles=200\n"
            "algorithm = tbd-bp:iterations=1,particles=150,exact_kappa=true\n"
            "[scenario]\nlayout = toy\n");
  run_ok(dir, {"run", "toy.ini", "--out", "T"});
  const CsvTable beliefs = parse_csv(dir.read("T/beliefs.csv"));
  std::map<std::string, std::pair<int, double>> per_object;  // "algorithm/label" → (samples, Σ weight)
  for (std::size_t r = 0; r < beliefs.rows.size(); ++r) {
    CHECK(beliefs.at(r, "trial") == "0");
    CHECK(beliefs.at(r, "k") == "1");
    auto& [samples, sum] = per_object[beliefs.at(r, "algorithm") + "/" + beliefs.at(r, "label")];
    ++samples;
    sum += number(beliefs, r, "weight");
  }
  // The toy's two POs (existence 1, no births) survive the one step under both trackers.
  REQUIRE(per_object.size() == 4);
  for (const auto& [key, value] : per_object) {
    INFO(key);
    CHECK(value.first == (key.rfind("tbd-bp:iterations=1,particles=200/", 0) == 0 ? 200 : 150));
    CHECK(value.second == Approx(1.0).epsilon(1e-12));
  }
  TempDir other;
  other.write("bad.ini", "scenario = grid\ntrials = 1\nbeliefs = true\nalgorithm = bp\n");
  const CliResult result = run_dabench(other, {"run", "bad.ini", "--out", "B"});
  CHECK(result.status != 0);
  CHECK(result.err.find("beliefs = true") != std::string::npos);
}

}  // namespace DABENCH_TEST_FILE
