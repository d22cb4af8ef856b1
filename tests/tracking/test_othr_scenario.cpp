// Tests of the "othr" tracking scenario (jdt-vb-multipath-othr, Sec. IV-A, Tables II–III):
// draw statistics against their sampling distributions (tolerance 5 standard errors, fixed
// seeds), truth trajectories against constant-velocity propagation, the model handed to
// trackers, registry construction and determinism.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <vector>

#include <Eigen/Cholesky>

#include "harness/tracking/registry.hpp"
#include "scenarios/tracking/othr.hpp"
#include "tests/support/scenario_draws.hpp"

namespace DABENCH_TEST_FILE {

namespace {

using namespace dabench;
using dabench::test::RunningMoments;

constexpr std::uint64_t kSeed = 20190557;

constexpr auto scenario_from = &dabench::test::scenario_from<OthrScenario>;

}  // namespace

TEST_CASE("othr scenario: clutter count is Poisson with mean N_c and uniform over the region", "[othr_scenario]") {
  const OthrScenario scenario = scenario_from({{"clutter", "125"}});
  constexpr int kRuns = 200;
  RunningMoments count;
  RunningMoments coordinate[3];
  TrackingScenarioSample sample;
  for (int run = 0; run < kRuns; ++run) {
    RandomStream rng(kSeed, 0, run);
    scenario.generate(rng, sample);
    int total = 0;
    for (int k = 0; k < sample.problem.scan_count(); ++k) {
      int clutter = 0;
      for (int j = 0; j < sample.problem.scans[k].cols(); ++j) {
        if (!sample.truth.origin[k][j].is_clutter()) continue;
        ++clutter;
        for (int c = 0; c < 3; ++c) coordinate[c].add(sample.problem.scans[k](c, j));
        const Eigen::Vector3d y = sample.problem.scans[k].col(j);
        REQUIRE((y.array() >= sample.problem.region_lower.array()).all());
        REQUIRE((y.array() <= sample.problem.region_upper.array()).all());
      }
      count.add(clutter);
      total += clutter;
    }
    REQUIRE(total == sample.truth.clutter);
  }
  // 6000 scans: se(mean) = √(125/6000) = 0.144; se(variance) ≈ √((λ + 2λ²)/n) = 2.29.
  CHECK(std::abs(count.mean() - 125.0) < 5.0 * 0.144);
  CHECK(std::abs(count.variance() - 125.0) < 5.0 * 2.29);
  // Uniform: mean at the centre of each side, se = width / √(12 n).
  const Eigen::Vector3d lower{1500.0, -0.524, 0.428}, upper{2000.0, 0.524, 0.608};
  for (int c = 0; c < 3; ++c) {
    INFO("coordinate " << c);
    const double width = upper[c] - lower[c];
    CHECK(std::abs(coordinate[c].mean() - 0.5 * (lower[c] + upper[c])) < 5.0 * width / std::sqrt(12.0 * coordinate[c].n));
    CHECK(std::abs(coordinate[c].variance() / (width * width / 12.0) - 1.0) < 5.0 * std::sqrt(0.8 / coordinate[c].n));
  }
}

TEST_CASE("othr scenario: detection rate of every path is pd", "[othr_scenario]") {
  for (const char* pd_text : {"0.75", "0.4"}) {
    const double pd = std::stod(pd_text);
    const OthrScenario scenario = scenario_from({{"pd", pd_text}, {"clutter", "0"}});
    constexpr int kRuns = 200;
    std::vector<double> detected(4, 0.0);
    double slots = 0.0;  // alive (target, scan) pairs, each a Bernoulli(pd) trial per path
    int dropped = 0;
    TrackingScenarioSample sample;
    for (int run = 0; run < kRuns; ++run) {
      RandomStream rng(kSeed, 1, run);
      scenario.generate(rng, sample);
      for (const auto& target : sample.truth.targets) {
        for (bool alive : target.alive) slots += alive ? 1.0 : 0.0;
      }
      for (const auto& scan : sample.truth.origin) {
        for (const auto& origin : scan) {
          REQUIRE(!origin.is_clutter());
          detected[origin.path] += 1.0;
        }
      }
      dropped += sample.truth.dropped_detections;
    }
    CHECK(slots == kRuns * (20.0 + 20.0 + 21.0 + 21.0));
    CHECK(dropped == 0);  // Table III targets stay well inside the region
    const double se = std::sqrt(pd * (1.0 - pd) / slots);  // 0.0034 (pd = 0.75), 0.0038 (0.4)
    for (int tau = 0; tau < 4; ++tau) {
      INFO("pd " << pd << " path " << dabench::othr::kPathTable[tau].name);
      CHECK(std::abs(detected[tau] / slots - pd) < 5.0 * se);
    }
  }
}

TEST_CASE("othr scenario: noise-free truth is constant-velocity propagation of Table III", "[othr_scenario]") {
  const OthrScenario scenario = scenario_from({{"process_psd", "0"}, {"clutter", "0"}});
  TrackingScenarioSample sample;
  RandomStream rng(kSeed, 2, 0);
  scenario.generate(rng, sample);
  REQUIRE(sample.truth.targets.size() == 4);
  const int first[4] = {0, 0, 9, 9}, last[4] = {19, 19, 29, 29};  // Table III lifetimes, 0-based
  for (int i = 0; i < 4; ++i) {
    const auto& target = sample.truth.targets[i];
    const Eigen::Vector4d x0 = OthrScenario::initial_state(i);
    for (int k = 0; k < 30; ++k) {
      INFO("target " << i << " scan " << k);
      const bool alive = k >= first[i] && k <= last[i];
      REQUIRE(target.alive[k] == alive);
      if (!alive) {
        CHECK(std::isnan(target.states(0, k)));
        continue;
      }
      const double t = 16.0 * (k - first[i]);
      const Eigen::Vector4d expected{x0[0] + x0[1] * t, x0[1], x0[2] + x0[3] * t, x0[3]};
      CHECK((target.states.col(k) - expected).cwiseAbs().maxCoeff() < 1e-9);
    }
  }
  // Targets 3 and 4 cross in ground range between the paper's scans 20 and 21 (0-based 19, 20).
  const auto& t3 = sample.truth.targets[2].states;
  const auto& t4 = sample.truth.targets[3].states;
  CHECK(t3(0, 19) < t4(0, 19));
  CHECK(t3(0, 20) > t4(0, 20));
  // Shorter runs cut the lifetimes: with K = 9 targets 3 and 4 never appear.
  const OthrScenario short_run = scenario_from({{"scans", "9"}, {"clutter", "0"}});
  RandomStream rng2(kSeed, 2, 1);
  short_run.generate(rng2, sample);
  REQUIRE(sample.problem.scan_count() == 9);
  CHECK(sample.truth.targets[0].alive[8]);
  CHECK(!sample.truth.targets[2].alive[8]);
  CHECK(sample.truth.targets[2].states.cols() == 9);
}

TEST_CASE("othr scenario: truth increments have the NCV process covariance Q", "[othr_scenario]") {
  const OthrScenario scenario = scenario_from({{"clutter", "0"}});
  constexpr int kRuns = 100;
  TrackingScenarioSample sample;
  RunningMoments whitened[4];
  for (int run = 0; run < kRuns; ++run) {
    RandomStream rng(kSeed, 3, run);
    scenario.generate(rng, sample);
    const Eigen::MatrixXd& F = sample.problem.transition;
    const Eigen::Matrix4d Q = sample.problem.process_covariance;
    const Eigen::Matrix4d L = Q.llt().matrixL();
    for (const auto& target : sample.truth.targets) {
      for (int k = 0; k + 1 < 30; ++k) {
        if (!target.alive[k] || !target.alive[k + 1]) continue;
        const Eigen::Vector4d v = target.states.col(k + 1) - F * target.states.col(k);
        const Eigen::Vector4d z = L.triangularView<Eigen::Lower>().solve(v);
        for (int c = 0; c < 4; ++c) whitened[c].add(z[c]);
      }
    }
  }
  // 100 runs × 78 transitions = 7800 draws per component: se(mean) = 0.0113, se(var) = 0.016.
  for (int c = 0; c < 4; ++c) {
    INFO("component " << c);
    REQUIRE(whitened[c].n == 7800.0);
    CHECK(std::abs(whitened[c].mean()) < 5.0 / std::sqrt(7800.0));
    CHECK(std::abs(whitened[c].variance() - 1.0) < 5.0 * std::sqrt(2.0 / 7800.0));
  }
}

TEST_CASE("othr scenario: measurement residuals against eq 57 of the truth have the stated sigmas", "[othr_scenario]") {
  const OthrScenario scenario = scenario_from({{"clutter", "0"}});
  constexpr int kRuns = 100;
  const double sigma[3] = {5.0, 0.001, 0.003};
  TrackingScenarioSample sample;
  RunningMoments residual[4][3];  // per path, per coordinate: residual / σ
  for (int run = 0; run < kRuns; ++run) {
    RandomStream rng(kSeed, 4, run);
    scenario.generate(rng, sample);
    for (int k = 0; k < sample.problem.scan_count(); ++k) {
      for (int j = 0; j < sample.problem.scans[k].cols(); ++j) {
        const auto origin = sample.truth.origin[k][j];
        const Eigen::Vector4d x = sample.truth.targets[origin.target].states.col(k);
        const Eigen::Vector3d h = dabench::othr::slant_measurement(x, dabench::othr::kPathTable[origin.path]);
        for (int c = 0; c < 3; ++c) residual[origin.path][c].add((sample.problem.scans[k](c, j) - h[c]) / sigma[c]);
      }
    }
  }
  for (int tau = 0; tau < 4; ++tau) {
    for (int c = 0; c < 3; ++c) {
      INFO("path " << tau << " coordinate " << c);
      const RunningMoments& m = residual[tau][c];
      REQUIRE(m.n > 5000.0);  // ≈ 100 · 82 · 0.75 = 6150
      CHECK(std::abs(m.mean()) < 5.0 / std::sqrt(m.n));
      CHECK(std::abs(m.variance() - 1.0) < 5.0 * std::sqrt(2.0 / m.n));
    }
  }
}

TEST_CASE("othr scenario: registry builds it and the model handed to trackers is the paper's", "[othr_scenario]") {
  const auto* entry = dabench::tracking_scenario_registry().find("othr");
  REQUIRE(entry != nullptr);
  const auto scenario = entry->create({{"pd", "0.4"}, {"clutter", "400"}});
  TrackingScenarioSample a, b, c;
  RandomStream rng_a(kSeed, 5, 0), rng_b(kSeed, 5, 0), rng_c(kSeed, 5, 1);
  scenario->generate(rng_a, a);
  scenario->generate(rng_b, b);
  scenario->generate(rng_c, c);
  REQUIRE(a.problem.scan_count() == 30);
  bool same = true, differs = false;
  for (int k = 0; k < 30; ++k) {
    same = same && a.problem.scans[k] == b.problem.scans[k];
    differs = differs || a.problem.scans[k].cols() != c.problem.scans[k].cols() ||
              a.problem.scans[k] != c.problem.scans[k];
  }
  CHECK(same);
  CHECK(differs);

  const dabench::TrackingProblem& p = a.problem;
  CHECK(p.scan_interval == 16.0);
  CHECK(p.transition(0, 1) == 16.0);
  CHECK(p.transition(2, 3) == 16.0);
  CHECK(p.process_covariance(0, 0) == Approx(1e-8 * 4096.0 / 3.0).epsilon(1e-14));
  CHECK(p.process_covariance(0, 1) == Approx(1e-8 * 128.0).epsilon(1e-14));
  CHECK(p.process_covariance(1, 1) == Approx(1e-8 * 16.0).epsilon(1e-14));
  CHECK(p.process_covariance(2, 2) == Approx(1e-8 / (1750.0 * 1750.0) * 4096.0 / 3.0).epsilon(1e-14));
  CHECK(p.process_covariance(0, 2) == 0.0);
  REQUIRE(p.detection_probability.size() == 4);
  for (double pd : p.detection_probability) CHECK(pd == 0.4);
  CHECK(p.region_volume() == Approx(500.0 * 1.048 * 0.18).epsilon(1e-14));
  CHECK(p.clutter_density() == Approx(400.0 / 94.32).epsilon(1e-14));
  REQUIRE(p.sensor->paths() == 4);
  const Eigen::Vector3d variances = p.sensor->noise_covariance(2).diagonal();
  CHECK(variances[0] == 25.0);
  CHECK(variances[1] == Approx(1e-6).epsilon(1e-14));
  CHECK(variances[2] == Approx(9e-6).epsilon(1e-14));

  CHECK_THROWS_AS(entry->create({{"pd", "0"}}), dabench::InputError);
  CHECK_THROWS_AS(entry->create({{"scans", "0"}}), dabench::InputError);
  CHECK_THROWS_AS(entry->create({{"clutter", "-1"}}), dabench::InputError);
}

}  // namespace DABENCH_TEST_FILE
