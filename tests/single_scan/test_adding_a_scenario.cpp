// docs/extending.md, "Adding a scenario": its example scenario, compiled here as written there (registered in
// the test binary alone, as example-uniform), run through `dabench run`'s code path
// (run_experiment) against the exact reference: the documented columns and sweep, exact
// methods that agree to 1e-12 and BP that does not on these loopy problems, the draw
// reproducible from (seed, point, trial) alone, and its parameter checks as one-line errors.
#include <catch2/catch.hpp>

#include <string>
#include <string_view>

#include "harness/core/params.hpp"
#include "harness/single_scan/registry.hpp"
#include "harness/single_scan/scenario.hpp"
#include "tests/support/cli_runner.hpp"
#include "tests/support/run_files.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench;
using namespace dabench::test::cli;

namespace {

// ---- the documented example (docs/extending.md, "Adding a scenario") ------------------------
struct UniformOptions {
  int targets = 4;        // n
  int measurements = 4;   // m
  double density = 0.7;   // probability that a (target, measurement) pair is gated
  double scale = 2.0;     // ψ is uniform on (0, scale]
  void bind(ParamList& p) {
    p.add("targets", targets, "targets n");
    p.add("measurements", measurements, "measurements m");
    p.add("density", density, "probability that a pair is gated, in [0, 1]");
    p.add("scale", scale, "largest weight psi (> 0)");
  }
  std::string validate() const {
    if (targets < 0 || measurements < 0) return "targets and measurements must be >= 0";
    if (!(density >= 0.0 && density <= 1.0)) return "density must be in [0, 1]";
    return scale > 0.0 ? "" : "scale must be > 0";
  }
};

class UniformScenario final : public SingleScanScenario {
 public:
  using Options = UniformOptions;
  static constexpr std::string_view kName = "example-uniform";
  static constexpr std::string_view kSummary = "n x m weights, each pair gated with probability density";
  explicit UniformScenario(const Options& options) : options_(options) {}
  void generate(RandomStream& rng, ScenarioSample& sample) const override {
    sample = ScenarioSample{};
    sample.problem.psi = RowMatrix::Zero(options_.targets, options_.measurements);
    for (int i = 0; i < options_.targets; ++i) {
      for (int j = 0; j < options_.measurements; ++j) {
        const double gate = rng.uniform(), weight = options_.scale * (1.0 - rng.uniform());  // two draws a pair
        if (gate < options_.density) sample.problem.psi(i, j) = weight;
      }
    }
  }

 private:
  Options options_;
};
DABENCH_REGISTER_SINGLE_SCAN_SCENARIO(UniformScenario);
// ---- end of the example -------------------------------------------------------------------

const char* const kExperiment =
    "scenario = example-uniform\n"
    "trials = 40\n"
    "seed = 3\n"
    "reference = exact\n"
    "algorithm = ehm\n"
    "algorithm = bp\n"
    "[sweep]\n"
    "density = 0.3, 1\n";

}  // namespace

TEST_CASE("adding a scenario: the documented example runs as an experiment", "[run][scenario]") {
  TempDir dir;
  dir.write("u.ini", kExperiment);
  const RunOutcome outcome = run_in(dir, "u.ini", "U", 2);
  CHECK(outcome.items_total == 80);
  const CsvTable trials = parse_csv(dir.read("U/trials.csv"));
  const std::vector<std::string> leading = {"point", "targets", "measurements", "density", "scale", "trial"};
  CHECK(std::vector<std::string>(trials.header.begin(), trials.header.begin() + 6) == leading);
  REQUIRE(trials.rows.size() == 80 * 3);
  double bp_worst = 0.0, ehm_worst = 0.0;
  for (std::size_t r = 0; r < trials.rows.size(); ++r) {
    INFO("row " << r);
    CHECK(trials.at(r, "status") == "ok");
    CHECK(trials.at(r, "n_targets") == "4");
    CHECK(trials.at(r, "n_measurements") == "4");
    if (trials.at(r, "algorithm") == "ehm") ehm_worst = std::max(ehm_worst, std::stod(trials.at(r, "max_error")));
    if (trials.at(r, "algorithm") == "bp") bp_worst = std::max(bp_worst, std::stod(trials.at(r, "max_error")));
  }
  CHECK(ehm_worst < 1e-12);  // exact against exact
  CHECK(bp_worst > 1e-3);    // complete 4 × 4 graphs are loopy: BP is an approximation there
  // The same experiment again (one thread): the same draws, so the same numbers.
  const RunOutcome again = run_in(dir, "u.ini", "V", 1);
  CHECK(again.items_total == 80);
  const CsvTable second = parse_csv(dir.read("V/trials.csv"));
  REQUIRE(second.rows.size() == trials.rows.size());
  for (std::size_t r = 0; r < trials.rows.size(); ++r) CHECK(second.at(r, "max_error") == trials.at(r, "max_error"));
}

TEST_CASE("adding a scenario: the example's parameters are checked", "[scenario]") {
  const auto* entry = single_scan_scenario_registry().find("example-uniform");
  REQUIRE(entry != nullptr);
  CHECK_THROWS_WITH(entry->create({{"density", "1.5"}}), Catch::Contains("density must be in [0, 1]"));
  CHECK_THROWS_WITH(entry->create({{"scale", "0"}}), Catch::Contains("scale must be > 0"));
  CHECK_THROWS_WITH(entry->create({{"sigma", "1"}}), Catch::Contains("sigma"));
  // Density 0: nothing gated, so every target is missed for sure.
  ScenarioSample sample;
  RandomStream rng(1, 0, 0);
  entry->create({{"density", "0"}})->generate(rng, sample);
  CHECK(sample.problem.psi.isZero());
}

}  // namespace DABENCH_TEST_FILE
