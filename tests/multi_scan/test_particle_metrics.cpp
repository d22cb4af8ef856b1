// Tests of the HPD value (eq 92) and entropy of particle beliefs (harness/multi_scan/particle_metrics.hpp):
// closed forms on hand-made beliefs, and calibration — when the truth is drawn from the
// represented distribution, HPD values are Uniform(0, 1) (one-sample Kolmogorov–Smirnov test at
// a fixed seed, 5 % critical value 1.358/√n) — for the bearings scenario's initial particle
// beliefs and for exact single-track posteriors after 4 and 12 scans (ranked by density and by
// likelihood); the likelihood ranking against a brute-force sort; and power: an
// overconfident belief (the posterior squared) is rejected.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "harness/core/params.hpp"
#include "harness/multi_scan/particle_metrics.hpp"
#include "harness/multi_scan/registry.hpp"
#include "scenarios/multi_scan/bearings.hpp"
#include "tests/support/kolmogorov_smirnov.hpp"

namespace DABENCH_TEST_FILE {

namespace {

using dabench::KeyValue;
using dabench::MultiScanBeliefs;
using dabench::MultiScanSample;
using dabench::RandomStream;
using dabench::SolveReport;
using dabench::Vector;
using dabench::test::ks_critical_5_percent;
using dabench::test::ks_uniform_statistic;

constexpr std::uint64_t kSeed = 92;

dabench::BearingsScenario scenario_with(const std::vector<KeyValue>& settings) {
  return dabench::BearingsScenario(dabench::make_options<dabench::BearingsOptions>(settings, "bearings"));
}

// HPD of the truth for each target of `draws` draws, ranked by density (eq 92) and by likelihood;
// `posterior` turns a sample into beliefs.
struct HpdValues {
  std::vector<double> density, likelihood;
};

template <class Posterior>
HpdValues hpd_values(const dabench::BearingsScenario& scenario, int draws, Posterior&& posterior) {
  HpdValues values;
  MultiScanSample sample;
  for (int k = 0; k < draws; ++k) {
    RandomStream rng(kSeed, 0, static_cast<std::uint32_t>(k));
    scenario.generate(rng, sample);
    const std::vector<Vector> beliefs = posterior(sample);
    for (int i = 0; i < sample.problem.tracks(); ++i) {
      const auto metrics = dabench::particle_belief_metrics(beliefs[i], sample.density_scale[i], sample.problem.prior[i],
                                                            sample.truth_probe[i]);
      values.density.push_back(metrics.hpd);
      values.likelihood.push_back(metrics.hpd_likelihood);
    }
  }
  return values;
}

std::vector<Vector> prior_beliefs(const MultiScanSample& sample) {
  std::vector<Vector> beliefs;
  for (const Vector& prior : sample.problem.prior) beliefs.push_back(prior / prior.sum());
  return beliefs;
}

// Exact Bayes for independent single tracks (one target per draw): q(p) ∝ ψ(p) Π_t Σ_j ψ_t(p, j).
std::vector<Vector> exact_single_track(const MultiScanSample& sample) {
  std::vector<Vector> beliefs = prior_beliefs(sample);
  for (const auto& scan : sample.problem.scans) {
    for (int i = 0; i < sample.problem.tracks(); ++i) {
      beliefs[i] = beliefs[i].cwiseProduct(scan.factor[i].rowwise().sum());
      beliefs[i] /= beliefs[i].sum();
    }
  }
  return beliefs;
}

}  // namespace

TEST_CASE("particle metrics: HPD and entropy of a hand-made belief", "[particle_metrics]") {
  // Four particles and a probe (index 4). Densities q·s: 0.4·1 = 0.4, 0.3·2 = 0.6, 0.2·1 = 0.2,
  // 0.1·10 = 1.0; probe 1e-6·3e5 = 0.3. Particles at least as dense as the truth: 0, 1, 3
  // carrying 0.4 + 0.3 + 0.1 (of total particle mass 1) → HPD 0.8.
  Vector q(5), s(5);
  q << 0.4, 0.3, 0.2, 0.1, 1e-6;
  s << 1.0, 2.0, 1.0, 10.0, 3e5;
  const auto metrics = dabench::particle_belief_metrics(q, s, Vector::Ones(q.size()), 4);
  CHECK(metrics.hpd == Approx(0.8).epsilon(1e-6));
  // Entropy −Σ q̃ log(q̃ s) with q̃ = q/(1) (probe excluded; masses renormalised).
  const double expected = -(0.4 * std::log(0.4) + 0.3 * std::log(0.6) + 0.2 * std::log(0.2) + 0.1 * std::log(1.0));
  CHECK(metrics.entropy == Approx(expected).epsilon(1e-6));
  // A truth denser than every particle has HPD 0; sparser than every particle, HPD 1.
  q[4] = 1.0;
  CHECK(dabench::particle_belief_metrics(q, s, Vector::Ones(q.size()), 4).hpd == 0.0);
  q[4] = 1e-12;
  CHECK(dabench::particle_belief_metrics(q, s, Vector::Ones(q.size()), 4).hpd == Approx(1.0));
}

TEST_CASE("particle metrics: the likelihood-ranked HPD is the belief mass of particles at least as likely as the truth",
          "[particle_metrics]") {
  // Random small problems: q, ψ, s arbitrary; brute force sorts the particles by q/ψ and sums
  // the renormalised belief of those ranked at or above the probe.
  RandomStream rng(kSeed, 5, 0);
  for (int trial = 0; trial < 50; ++trial) {
    const int n = 3 + trial % 7;
    Vector q(n + 1), prior(n + 1), s(n + 1);
    for (int p = 0; p <= n; ++p) {
      q[p] = rng.uniform(0.01, 1.0);
      prior[p] = rng.uniform(0.1, 2.0);
      s[p] = rng.uniform(0.5, 3.0);
    }
    if (trial % 5 == 0) q[1] = q[n] * prior[1] / prior[n];  // a tie with the truth counts as at least as likely
    std::vector<std::pair<double, double>> ranked;  // (likelihood, q) of the particles
    double mass = 0.0;
    for (int p = 0; p < n; ++p) {
      ranked.push_back({q[p] / prior[p], q[p]});
      mass += q[p];
    }
    std::sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    double above = 0.0;
    for (const auto& [likelihood, weight] : ranked) {
      if (likelihood < q[n] / prior[n]) break;
      above += weight;
    }
    INFO("trial " << trial);
    CHECK(dabench::particle_belief_metrics(q, s, prior, n).hpd_likelihood == Approx(above / mass).epsilon(1e-12));
  }
  // With ψ ∝ 1/s (the density's scale) both rankings coincide.
  Vector q(5), s(5);
  q << 0.4, 0.3, 0.2, 0.1, 1e-6;
  s << 1.0, 2.0, 1.0, 10.0, 3e5;
  const auto metrics = dabench::particle_belief_metrics(q, s, s.cwiseInverse(), 4);
  CHECK(metrics.hpd_likelihood == Approx(metrics.hpd).epsilon(1e-12));
}

TEST_CASE("particle metrics: entropy of uniform weights over particles from a known density", "[particle_metrics]") {
  // Equal weights over N particles, scale N·g with g the uniform density on a 200×200 square:
  // the entropy of that uniform density, log(40000).
  const int n = 1000;
  Vector q = Vector::Constant(n + 1, 1.0 / n), s = Vector::Constant(n + 1, n / 40000.0);
  q[n] = 1e-9;
  CHECK(dabench::particle_belief_metrics(q, s, Vector::Ones(q.size()), n).entropy == Approx(std::log(40000.0)).epsilon(1e-6));
}

TEST_CASE("particle metrics: HPD of the truth under the initial bearing posterior is uniform", "[particle_metrics]") {
  // The truth is uniform on the region and the initialising bearing is measured from it, so
  // given that bearing the truth is a draw from π0, which the weighted particles represent.
  const auto scenario = scenario_with({{"particles", "2000"}, {"mean_targets", "8"}, {"poisson_targets", "0"}});
  const std::vector<double> values = hpd_values(scenario, 100, prior_beliefs).density;
  REQUIRE(values.size() == 800);
  const double d = ks_uniform_statistic(values);
  INFO("KS D = " << d << ", 5% critical value " << ks_critical_5_percent(values.size()));
  CHECK(d < ks_critical_5_percent(values.size()));
}

TEST_CASE("particle metrics: HPD of the truth under the exact single-track posterior is uniform", "[particle_metrics][release-only]") {
  for (const char* rounds : {"1", "3"}) {
    const auto scenario = scenario_with({{"particles", "10000"}, {"mean_targets", "1"}, {"poisson_targets", "0"},
                                         {"scans_per_sensor", rounds}});
    const HpdValues values = hpd_values(scenario, 400, exact_single_track);
    REQUIRE(values.density.size() == 400);
    // Both rankings: by the density (eq 92) and by the likelihood q/ψ.
    for (const auto* ranked : {&values.density, &values.likelihood}) {
      const double d = ks_uniform_statistic(*ranked);
      INFO("scans_per_sensor " << rounds << (ranked == &values.density ? ", density" : ", likelihood") << ": KS D = " << d
                               << ", 5% critical value " << ks_critical_5_percent(400));
      CHECK(d < ks_critical_5_percent(400));
    }
  }
}

TEST_CASE("particle metrics: an overconfident belief fails the uniformity test", "[particle_metrics]") {
  // Squaring the exact posterior halves its spread: the truth falls in its tails too often.
  const auto scenario = scenario_with({{"particles", "10000"}, {"mean_targets", "1"}, {"poisson_targets", "0"}});
  const std::vector<double> values = hpd_values(scenario, 400, [](const MultiScanSample& sample) {
    std::vector<Vector> beliefs = exact_single_track(sample);
    for (int i = 0; i < sample.problem.tracks(); ++i) {
      // q²/ψ keeps the prior's importance weights and squares the likelihood.
      beliefs[i] = beliefs[i].cwiseProduct(beliefs[i]).cwiseQuotient(sample.problem.prior[i]);
      beliefs[i] /= beliefs[i].sum();
    }
    return beliefs;
  }).density;
  const double d = ks_uniform_statistic(values);
  INFO("KS D = " << d);
  CHECK(d > 2.0 * ks_critical_5_percent(values.size()));
}

}  // namespace DABENCH_TEST_FILE
