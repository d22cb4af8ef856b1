// The example problem kind of docs "Adding a kind" (README.md), whole in one file: a problem and
// its solver interface, a scenario and two estimators in their registries, the execution that
// writes a work unit's rows, and the kind's descriptor, registered with
// DABENCH_REGISTER_PROBLEM_KIND. Built with apps/dabench.cpp into the program
// dabench_example_kind (tests/CMakeLists.txt), which tests/run/test_adding_a_kind.cpp runs through
// `run`, `merge`, `compare` and `schedule`: nothing outside this file knows the kind.
//
// The problem: one target at an unknown position x on a line [0, L] and m measurements of it,
// each the target's (x + σ·N(0, 1)) or, with probability `clutter`, clutter (uniform on [0, L]).
// An estimator returns x̂; the error is |x̂ − x|, and the per-item file residuals.csv holds each
// measurement's residual z_j − x̂.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "harness/core/params.hpp"
#include "harness/core/random_stream.hpp"
#include "harness/core/registry.hpp"
#include "harness/core/row_fields.hpp"
#include "harness/core/solve_report.hpp"
#include "harness/run/execution.hpp"
#include "harness/run/kinds/registry_kind.hpp"
#include "harness/run/problem_kind.hpp"
#include "harness/run/run_plan.hpp"
#include "harness/run/trial_draw.hpp"

namespace dabench::example {

// ---- the problem and its solver interface -------------------------------------------------------
struct LocationSample {
  std::vector<double> z;  // the measurements
  double truth = 0.0;     // x
};

class LocationScenario {
 public:
  virtual ~LocationScenario() = default;
  virtual void generate(RandomStream& rng, LocationSample& sample) const = 0;
};

class LocationEstimator {
 public:
  virtual ~LocationEstimator() = default;
  // x̂ from the measurements, sorted (at least one).
  virtual double estimate(const std::vector<double>& sorted_z) const = 0;
};

Registry<LocationScenario>& location_scenarios() {
  static Registry<LocationScenario> registry;
  return registry;
}

Registry<LocationEstimator>& location_estimators() {
  static Registry<LocationEstimator> registry;
  return registry;
}

std::unique_ptr<LocationEstimator> make_location_estimator(std::string_view spec) {
  return location_estimators().make(spec, "location estimator");
}

// ---- a scenario and two estimators ---------------------------------------------------------------
struct ClutteredLineOptions {
  int measurements = 8;  // m
  double clutter = 0.2;  // probability that a measurement is clutter
  double sigma = 1.0;    // σ of the target's measurements
  double length = 100.0;
  void bind(ParamList& p) {
    p.add("measurements", measurements, "measurements m per trial");
    p.add("clutter", clutter, "probability that a measurement is clutter, in [0, 1]");
    p.add("sigma", sigma, "standard deviation of the target's measurements (> 0)");
    p.add("length", length, "the line [0, length] of the target and the clutter (> 0)");
  }
  std::string validate() const {
    if (measurements < 0 || measurements > 100000) return "measurements must be in [0, 100000]";
    if (!(clutter >= 0.0 && clutter <= 1.0)) return "clutter must be in [0, 1]";
    return sigma > 0.0 && length > 0.0 ? "" : "sigma and length must be > 0";
  }
};

class ClutteredLine final : public LocationScenario {
 public:
  using Options = ClutteredLineOptions;
  static constexpr std::string_view kName = "example-line";
  static constexpr std::string_view kSummary = "one target on a line, m measurements of it or of uniform clutter";
  explicit ClutteredLine(const Options& options) : options_(options) {}
  void generate(RandomStream& rng, LocationSample& sample) const override {
    sample.truth = rng.uniform(0.0, options_.length);
    sample.z.resize(static_cast<std::size_t>(options_.measurements));
    for (double& z : sample.z) {
      const bool clutter = rng.bernoulli(options_.clutter);
      const double from_clutter = rng.uniform(0.0, options_.length), noise = rng.normal();  // three draws each
      z = clutter ? from_clutter : sample.truth + options_.sigma * noise;
    }
  }

 private:
  Options options_;
};

struct TrimmedMeanOptions {
  double trim = 0.0;  // fraction of the measurements left out at each end
  void bind(ParamList& p) { p.add("trim", trim, "fraction left out at each end, in [0, 0.5)"); }
  std::string validate() const { return trim >= 0.0 && trim < 0.5 ? "" : "trim must be in [0, 0.5)"; }
};

class TrimmedMean final : public LocationEstimator {
 public:
  using Options = TrimmedMeanOptions;
  static constexpr std::string_view kName = "example-mean";
  static constexpr std::string_view kSummary = "mean of the measurements, trimmed at both ends";
  explicit TrimmedMean(const Options& options) : options_(options) {}
  double estimate(const std::vector<double>& z) const override {
    const auto cut = static_cast<std::size_t>(options_.trim * static_cast<double>(z.size()));
    double sum = 0.0;
    for (std::size_t j = cut; j < z.size() - cut; ++j) sum += z[j];
    return sum / static_cast<double>(z.size() - 2 * cut);
  }

