// A UKF failure inside a tracker (algorithms/tracking/ukf.hpp, UnscentedFailure) ends as the run's
// `failed:` status, never as NaN estimates or metrics. The trigger: the OTHR sensor with a
// measurement function undefined (NaN) beyond a bearing rate |ϑ̇| of `bound` rad/s, a region
// that JDT-VB's estimates never enter but the sigma points of a new track (ϑ̇ s.d. 2e-4) do at
// its first update, so the innovation covariance S of scan 1 is not finite.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "algorithms/tracking/jdt_vb.hpp"
#include "harness/core/random_stream.hpp"
#include "harness/tracking/registry.hpp"
#include "scenarios/tracking/othr.hpp"
#include "tests/support/cli_runner.hpp"
#include "tests/support/run_files.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench::test::cli;

namespace {

class BoundedSensor final : public dabench::MultipathMeasurementModel {
 public:
  BoundedSensor(std::shared_ptr<const dabench::MultipathMeasurementModel> sensor, double bound)
      : sensor_(std::move(sensor)), bound_(bound) {}
  int state_dim() const override { return sensor_->state_dim(); }
  int measurement_dim() const override { return sensor_->measurement_dim(); }
  int paths() const override { return sensor_->paths(); }
  dabench::Vector measure(int path, const dabench::Vector& x) const override {
    if (std::abs(x[3]) > bound_) return dabench::Vector::Constant(measurement_dim(), std::numeric_limits<double>::quiet_NaN());
    return sensor_->measure(path, x);
  }
  Eigen::MatrixXd jacobian(int path, const dabench::Vector& x) const override { return sensor_->jacobian(path, x); }
  const Eigen::MatrixXd& noise_covariance(int path) const override { return sensor_->noise_covariance(path); }
  bool invert(int path, const dabench::Vector& y, dabench::Vector& x) const override { return sensor_->invert(path, y, x); }

 private:
  std::shared_ptr<const dabench::MultipathMeasurementModel> sensor_;
  double bound_;
};

struct BoundedOthrOptions {
  int scans = 6;
  double bound = 3e-4;  // rad/s

  void bind(dabench::ParamList& p) {
    p.add("scans", scans, "scans K");
    p.add("bound", bound, "largest |bearing rate| at which h is defined, rad/s");
  }
  std::string validate() const { return scans >= 2 && bound > 0.0 ? "" : "bad test scenario"; }
};

// The othr scenario's draw (defaults, `scans` scans) with its sensor bounded.
class BoundedOthrScenario final : public dabench::TrackingScenario {
 public:
  using Options = BoundedOthrOptions;
  static constexpr std::string_view kName = "test-othr-bounded-sensor";
  static constexpr std::string_view kSummary = "test only: othr with h undefined beyond a bearing rate";
  explicit BoundedOthrScenario(const Options& options) : o_(options) {}

  void generate(dabench::RandomStream& rng, dabench::TrackingScenarioSample& sample) const override {
    dabench::OthrOptions othr;
    othr.scans = o_.scans;
    dabench::OthrScenario(othr).generate(rng, sample);
    sample.problem.sensor = std::make_shared<BoundedSensor>(sample.problem.sensor, o_.bound);
  }

 private:
  Options o_;
};
DABENCH_REGISTER_TRACKING_SCENARIO(BoundedOthrScenario);

const char* const kFailure = "failed:ukf: innovation covariance not positive definite at scan 1";

}  // namespace

TEST_CASE("jdt-vb: a UKF failure is the run's failed: status, with no tracks", "[jdt_vb][ukf]") {
  for (const double bound : {3e-4, 1.0}) {
    INFO("bound " << bound);
    dabench::TrackingScenarioSample sample;
    dabench::RandomStream rng(2024, 0, 0);
    BoundedOthrScenario({6, bound}).generate(rng, sample);
    dabench::JdtVbTracker tracker{dabench::JdtVbOptions{}};
    dabench::TrackSet tracks;
    dabench::SolveReport report;
    tracker.run(sample.problem, tracks, report);
    if (bound < 1.0) {
      CHECK(report.skipped == kFailure);
      CHECK(tracks.tracks.empty());
    } else {  // the same draw with h defined wherever the sigma points go: finite tracks
      CHECK(report.skipped.empty());
      REQUIRE_FALSE(tracks.tracks.empty());
      for (const dabench::Track& track : tracks.tracks) CHECK(track.states.allFinite());
    }
  }
}

TEST_CASE("run tracking: a UKF failure writes a failed: row and no NaN metric", "[run][tracking][ukf]") {
  TempDir dir;
  dir.write("u.ini",
            "scenario = test-othr-bounded-sensor\n"
            "trials = 2\n"
            "seed = 3\n"
            "algorithm = jdt-vb\n"
            "[sweep]\n"
            "bound = 3e-4, 1\n");
  run_in(dir, "u.ini", "U", 2);
  const CsvTable trials = parse_csv(dir.read("U/trials.csv"));
  REQUIRE(trials.rows.size() == 4);
  for (std::size_t r = 0; r < trials.rows.size(); ++r) {
    INFO("row " << r);
    const bool bounded = trials.at(r, "point") == "0";
    CHECK(trials.at(r, "status") == (bounded ? kFailure : "ok"));
    for (const char* column : {"nvt", "tpd", "nft", "mospa_km", "iterations", "free_energy"}) {
      if (bounded) CHECK(trials.at(r, column).empty());
      else CHECK(std::isfinite(number(trials, r, column)));
    }
  }
  // Summaries count the failures and average nothing of them.
  const CsvTable summary = parse_csv(dir.read("U/summary.csv"));
  REQUIRE(summary.rows.size() == 2);
  CHECK(summary.at(0, "failed") == "2");
  CHECK(summary.at(0, "nvt_count") == "0");
  CHECK(summary.at(1, "ok") == "2");
}

}  // namespace DABENCH_TEST_FILE
