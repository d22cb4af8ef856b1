// Tests of MPTF (algorithms/tracking/mptf.hpp): the PDA update against
// the UKF update it reduces to, M/N logic on hand-made detection sequences, slant ↔ ground
// conversion and fusion on noiseless multipath slant states, the whole tracker on the clutter-free
// OTHR scenario against bounds from the noise levels, registry options and determinism.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <numbers>
#include <optional>
#include <vector>

#include "algorithms/tracking/chi_square.hpp"
#include "algorithms/tracking/mptf.hpp"
#include "algorithms/tracking/ukf.hpp"
#include "harness/tracking/metrics.hpp"
#include "harness/tracking/registry.hpp"
#include "scenarios/tracking/othr.hpp"
#include "tests/support/tracker_runs.hpp"

namespace DABENCH_TEST_FILE {

namespace {

using dabench::mptf::Estimate;
using dabench::mptf::Matrix4;
using dabench::mptf::Vector4;

constexpr std::uint64_t kSeed = 20190558;

dabench::TrackingScenarioSample othr_sample(const std::vector<dabench::KeyValue>& settings, std::uint32_t trial) {
  const dabench::OthrScenario scenario(dabench::make_options<dabench::OthrOptions>(settings, "othr"));
  dabench::TrackingScenarioSample sample;
  dabench::RandomStream rng(kSeed, 0, trial);
  scenario.generate(rng, sample);
  return sample;
}


const dabench::othr::OthrMeasurementModel& othr_sensor() {
  static const dabench::othr::OthrMeasurementModel sensor(5.0, 0.001, 0.003);
  return sensor;
}

}  // namespace

TEST_CASE("mptf: PDA with one gated measurement, P_D = 1 and no clutter is the UKF update", "[mptf]") {
  Estimate track;
  track.mean = Vector4(1800.0, 0.1, 0.5, 1e-4);
  Eigen::Matrix4d A;
  A << 6.0, 0.01, 0.2, 0.001, 0.0, 2e-3, 0.0, 1e-5, 0.0, 0.0, 4e-3, 2e-5, 0.0, 0.0, 0.0, 1e-4;
  track.covariance = A * A.transpose();
  dabench::mptf::PdaModel model;
  model.noise = Eigen::Vector3d(25.0, 1e-6, 9e-6).asDiagonal();
  model.pd = 1.0;
  model.pg = 0.971;
  model.gate = dabench::chi_square_quantile(model.pg, 3);
  model.clutter_density = 0.0;
  // One measurement in the gate and one far outside it (ignored).
  Eigen::MatrixXd scan(3, 2);
  scan.col(0) << 1804.0, 0.1012, 0.503;
  scan.col(1) << 1900.0, 0.1, 0.5;
  dabench::ScanIndex index;
  index.build(scan);
  dabench::mptf::PdaScratch scratch;
  std::vector<char> gated(2, 0);
  Estimate pda = track;
  REQUIRE(dabench::mptf::pda_update(pda, scan, index, model, scratch, gated) == 1);
  CHECK(gated == std::vector<char>{1, 0});

  dabench::UnscentedModel ukf_model;
  ukf_model.transition = [](const dabench::Vector& x) { return x; };
  ukf_model.process_covariance = Eigen::Matrix4d::Zero();
  ukf_model.measure = [](const dabench::Vector& x) { return dabench::Vector(x.head(3)); };
  std::vector<std::optional<dabench::ScanMeasurement>> scans{dabench::ScanMeasurement{scan.col(0), model.noise}};
  const auto ukf = dabench::unscented_filter({track.mean, track.covariance}, scans, ukf_model);
  for (int i = 0; i < 4; ++i) {
    INFO("component " << i);
    CHECK(pda.mean[i] == Approx(ukf[0].mean[i]).epsilon(1e-12).margin(1e-14));
    for (int j = 0; j < 4; ++j) {
      CHECK(pda.covariance(i, j) == Approx(ukf[0].covariance(i, j)).epsilon(1e-9).margin(1e-14 * std::abs(A(i, i) * A(j, j))));
    }
  }
}

TEST_CASE("mptf: PDA weights with clutter follow beta_0 = b / (b + sum e)", "[mptf]") {
  // Two gated measurements; compare the posterior mean with the hand-computed PDA combination.
  Estimate track{Vector4(1800.0, 0.0, 0.5, 0.0), Eigen::Vector4d(16.0, 4e-6, 1e-5, 1e-8).asDiagonal()};
  dabench::mptf::PdaModel model;
  model.noise = Eigen::Vector3d(9.0, 1e-6, 4e-6).asDiagonal();
  model.pd = 0.75;
  model.pg = 0.971;
  model.gate = dabench::chi_square_quantile(model.pg, 3);
  model.clutter_density = 0.5;
  Eigen::MatrixXd scan(3, 2);
  scan.col(0) << 1803.0, 0.001, 0.502;
  scan.col(1) << 1796.0, -0.002, 0.499;
  dabench::ScanIndex index;
  index.build(scan);
  dabench::mptf::PdaScratch scratch;
  std::vector<char> gated(2, 0);
  Estimate pda = track;
  REQUIRE(dabench::mptf::pda_update(pda, scan, index, model, scratch, gated) == 2);
  // Diagonal S = P⁻ + R: innovations scaled per coordinate.
  const Eigen::Vector3d S(25.0, 5e-6, 1.4e-5);
  const Eigen::Vector3d nu0 = scan.col(0) - track.mean.head<3>(), nu1 = scan.col(1) - track.mean.head<3>();
  const double e0 = std::exp(-0.5 * nu0.cwiseAbs2().cwiseQuotient(S).sum());
  const double e1 = std::exp(-0.5 * nu1.cwiseAbs2().cwiseQuotient(S).sum());
  const double b = 0.5 * std::pow(2.0 * std::numbers::pi, 1.5) * std::sqrt(S.prod()) * (1.0 - 0.75 * 0.971) / 0.75;
  const Eigen::Vector3d nu = (e0 * nu0 + e1 * nu1) / (b + e0 + e1);
  const Eigen::Vector3d gain = Eigen::Vector3d(16.0, 4e-6, 1e-5).cwiseQuotient(S);
  for (int i = 0; i < 3; ++i) CHECK(pda.mean[i] == Approx(track.mean[i] + gain[i] * nu[i]).epsilon(1e-12));
  CHECK(pda.mean[3] == track.mean[3]);  // uncorrelated azimuth rate is untouched
  // Covariance of the range: P⁻ − (1 − β_0) K S K + K² (Σβν² − ν²).
  const double beta0 = b / (b + e0 + e1);
  const double spread = (e0 * nu0[0] * nu0[0] + e1 * nu1[0] * nu1[0]) / (b + e0 + e1) - nu[0] * nu[0];
  CHECK(pda.covariance(0, 0) ==
        Approx(16.0 - (1.0 - beta0) * gain[0] * gain[0] * S[0] + gain[0] * gain[0] * spread).epsilon(1e-12));
}

TEST_CASE("mptf: M/N logic 1/3 confirms and deletes on hand-made sequences", "[mptf]") {
  using dabench::mptf::TrackLogic;
  auto play = [](TrackLogic logic, const std::vector<int>& hits, std::vector<int>* confirmed_at, int* deleted_at) {
    *deleted_at = -1;
    for (std::size_t k = 0; k < hits.size(); ++k) {
      logic.record(hits[k] != 0);
      if (logic.confirmed() && confirmed_at->empty()) confirmed_at->push_back(static_cast<int>(k));
      if (logic.deleted()) {
        *deleted_at = static_cast<int>(k);
        return;
      }
    }
  };
  std::vector<int> confirmed;
  int deleted = 0;
  play(TrackLogic(1, 3, 3), {0, 0, 1, 0, 0, 1, 0, 0, 0, 1}, &confirmed, &deleted);
  CHECK(confirmed == std::vector<int>{2});  // 1 of 3 met at the third scan
  CHECK(deleted == 8);                      // three consecutive misses after confirmation
  confirmed.clear();
  play(TrackLogic(1, 3, 3), {0, 0, 0, 1}, &confirmed, &deleted);
  CHECK(confirmed.empty());
  CHECK(deleted == 2);  // window of three ends empty
  confirmed.clear();
  play(TrackLogic(1, 3, 5), {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0}, &confirmed, &deleted);
  CHECK(confirmed == std::vector<int>{0});
  CHECK(deleted == 10);  // four misses survive, the fifth in a row deletes
  confirmed.clear();
  play(TrackLogic(2, 3, 3), {1, 0, 1}, &confirmed, &deleted);
  CHECK(confirmed == std::vector<int>{2});
  confirmed.clear();
  play(TrackLogic(2, 3, 3), {1, 0, 0, 1}, &confirmed, &deleted);
  CHECK(confirmed.empty());
  CHECK(deleted == 2);
}

TEST_CASE("mptf: slant-state Jacobian matches central differences", "[mptf]") {
  const auto& sensor = othr_sensor();
  const Vector4 x(1750.0, 0.1, 0.48, 8.7e-5);
  for (int tau = 0; tau < 4; ++tau) {
    const Matrix4 J = dabench::mptf::slant_state_jacobian(sensor, tau, x);
    const double steps[4] = {1e-3, 1e-6, 1e-7, 1e-9};
    for (int c = 0; c < 4; ++c) {
      Vector4 plus = x, minus = x;
      plus[c] += steps[c];
      minus[c] -= steps[c];
      const Vector4 numeric = (dabench::mptf::slant_state(sensor, tau, plus) - dabench::mptf::slant_state(sensor, tau, minus)) /
                              (2.0 * steps[c]);
      for (int r = 0; r < 4; ++r) {
        INFO("path " << tau << " row " << r << " column " << c);
        CHECK(J(r, c) == Approx(numeric[r]).epsilon(1e-5).margin(1e-9 * std::max(1.0, std::abs(numeric[r]))));
      }
    }
  }
}

TEST_CASE("mptf: fusing noiseless slant states of the four paths recovers the ground state", "[mptf]") {
  const auto& sensor = othr_sensor();
  const Vector4 truth(1850.0, 0.2, 0.54, 8.7e-5);
  const Matrix4 slant_covariance = Eigen::Vector4d(4.0, 1e-7, 2e-6, 1e-9).asDiagonal();
  std::vector<Estimate> ground(4);
  for (int tau = 0; tau < 4; ++tau) {
    const Estimate slant{dabench::mptf::slant_state(sensor, tau, truth), slant_covariance};
    REQUIRE(dabench::mptf::ground_from_slant(sensor, tau, slant, 20, ground[tau]));
    INFO("path " << tau);
    CHECK((ground[tau].mean - truth).cwiseQuotient(Vector4(1e-8, 1e-12, 1e-12, 1e-15)).cwiseAbs().maxCoeff() < 1.0);
  }
  // Distinct paths see the same target at slant ranges tens of km apart.
  CHECK(std::abs(dabench::mptf::slant_state(sensor, 3, truth)[0] - dabench::mptf::slant_state(sensor, 0, truth)[0]) > 50.0);
  const Estimate* members[4] = {&ground[0], &ground[1], &ground[2], &ground[3]};
  Estimate fused;
  const double chi2 = dabench::mptf::fuse(members, 4, fused);
  CHECK(chi2 < 1e-12);
  CHECK(std::abs(fused.mean[0] - truth[0]) < 1e-8);
  CHECK(std::abs(fused.mean[2] - truth[2]) < 1e-12);
  // Fused information is the sum: the range variance falls below every member's.
  for (int tau = 0; tau < 4; ++tau) CHECK(fused.covariance(0, 0) < ground[tau].covariance(0, 0));

  // Swapping two paths' labels (EE ↔ FF) gives ground estimates that disagree strongly.
  Estimate swapped_ee, swapped_ff;
  REQUIRE(dabench::mptf::ground_from_slant(sensor, 3, {dabench::mptf::slant_state(sensor, 0, truth), slant_covariance}, 20, swapped_ee));
  REQUIRE(dabench::mptf::ground_from_slant(sensor, 0, {dabench::mptf::slant_state(sensor, 3, truth), slant_covariance}, 20, swapped_ff));
  const Estimate* wrong[4] = {&swapped_ee, &ground[1], &ground[2], &swapped_ff};
  CHECK(dabench::mptf::fuse(wrong, 4, fused) > 1000.0);
}

TEST_CASE("mptf: without clutter and with pd = 1 every OTHR target gets one accurate track", "[mptf]") {
  for (std::uint32_t trial = 0; trial < 3; ++trial) {
    INFO("trial " << trial);
    const auto sample = othr_sample({{"pd", "1"}, {"clutter", "0"}}, trial);
    const dabench::TrackSet tracks = dabench::test::solved_tracks("mptf", sample.problem);
    const auto m = dabench::compute_tracking_metrics(sample.truth, tracks, dabench::TrackingMetricsOptions{});
    CHECK(m.nvt == 4.0);
    CHECK(m.nft == 0.0);
    CHECK(m.tpd > 0.95);
    // Bounds from the noise (E|e| = 0.8σ for a normal error): fusing four paths' single-scan
    // measurements gives σ_g ≈ σ_r/2 = 2.5 km, E|e| = 2.0 km, which filtering must beat; in
    // bearing, one path's single scan gives σ_ϑ ≈ σ_ζ = 3 mrad, E|e| = 2.4 mrad (the EF/FE
    // PDA bias of the header keeps MPTF at about that four-path level, 1.2 mrad).
    CHECK(m.aee_range_km < 2.0);
    CHECK(m.aee_bearing_rad < 2.4e-3);
  }
}

TEST_CASE("mptf: tracks end miss_limit scans after the last detection, 3 or 5 by clutter", "[mptf]") {
  // One target (Table III target 1), noiseless detections on paths EE, FE, FF at scans 0..9,
  // nothing afterwards. Its three slant tracks pair at scan 1, confirm at scan 2 (1/3) and
  // form a confirmed fused track back-filled to scan 0; after the last detection they coast
  // and are deleted at the miss_limit-th empty scan, so the fused track's last scan is
  // 9 + miss_limit − 1. N_c only sets the clutter density and the default miss_limit.
  auto sample = othr_sample({{"pd", "1"}, {"clutter", "0"}, {"scans", "16"}, {"process_psd", "0"}}, 0);
  dabench::TrackingProblem& problem = sample.problem;
  const Eigen::MatrixXd truth = sample.truth.targets[0].states;
  for (int k = 0; k < problem.scan_count(); ++k) {
    problem.scans[k].resize(3, k <= 9 ? 3 : 0);
    if (k > 9) continue;
    int column = 0;
    for (int tau : {0, 2, 3}) {
      problem.scans[k].col(column++) = dabench::othr::slant_measurement(truth.col(k), dabench::othr::kPathTable[tau]);
    }
  }
  struct Case {
    double clutter;
    const char* spec;
    int last_scan;
  };
  for (const Case& c : {Case{125.0, "mptf", 11}, Case{400.0, "mptf", 13}, Case{400.0, "mptf:deletion_misses=4", 12}}) {
    INFO("clutter " << c.clutter << " spec " << c.spec);
    problem.clutter_mean = c.clutter;
    const dabench::TrackSet tracks = dabench::test::solved_tracks(c.spec, problem);
    int confirmed = 0;
    for (const dabench::Track& track : tracks.tracks) {
      if (!track.confirmed) continue;
      ++confirmed;
      CHECK(track.first_scan == 0);
      CHECK(track.first_scan + track.length() - 1 == c.last_scan);
      for (int i = 0; i < track.length() && track.first_scan + i <= 9; ++i) {
        const int k = track.first_scan + i;
        CHECK(std::abs(track.states(0, i) - truth(0, k)) < 1.0);     // km
        CHECK(std::abs(track.states(2, i) - truth(2, k)) < 2e-4);    // rad
      }
    }
    CHECK(confirmed == 1);
  }
}

TEST_CASE("mptf: registry builds from a SPEC and rejects bad options", "[mptf]") {
  const auto* entry = dabench::tracking_tracker_registry().find("mptf");
  REQUIRE(entry != nullptr);
  CHECK_NOTHROW(dabench::make_tracker("mptf:pg=0.99,confirm_hits=2,confirm_scans=3,deletion_misses=4"));
  CHECK_THROWS_AS(dabench::make_tracker("mptf:pg=1"), dabench::InputError);
  CHECK_THROWS_WITH(dabench::make_tracker("mptf:confirm_hits=4"), Catch::Contains("confirm_hits"));
  CHECK_THROWS_AS(dabench::make_tracker("mptf:deletion_misses=-1"), dabench::InputError);
  CHECK_THROWS_AS(dabench::make_tracker("mptf:max_azimuth_rate=0"), dabench::InputError);
  CHECK_THROWS_AS(dabench::make_tracker("mptf:fusion_pg=abc"), dabench::InputError);
  CHECK_THROWS_AS(dabench::make_tracker("mptf:nokey=1"), dabench::InputError);
  // A problem the tracker cannot read is an input error too.
  dabench::TrackingProblem empty;
  dabench::TrackSet tracks;
  dabench::SolveReport report;
  CHECK_THROWS_AS(dabench::make_tracker("mptf")->run(empty, tracks, report), dabench::InputError);
}

TEST_CASE("mptf: same input gives identical tracks", "[mptf]") {
  const auto sample = othr_sample({{"pd", "0.75"}, {"clutter", "125"}}, 7);
  const dabench::TrackSet a = dabench::test::solved_tracks("mptf", sample.problem);
  const dabench::TrackSet b = dabench::test::solved_tracks("mptf", sample.problem);
  REQUIRE(a.tracks.size() == b.tracks.size());
  REQUIRE(!a.tracks.empty());
  for (std::size_t i = 0; i < a.tracks.size(); ++i) {
    CHECK(a.tracks[i].first_scan == b.tracks[i].first_scan);
    CHECK(a.tracks[i].states == b.tracks[i].states);
    CHECK(a.tracks[i].covariance_diagonals == b.tracks[i].covariance_diagonals);
    CHECK(a.tracks[i].states.allFinite());
  }
}

}  // namespace DABENCH_TEST_FILE
