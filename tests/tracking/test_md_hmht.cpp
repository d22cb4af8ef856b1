// Tests of MD-HMHT (algorithms/tracking/md_hmht.hpp): the track filter's gates and costs against
// per-path unscented transforms and ψ computed from its definition, its multi-path update against
// the UKF on the stacked measurement, one noiseless target giving one exact track, the OTHR
// scenario against Table IV-level bounds, the hypothesis settings, options and determinism.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include <Eigen/LU>

#include "algorithms/tracking/chi_square.hpp"
#include "algorithms/tracking/md_hmht_tracks.hpp"
#include "harness/core/errors.hpp"
#include "harness/core/random_stream.hpp"
#include "harness/tracking/metrics.hpp"
#include "harness/tracking/registry.hpp"
#include "scenarios/tracking/othr.hpp"
#include "tests/support/tracker_runs.hpp"

namespace DABENCH_TEST_FILE {

namespace {

dabench::TrackingScenarioSample draw(double pd, double clutter, int run, int scans = 30) {
  dabench::OthrOptions o;
  o.pd = pd;
  o.clutter = clutter;
  o.scans = scans;
  dabench::TrackingScenarioSample sample;
  dabench::RandomStream rng(2024, 0, static_cast<std::uint32_t>(run));
  dabench::OthrScenario(o).generate(rng, sample);
  return sample;
}


// The problem of `sample` with target 0's noiseless detections on `paths` at scans 0..last only.
dabench::TrackingProblem one_target(const dabench::TrackingScenarioSample& sample, const std::vector<int>& paths,
                                    int last) {
  dabench::TrackingProblem problem = sample.problem;
  const Eigen::MatrixXd& truth = sample.truth.targets[0].states;
  for (int k = 0; k < problem.scan_count(); ++k) {
    problem.scans[k].resize(3, k <= last ? static_cast<int>(paths.size()) : 0);
    if (k > last) continue;
    for (std::size_t c = 0; c < paths.size(); ++c) {
      problem.scans[k].col(static_cast<int>(c)) =
          dabench::othr::slant_measurement(truth.col(k), dabench::othr::kPathTable[paths[c]]);
    }
  }
  return problem;
}

}  // namespace

TEST_CASE("md-hmht filter: gates and costs are the per-path UKF predictions and -ln psi", "[md_hmht]") {
  const auto sample = draw(0.75, 125.0, 3);
  const dabench::TrackingProblem& problem = sample.problem;
  const double pg = 0.971;
  const dabench::md_hmht::TrackFilter filter(problem, pg);
  dabench::md_hmht::TrackNode node;
  node.estimate.mean = sample.truth.targets[0].states.col(4);
  Eigen::Matrix4d A;
  A << 2.0, 0.0, 0.0, 0.0, 1e-3, 2e-3, 0.0, 0.0, 0.0, 0.0, 1e-3, 0.0, 0.0, 0.0, 2e-6, 1e-5;
  node.estimate.covariance = A * A.transpose();
  node.scan = 4;
  const Eigen::MatrixXd& scan = problem.scans[5];
  dabench::ScanIndex index;
  index.build(scan);
  dabench::md_hmht::TrackPrediction p;
  filter.predict(node, scan, index, p);

  const Eigen::MatrixXd predicted_covariance =
      problem.transition * node.estimate.covariance * problem.transition.transpose() + problem.process_covariance;
  const dabench::Gaussian x{problem.transition * node.estimate.mean, predicted_covariance};
  const double gate = dabench::chi_square_quantile(pg, 3);
  const double lambda = problem.clutter_mean / problem.region_volume();
  int gated = 0;
  for (int tau = 0; tau < 4; ++tau) {
    const auto u = dabench::unscented_transform(x, [&](const dabench::Vector& s) { return problem.sensor->measure(tau, s); });
    const Eigen::MatrixXd S = u.covariance + problem.sensor->noise_covariance(tau);
    std::vector<std::pair<int, double>> expected;  // (measurement, −ln ψ) over all measurements in the gate
    for (int j = 0; j < scan.cols(); ++j) {
      const Eigen::VectorXd d = scan.col(j) - u.mean;
      const double d2 = d.dot(S.inverse() * d);
      if (d2 > gate) continue;
      const double density = std::exp(-0.5 * d2) / std::sqrt((2.0 * std::numbers::pi * S).determinant());
      const double psi = 0.75 * density / ((1.0 - 0.75 * pg) * lambda);
      expected.emplace_back(j, -std::log(psi));
    }
    INFO("path " << tau);
    REQUIRE(p.arcs[tau].size() == expected.size());
    std::sort(expected.begin(), expected.end());
    auto arcs = p.arcs[tau];
    std::sort(arcs.begin(), arcs.end(), [](const auto& a, const auto& b) { return a.measurement < b.measurement; });
    for (std::size_t i = 0; i < arcs.size(); ++i) {
      CHECK(arcs[i].measurement == expected[i].first);
      CHECK(arcs[i].cost == Approx(expected[i].second).epsilon(1e-9).margin(1e-9));
    }
    gated += static_cast<int>(arcs.size());
  }
  CHECK(gated >= 2);  // the target's own returns at p_d = 0.75 (scan 5 of this draw)
  CHECK(p.miss_log_sum == Approx(4.0 * std::log(1.0 - 0.75 * pg)).epsilon(1e-14));
}

TEST_CASE("md-hmht filter: an update with several paths is the UKF update on their stacked measurement", "[md_hmht]") {
  const auto sample = draw(1.0, 0.0, 1);
  const dabench::TrackingProblem& problem = sample.problem;
  const dabench::md_hmht::TrackFilter filter(problem, 0.971);
  auto node = std::make_shared<dabench::md_hmht::TrackNode>();
  node->estimate.mean = sample.truth.targets[1].states.col(2);
  node->estimate.mean[0] += 3.0;
  node->estimate.covariance = Eigen::Vector4d(16.0, 1e-5, 1e-5, 1e-9).asDiagonal();
  node->scan = 2;
  node->llr = 1.5;
  const Eigen::MatrixXd& scan = problem.scans[3];
  dabench::ScanIndex index;
  index.build(scan);
  dabench::md_hmht::TrackPrediction p;
  filter.predict(*node, scan, index, p);
  // Each path's own return (no clutter, p_d = 1): take paths 0 and 2.
  int measurement[4] = {-1, -1, -1, -1};
  double cost = 0.0;
  for (int tau : {0, 2}) {
    REQUIRE(!p.arcs[tau].empty());
    for (const auto& arc : p.arcs[tau]) {
      if (sample.truth.origin[3][arc.measurement].target != 1 || sample.truth.origin[3][arc.measurement].path != tau) continue;
      measurement[tau] = arc.measurement;
      cost += arc.cost;
    }
    REQUIRE(measurement[tau] >= 0);
  }
  const dabench::md_hmht::TrackNode next = filter.update(node, p, measurement, scan, 3, 99);

  dabench::Gaussian expected = p.predicted;
  dabench::ScanMeasurement y;
  y.value.resize(6);
  y.value << scan.col(measurement[0]), scan.col(measurement[2]);
  y.covariance = Eigen::MatrixXd::Zero(6, 6);
  y.covariance.topLeftCorner(3, 3) = problem.sensor->noise_covariance(0);
  y.covariance.bottomRightCorner(3, 3) = problem.sensor->noise_covariance(2);
  dabench::unscented_update(expected, y, [&](const dabench::Vector& s) {
    dabench::Vector h(6);
    h << problem.sensor->measure(0, s), problem.sensor->measure(2, s);
    return h;
  });
  for (int i = 0; i < 4; ++i) {
    CHECK(next.estimate.mean[i] == Approx(expected.mean[i]).epsilon(1e-10));
    for (int c = 0; c < 4; ++c) CHECK(next.estimate.covariance(i, c) == Approx(expected.covariance(i, c)).epsilon(1e-7).margin(1e-15));
  }
  CHECK(next.llr == Approx(1.5 + p.miss_log_sum - cost).epsilon(1e-14));
  CHECK(next.last_hit_scan == 3);
  CHECK(next.serial == 99);
  CHECK(next.previous.get() == node.get());
}

TEST_CASE("md-hmht: one target without clutter gives one exact track", "[md_hmht]") {
  const auto sample = draw(1.0, 0.0, 0, 20);
  for (const std::vector<int>& paths : {std::vector<int>{0, 1, 2, 3}, std::vector<int>{0, 2, 3}}) {
    INFO("paths " << paths.size());
    const dabench::TrackingProblem problem = one_target(sample, paths, 19);
    const dabench::TrackSet tracks = dabench::test::solved_tracks("md-hmht", problem);
    REQUIRE(tracks.tracks.size() == 1);
    const dabench::Track& track = tracks.tracks[0];
    CHECK(track.confirmed);
    CHECK(track.first_scan == 0);
    CHECK(track.length() == 20);
    const Eigen::MatrixXd& truth = sample.truth.targets[0].states;
    for (int k = 0; k < 20; ++k) {
      // Noiseless returns: the estimate converges on the truth (head from ≥ 3 paths at scan 0).
      CHECK(std::abs(track.states(0, k) - truth(0, k)) < (k < 3 ? 1.5 : 0.5));  // km
      CHECK(std::abs(track.states(2, k) - truth(2, k)) < 5e-4);                  // rad
    }
    // The state the metrics see: one valid track, no false one, detected at every scan.
    dabench::TrackingTruth one = sample.truth;
    one.targets.resize(1);
    const auto m = dabench::compute_tracking_metrics(one, tracks, {});
    CHECK(m.nvt == 1.0);
    CHECK(m.nft == 0.0);
    CHECK(m.tpd == 1.0);
  }
}

TEST_CASE("md-hmht: a track ends at its last return and is not reported past it", "[md_hmht]") {
  const auto sample = draw(1.0, 0.0, 0, 20);
  dabench::TrackingProblem problem = one_target(sample, {0, 1, 3}, 9);
  for (double clutter : {125.0, 400.0}) {
    problem.clutter_mean = clutter;  // density of the likelihood ratios and the 3 / 5 deletion rule
    const dabench::TrackSet tracks = dabench::test::solved_tracks("md-hmht", problem);
    REQUIRE(tracks.tracks.size() == 1);
    CHECK(tracks.tracks[0].first_scan == 0);
    CHECK(tracks.tracks[0].length() == 10);
  }
}

TEST_CASE("md-hmht: at pd = 0.75 and 125 clutter per scan it tracks all four targets", "[md_hmht]") {
  // Table IV, MD-HMHT at pd = 0.75, N_c = 125: NVT 3.88, TPD 0.96, NFT 0.40, AEE-R 2.47 km,
  // AEE-B 1.20 mrad, MOSPA 10.9 km. Eight runs; bounds leave room for Monte Carlo spread.
  std::vector<dabench::TrackingMetrics> runs;
  for (int run = 0; run < 8; ++run) {
    const auto sample = draw(0.75, 125.0, run);
    runs.push_back(dabench::compute_tracking_metrics(sample.truth, dabench::test::solved_tracks("md-hmht", sample.problem), {}));
  }
  const auto m = dabench::mean_over_runs(runs);
  CHECK(m.nvt >= 3.5);
  CHECK(m.tpd >= 0.9);
  CHECK(m.nft <= 1.0);
  CHECK(m.aee_range_km < 3.0);
  CHECK(m.aee_bearing_rad < 1.5e-3);
  CHECK(m.mospa_km < 15.0);
}

TEST_CASE("md-hmht: every hypothesis setting tracks the four targets without clutter", "[md_hmht]") {
  // Without clutter the only doubt is which of a target's paths took which return (FE and EF
  // returns share a range): every n, W and selection reading still gives one track per target.
  for (int run = 0; run < 2; ++run) {
    const auto sample = draw(1.0, 0.0, run);
    for (const char* spec : {"md-hmht:hypotheses=1,window=1", "md-hmht:hypotheses=5,window=4", "md-hmht:per_parent=1"}) {
      INFO(spec << ", run " << run);
      const auto m = dabench::compute_tracking_metrics(sample.truth, dabench::test::solved_tracks(spec, sample.problem), {});
      CHECK(m.nvt == 4.0);
      CHECK(m.nft == 0.0);
      CHECK(m.tpd > 0.95);
    }
  }
}

TEST_CASE("md-hmht: the same problem gives identical tracks", "[md_hmht][release-only]") {
  const auto sample = draw(0.4, 400.0, 5);
  const dabench::TrackSet a = dabench::test::solved_tracks("md-hmht", sample.problem);
  const dabench::TrackSet b = dabench::test::solved_tracks("md-hmht", sample.problem);
  REQUIRE(a.tracks.size() == b.tracks.size());
  for (std::size_t t = 0; t < a.tracks.size(); ++t) {
    CHECK(a.tracks[t].id == b.tracks[t].id);
    CHECK(a.tracks[t].first_scan == b.tracks[t].first_scan);
    CHECK(a.tracks[t].states == b.tracks[t].states);
    CHECK(a.tracks[t].covariance_diagonals == b.tracks[t].covariance_diagonals);
  }
}

TEST_CASE("md-hmht: options are checked", "[md_hmht]") {
  CHECK_NOTHROW(dabench::make_tracker("md-hmht:hypotheses=2,window=2,deletion_misses=4,per_parent=1,confirm_llr=5"));
  CHECK_THROWS_AS(dabench::make_tracker("md-hmht:hypotheses=-1"), dabench::InputError);
  CHECK_THROWS_AS(dabench::make_tracker("md-hmht:window=0"), dabench::InputError);
  CHECK_THROWS_AS(dabench::make_tracker("md-hmht:gate_probability=1"), dabench::InputError);
  CHECK_THROWS_WITH(dabench::make_tracker("md-hmht:confirm_llr=0"), Catch::Contains("confirm_llr"));
  CHECK_THROWS_AS(dabench::make_tracker("md-hmht:head_range=0"), dabench::InputError);
  CHECK_THROWS_AS(dabench::make_tracker("md-hmht:nokey=1"), dabench::InputError);
  auto tracker = dabench::make_tracker("md-hmht");
  dabench::TrackingProblem empty;
  dabench::TrackSet tracks;
  dabench::SolveReport report;
  tracker->run(empty, tracks, report);
  CHECK(report.skipped == "problem_without_multipath_sensor");
  auto sample = draw(0.75, 125.0, 0, 3);
  sample.problem.scans[1](0, 0) = std::nan("");
  CHECK_THROWS_WITH(tracker->run(sample.problem, tracks, report), Catch::Contains("not finite"));
}

}  // namespace DABENCH_TEST_FILE
