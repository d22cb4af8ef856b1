// Tests of the tracker registry (harness/tracking/registry.hpp, DABENCH_REGISTER_TRACKING_TRACKER): a tracker
// defined here registers with one line, SPECs set its options, bad SPECs are InputErrors.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "harness/tracking/registry.hpp"

namespace DABENCH_TEST_FILE {

namespace {

// A test-only tracker: one track per scan holding `value` in every state entry.
struct ConstantTrackerOptions {
  double value = 1.5;  // state entry of every track

  void bind(dabench::ParamList& p) { p.add("value", value, "state entry of every track, finite"); }
  std::string validate() const { return std::isfinite(value) ? "" : "value must be finite"; }
};

class ConstantTracker final : public dabench::Tracker {
 public:
  using Options = ConstantTrackerOptions;
  static constexpr std::string_view kName = "test-constant-tracker";
  static constexpr std::string_view kSummary = "test only: one constant track per scan";
  explicit ConstantTracker(const Options& options) : options_(options) {}

  void run(const dabench::TrackingProblem& problem, dabench::TrackSet& tracks, dabench::SolveReport& report) override {
    report.reset();
    tracks.tracks.clear();
    for (int k = 0; k < problem.scan_count(); ++k) {
      dabench::Track track;
      track.id = k;
      track.first_scan = k;
      track.states = Eigen::MatrixXd::Constant(2, 1, options_.value);
      track.covariance_diagonals = Eigen::MatrixXd::Ones(2, 1);
      tracks.tracks.push_back(track);
    }
  }

 private:
  Options options_;
};

DABENCH_REGISTER_TRACKING_TRACKER(ConstantTracker);

}  // namespace

TEST_CASE("tracker registry: registered tracker is built from a SPEC with its options", "[tracking_tracker_registry]") {
  const auto* entry = dabench::tracking_tracker_registry().find("test-constant-tracker");
  REQUIRE(entry != nullptr);
  CHECK(entry->summary == "test only: one constant track per scan");
  auto tracker = dabench::make_tracker("test-constant-tracker:value=-2.25");
  dabench::TrackingProblem problem;
  problem.scans.resize(3);
  dabench::TrackSet tracks;
  dabench::SolveReport report;
  tracker->run(problem, tracks, report);
  REQUIRE(tracks.tracks.size() == 3);
  CHECK(tracks.tracks[2].first_scan == 2);
  CHECK(tracks.tracks[2].length() == 1);
  CHECK(tracks.tracks[2].states(1, 0) == -2.25);
  CHECK(report.skipped.empty());
}

TEST_CASE("tracker registry: unknown names and keys and invalid values are input errors", "[tracking_tracker_registry]") {
  CHECK_THROWS_AS(dabench::make_tracker("no-such-tracker"), dabench::InputError);
  CHECK_THROWS_WITH(dabench::make_tracker("no-such-tracker"), Catch::Contains("unknown tracker 'no-such-tracker'"));
  CHECK_THROWS_AS(dabench::make_tracker("test-constant-tracker:nokey=1"), dabench::InputError);
  CHECK_THROWS_AS(dabench::make_tracker("test-constant-tracker:value=abc"), dabench::InputError);
}

}  // namespace DABENCH_TEST_FILE