 private:
  Options options_;
};

struct MedianOptions {
  void bind(ParamList&) {}
  std::string validate() const { return ""; }
};

class Median final : public LocationEstimator {
 public:
  using Options = MedianOptions;
  static constexpr std::string_view kName = "example-median";
  static constexpr std::string_view kSummary = "median of the measurements";
  explicit Median(const Options&) {}
  double estimate(const std::vector<double>& z) const override {
    const std::size_t half = z.size() / 2;
    return z.size() % 2 == 1 ? z[half] : 0.5 * (z[half - 1] + z[half]);
  }
};

template <class Made, class Product>
struct Registration {
  explicit Registration(Registry<Product>& registry) { registry.add(make_registry_entry<Made, Product>()); }
};
const Registration<ClutteredLine, LocationScenario> cluttered_line_registration(location_scenarios());
const Registration<TrimmedMean, LocationEstimator> trimmed_mean_registration(location_estimators());
const Registration<Median, LocationEstimator> median_registration(location_estimators());

// ---- the execution: one unit is one estimator on one item's draw ----------------------------------
struct LocationWorker final : RunWorker {
  std::vector<std::unique_ptr<LocationEstimator>> estimators;  // one per SPEC
  LocationSample sample;
  std::vector<double> sorted_z;
  SolveReport report;
};

class LocationExecution final : public RunExecution {
 public:
  LocationExecution(const RunPlan& plan, std::vector<std::unique_ptr<LocationScenario>> scenarios)
      : plan_(plan), scenarios_(std::move(scenarios)), point_prefix_(plan.point_row_prefixes()), spec_field_(plan.spec_fields()) {}

  std::unique_ptr<RunWorker> make_worker() const override {
    auto worker = std::make_unique<LocationWorker>();
    for (const std::string& spec : plan_.specs) worker->estimators.push_back(make_location_estimator(spec));
    worker->texts.resize(2);  // residuals.csv, trials.csv (the kind's item_files(), then trials.csv)
    return worker;
  }

  void run_unit(RunWorker& base, long long item, std::size_t part) const override {
    auto& worker = static_cast<LocationWorker&>(base);
    const auto [point, trial] = draw_trial(plan_, scenarios_, item, worker.sample);
    worker.report.reset();
    const auto start = std::chrono::steady_clock::now();
    double estimate = 0.0;
    if (worker.sample.z.empty()) {
      worker.report.skipped = "no_measurements";
    } else {
      worker.sorted_z.assign(worker.sample.z.begin(), worker.sample.z.end());
      std::sort(worker.sorted_z.begin(), worker.sorted_z.end());
      estimate = worker.estimators[part]->estimate(worker.sorted_z);
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    worker.busy_seconds += seconds;
    const bool ok = worker.report.skipped.empty();
    const std::string& prefix = point_prefix_[point];
    if (ok) {
      for (std::size_t j = 0; j < worker.sample.z.size(); ++j) {
        fmt::format_to(std::back_inserter(worker.texts[0]), "{},{},{},{}", prefix, trial, spec_field_[part], j + 1);
        append_number(worker.texts[0], worker.sample.z[j] - estimate);
        worker.texts[0] += '\n';
      }
    }
    std::string& row = worker.texts[1];
    fmt::format_to(std::back_inserter(row), "{},{},{},{},", prefix, trial, plan_.seed, spec_field_[part]);
    append_status(row, worker.report);
    fmt::format_to(std::back_inserter(row), ",{}", worker.sample.z.size());
    const double nan = std::nan("");
    append_number(row, worker.sample.truth);
    append_number(row, ok ? estimate : nan);
    append_number(row, ok ? std::abs(estimate - worker.sample.truth) : nan);
    append_number(row, 1e6 * seconds);
    row += '\n';
  }

 private:
  const RunPlan& plan_;
  std::vector<std::unique_ptr<LocationScenario>> scenarios_;
  std::vector<std::string> point_prefix_;  // "point,param values" per point
  std::vector<std::string> spec_field_;    // CSV-quoted SPEC per estimator
};

// ---- the kind's descriptor -----------------------------------------------------------------------
class LocationKind final : public RegistryKind<LocationScenario, LocationEstimator> {
 public:
  LocationKind() : RegistryKind(location_scenarios(), location_estimators(), make_location_estimator) {}
  std::string_view name() const override { return "example-location"; }
  std::string_view key() const override { return "example_location"; }
  std::string_view algorithm_noun() const override { return "location estimator"; }
  std::string_view algorithms_title() const override { return "Location estimators (the example kind):"; }
  std::string_view scenarios_title() const override { return "Location scenarios (the example kind):"; }
  const std::vector<std::string>& metric_columns() const override {
    static const std::vector<std::string> columns = {"n_measurements", "truth", "estimate", "error", "time_us"};
    return columns;
  }
  std::vector<ItemFile> item_files(const std::string& point_columns, const Experiment&) const override {
    return {{"residuals.csv", point_columns + ",trial,algorithm,measurement,residual\n"}};
  }
  std::string_view error_column() const override { return "error"; }
  AlgorithmTimeColumn time_column() const override { return {"time_us", 1e-6}; }
  std::unique_ptr<RunExecution> make_execution(const RunPlan& plan) const override {
    return std::make_unique<LocationExecution>(plan, point_scenarios(plan));
  }
};

DABENCH_REGISTER_PROBLEM_KIND(LocationKind);

}  // namespace dabench::example
