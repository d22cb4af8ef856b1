// The contract every registered tracker must keep (DESIGN.md, "a contract test runs every
// registered algorithm on a tiny problem"), over tracking_tracker_registry(), so a new tracker is covered
// when it registers itself. Each is built with its defaults and run on short OTHR runs,
// including one without clutter and one with no detections at all; it either refuses
// (report.skipped) or returns tracks that
//   - lie inside the run (0 ≤ first_scan, first_scan + length ≤ K), with state and covariance
//     diagonals of the same shape, the sensor's state dimension, finite, variances ≥ 0,
//   - carry distinct ids,
// and results that depend only on the problem: identical from a fresh tracker and from one
// that ran other problems in between.
#include <catch2/catch.hpp>

#include <cmath>
#include <set>

#include "harness/core/random_stream.hpp"
#include "harness/tracking/registry.hpp"
#include "scenarios/tracking/othr.hpp"

namespace DABENCH_TEST_FILE {

namespace {

using namespace dabench;

TrackingScenarioSample othr_run(double pd, double clutter, int scans, std::uint32_t trial) {
  OthrOptions o;
  o.pd = pd;
  o.clutter = clutter;
  o.scans = scans;
  TrackingScenarioSample sample;
  RandomStream rng(77, 0, trial);
  OthrScenario(o).generate(rng, sample);
  return sample;
}

void check_valid(const TrackSet& tracks, const TrackingProblem& problem) {
  std::set<int> ids;
  for (const Track& t : tracks.tracks) {
    INFO("track " << t.id);
    CHECK(ids.insert(t.id).second);
    CHECK(t.first_scan >= 0);
    CHECK(t.length() >= 1);
    CHECK(t.first_scan + t.length() <= problem.scan_count());
    CHECK(t.states.rows() == problem.sensor->state_dim());
    CHECK(t.covariance_diagonals.rows() == t.states.rows());
    CHECK(t.covariance_diagonals.cols() == t.states.cols());
    CHECK(t.states.allFinite());
    CHECK(t.covariance_diagonals.allFinite());
    CHECK((t.covariance_diagonals.array() >= 0.0).all());
  }
}

bool same(const TrackSet& a, const TrackSet& b) {
  if (a.tracks.size() != b.tracks.size()) return false;
  for (std::size_t t = 0; t < a.tracks.size(); ++t) {
    const Track& x = a.tracks[t];
    const Track& y = b.tracks[t];
    if (x.id != y.id || x.first_scan != y.first_scan || x.confirmed != y.confirmed || x.states != y.states ||
        x.covariance_diagonals != y.covariance_diagonals)
      return false;
  }
  return true;
}

}  // namespace

TEST_CASE("tracker contract: the registry holds jdt-vb and mptf", "[contract]") {
  const auto& entries = tracking_tracker_registry().entries();
  CHECK(entries.count("jdt-vb") == 1);
  CHECK(entries.count("mptf") == 1);
  for (const auto& [name, entry] : entries) {
    CHECK(name == entry.name);
    CHECK_FALSE(entry.summary.empty());
  }
}

TEST_CASE("tracker contract: every tracker returns valid tracks that depend only on the run", "[contract]") {
  const std::vector<TrackingScenarioSample> runs = {othr_run(0.75, 125.0, 8, 0), othr_run(1.0, 0.0, 6, 1),
                                                    othr_run(1e-9, 20.0, 5, 2), othr_run(0.4, 400.0, 6, 3)};
  for (const auto& [name, entry] : tracking_tracker_registry().entries()) {
    if (name.rfind("test-", 0) == 0) continue;  // test-only trackers of other test files
    INFO("tracker " << name);
    auto reused = make_tracker(name);
    std::vector<TrackSet> first(runs.size());
    for (std::size_t r = 0; r < runs.size(); ++r) {
      INFO("run " << r);
      SolveReport report;
      reused->run(runs[r].problem, first[r], report);
      if (!report.skipped.empty()) continue;
      check_valid(first[r], runs[r].problem);
    }
    // No detections at all (pd 1e-9): nothing is confirmed.
    for (const Track& t : first[2].tracks) CHECK_FALSE(t.confirmed);
    for (std::size_t r = 0; r < runs.size(); ++r) {
      auto fresh = make_tracker(name);
      TrackSet again;
      SolveReport report;
      fresh->run(runs[r].problem, again, report);
      CHECK(same(first[r], again));
    }
  }
}

}  // namespace DABENCH_TEST_FILE
