// Tests of the TBD-MB tracker (algorithms/tbd/tbd_mb.hpp, a reconstruction of docs/models/track-before-detect.md
// §4.1) on small hand-made problems (frames from tests/support/tbd_frames.hpp):
//  - One Bernoulli and no births: the update is the exact Bayes update under the likelihood on
//    the object's support, computed here from the model's equations on the same particles
//    (with and without exclusivity: one Bernoulli has nothing to exclude).
//  - Exclusivity: two Bernoullis on one object's cell share it (r̃₁ + r̃₂ ≤ 1), where
//    association = none and the non-interacting TBD-BP update make both certain; without
//    exclusivity the new Bernoullis around one object are each kept.
//  - An object appearing in a static scene is born from the Poisson intensity, reported near
//    the truth, and not duplicated in the neighbouring cells from its third step on.
//  - Pure noise: no estimates; the Poisson mass stays below its noise-free bound; without
//    recycling the cells' mass after an update is zero.
//  - Same seed ⇒ bit-identical output; bad options are InputErrors naming the field.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <numeric>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "algorithms/tbd/tbd_bp.hpp"
#include "algorithms/tbd/tbd_mb.hpp"
#include "harness/core/random_stream.hpp"
#include "harness/core/solve_report.hpp"
#include "harness/tbd/problem.hpp"
#include "harness/tbd/registry.hpp"
#include "tests/support/input_error.hpp"
#include "tests/support/tbd_frames.hpp"
#include "tests/support/tbd_runs.hpp"

namespace DABENCH_TEST_FILE {

namespace {

using namespace dabench;
using namespace dabench::test;

constexpr std::uint64_t kSeed = 20210901;

// estimates_per_step (tests/support/tbd_runs.hpp), also checking that every step converged.
EstimatesPerStep converged_estimates(dabench::TbdTracker& tracker, const TbdProblem& problem) {
  std::vector<SolveReport> reports;
  EstimatesPerStep out = dabench::test::estimates_per_step(tracker, problem, &reports);
  for (const SolveReport& report : reports) CHECK(report.converged);
  return out;
}

}  // namespace

TEST_CASE("tbd-mb: one Bernoulli without births is the Bayes update with the support likelihood",
          "[tbd][tbd_mb]") {
  for (const int association : {TbdMb::kObjects, TbdMb::kNone}) {  // one Bernoulli: nothing to exclude
  for (const bool present : {true, false}) {  // the object in the frame, or noise only (r̃ not near 1)
  for (const TbdSignal signal : {TbdSignal::fluctuating, TbdSignal::deterministic}) {
    INFO("association " << association << ", present " << present << ", signal " << static_cast<int>(signal));
    TbdProblem p = grid_problem(10, signal, kSeed, 3);
    p.filter.birth_mean = 0.0;
    const TbdPrior prior = prior_at(4.3, 5.6, 0.2, 0.6);
    p.initial_objects.push_back(prior);
    RandomStream rng(kSeed, 1, 0);
    p.frames.push_back(draw_frame(p.sensor, p.amplitude,
                                  present ? std::vector<Eigen::Vector2d>{{4.5, 5.5}} : std::vector<Eigen::Vector2d>{}, rng));
    TbdMbOptions options;
    options.particles = 500;
    options.association = association;
    TbdMb mb(options);
    converged_estimates(mb, p);
    if (!present && mb.objects().empty()) continue;  // recycled: r̃ below 0.1
    REQUIRE(mb.objects().size() == 1);

    // The same particles (the tracker's stream draws the prior first), weighted here by
    // ℓ = Π over the cells within 2σ_h of N(z; μ, (σ² + c) I₂)/N(z; 0, σ² I₂).
    RandomStream stream(dabench::algorithm_stream_seed(kSeed, 0), 0, 3);
    dabench::ParticleObject o;
    dabench::sample_prior(o, prior, options.particles, stream);
    const double radius = 2.0 * std::sqrt(p.sensor.spread_variance);
    double mass = 0.0;
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (int i = 0; i < o.size(); ++i) {
      double log_ratio = 0.0;
      for (int row = 0; row < p.sensor.rows; ++row) {
        for (int column = 0; column < p.sensor.columns; ++column) {
          const double dx = column + 0.5 - o.x[i], dy = row + 0.5 - o.y[i];
          if (dx * dx + dy * dy > radius * radius) continue;
          Eigen::Vector2d mu;
          double c = 0.0;
          dabench::test::cell_signal(p.sensor, p.amplitude, column, row, o.x[i], o.y[i], mu, c);
          const Eigen::Vector2d z = p.frames[0].col(row * p.sensor.columns + column);
          log_ratio += -std::log(1.0 + c) - (z - mu).squaredNorm() / (2.0 * (1.0 + c)) + z.squaredNorm() / 2.0;
        }
      }
      const double w = o.weight[i] * std::exp(log_ratio);
      mass += w;
      mean += w * Eigen::Vector2d(o.x[i], o.y[i]);
    }
    mean /= mass;
    const double r = prior.existence;
    CHECK(mb.objects()[0].existence == Approx(r * mass / (r * mass + 1.0 - r)).epsilon(1e-10));
    CHECK((mb.objects()[0].mean().head<2>() - mean).norm() < 0.05);  // resampled: Monte Carlo error only
    if (present) CHECK((mean - Eigen::Vector2d(4.5, 5.5)).norm() < 0.5);
    if (!present) CHECK(mb.objects()[0].existence < 0.99);
  }
  }
  }
}

TEST_CASE("tbd-mb: two Bernoullis on one object's cell do not both stay; without exclusivity both are certain",
          "[tbd][tbd_mb]") {
  TbdProblem p = grid_problem(10, TbdSignal::deterministic, kSeed, 4);
  p.filter.birth_mean = 0.0;
  // Both priors inside cell (4, 4), on the object.
  p.initial_objects = {prior_at(4.5, 4.5, 0.005, 0.9), prior_at(4.5, 4.5, 0.005, 0.9)};
  RandomStream rng(kSeed, 2, 0);
  p.frames.push_back(draw_frame(p.sensor, p.amplitude, {{4.5, 4.5}}, rng));
  TbdMbOptions options;
  options.particles = 400;
  TbdMb mb(options);
  converged_estimates(mb, p);
  // Exactly, r̃₀ = r̃₁ ≈ ½. The SPA on this loopy pair (they share their whole support, and ℓ
  // is about e^500) settles, with the serial schedule, on the fixed point where the first
  // Bernoulli holds the object and the second is recycled: never both.
  REQUIRE(mb.objects().size() == 1);
  CHECK(mb.objects()[0].label == 0);
  CHECK(mb.objects()[0].existence > 0.99);

  // association = none: each Bernoulli alone, both certain, both reported.
  options.association = TbdMb::kNone;
  TbdMb none(options);
  const auto reported = converged_estimates(none, p);
  REQUIRE(none.objects().size() == 2);
  CHECK(none.objects()[0].existence > 0.999);
  CHECK(none.objects()[1].existence > 0.999);
  CHECK(reported[0].size() == 2);

  dabench::TbdBpOptions alone;
  alone.particles = 400;
  alone.iterations = 1;
  alone.interaction = false;
  dabench::TbdBp bp(alone);
  converged_estimates(bp, p);
  REQUIRE(bp.objects().size() == 2);
  CHECK(bp.objects()[0].existence > 0.999);
  CHECK(bp.objects()[1].existence > 0.999);
}

TEST_CASE("tbd-mb: an object appearing in a static scene is born, reported near the truth, and not duplicated",
          "[tbd][tbd_mb]") {
  for (std::uint32_t trial = 0; trial < 4; ++trial) {
    INFO("trial " << trial);
    TbdProblem p = grid_problem(12, TbdSignal::deterministic, kSeed, trial);
    RandomStream rng(kSeed, 3, trial);
    const Eigen::Vector2d where(6.3, 5.6);
    for (int k = 0; k < 8; ++k) {
      p.frames.push_back(draw_frame(p.sensor, p.amplitude, k < 2 ? std::vector<Eigen::Vector2d>{} : std::vector{where}, rng));
    }
    TbdMbOptions options;
    options.particles = 1000;
    TbdMb mb(options);
    const auto estimates = converged_estimates(mb, p);
    CHECK(estimates[0].empty());
    CHECK(estimates[1].empty());
    for (int k = 2; k < p.steps(); ++k) {
      INFO("step " << k);
      REQUIRE_FALSE(estimates[k].empty());
      double nearest = 1e9;
      for (const TbdEstimate& e : estimates[k]) nearest = std::min(nearest, (e.state.head<2>() - where).norm());
      CHECK(nearest < 0.5);
      for (const TbdEstimate& e : estimates[k]) UNSCOPED_INFO("estimate " << e.state.head<2>().transpose() << " r " << e.existence << " label " << e.label);
      if (k >= 4) CHECK(estimates[k].size() == 1);
    }
  }
}

TEST_CASE("tbd-mb: without exclusivity the new Bernoullis around one object are each kept (duplicates)",
          "[tbd][tbd_mb]") {
  // A static object at a cell centre, no prior: every new Bernoulli whose cell lies in its
  // footprint sees the object alone (ξ_j = Λ_j ℓ̄_j ≫ 1), so several are kept at the first step
  // with the object; with exclusivity (the default) one is.
  for (std::uint32_t trial = 0; trial < 3; ++trial) {
    INFO("trial " << trial);
    TbdProblem p = grid_problem(12, TbdSignal::deterministic, kSeed, trial);
    RandomStream rng(kSeed, 5, trial);
    for (int k = 0; k < 3; ++k) p.frames.push_back(draw_frame(p.sensor, p.amplitude, {{6.5, 5.5}}, rng));
    TbdMbOptions options;
    options.particles = 500;
    TbdMb exclusive(options);
    options.association = TbdMb::kNone;
    TbdMb none(options);
    const auto one = converged_estimates(exclusive, p), many = converged_estimates(none, p);
    CHECK(one[0].size() == 1);
    CHECK(many[0].size() >= 2);
    for (const TbdEstimate& e : many[0]) CHECK((e.state.head<2>() - Eigen::Vector2d(6.5, 5.5)).norm() < 1.5);
  }
}

TEST_CASE("tbd-mb: pure noise gives no estimates and a bounded Poisson mass; no recycling empties it",
          "[tbd][tbd_mb]") {
  for (const bool recycling : {true, false}) {
    INFO("recycling " << recycling);
    TbdProblem p = grid_problem(12, TbdSignal::fluctuating, kSeed, 5);
    p.filter.birth_mean = 1e-3;
    RandomStream rng(kSeed, 4, 0);
    for (int k = 0; k < 30; ++k) p.frames.push_back(draw_frame(p.sensor, p.amplitude, {}, rng));
    TbdMbOptions options;
    options.particles = 300;
    options.recycling = recycling;
    TbdMb mb(options);
    mb.start(p);
    for (int k = 0; k < p.steps(); ++k) {
      std::vector<TbdEstimate> estimates;
      SolveReport report;
      mb.step(k, estimates, report);
      CHECK(estimates.empty());
    }
    const std::vector<double>& mass = mb.undetected_mass();
    const double total = std::accumulate(mass.begin(), mass.end(), 0.0);
    if (recycling) {
      // Each update keeps at most Λ ℓ̄ of a cell's mass, E_noise[ℓ̄] = 1: the mean total stays
      // below the births' Σ_k p_s^k μ_B ≤ 30 μ_B (a margin of 1.5 for the noise); ℓ̄ is heavy
      // tailed (D1: a cell's ratio has median ≈ 0.06), so a typical total is far lower.
      CHECK(total > 0.0);
      CHECK(total < 1.5 * 30 * p.filter.birth_mean);
    } else {
      CHECK(total == 0.0);
    }
  }
}

TEST_CASE("tbd-mb: same seed gives identical output; bad options are named", "[tbd][tbd_mb]") {
  TbdProblem p = grid_problem(10, TbdSignal::fluctuating, kSeed, 6);
  RandomStream rng(kSeed, 5, 0);
  for (int k = 0; k < 5; ++k) p.frames.push_back(draw_frame(p.sensor, p.amplitude, {{3.2, 6.7}}, rng));
  TbdMbOptions options;
  options.particles = 300;
  TbdMb first(options), second(options);
  const auto a = converged_estimates(first, p);
  const auto b = converged_estimates(second, p);
  for (int k = 0; k < p.steps(); ++k) {
    REQUIRE(a[k].size() == b[k].size());
    for (std::size_t e = 0; e < a[k].size(); ++e) {
      CHECK(a[k][e].state == b[k][e].state);
      CHECK(a[k][e].existence == b[k][e].existence);
      CHECK(a[k][e].label == b[k][e].label);
    }
  }
  for (const char* spec : {"tbd-mb:recycle_threshold=0.6", "tbd-mb:particles=5", "tbd-mb:recycled=1", "tbd-mb:association=cells"}) {
    const std::string message = dabench::test::input_error_message([&] { dabench::make_tbd_tracker(spec); });
    const std::string field = std::string(spec).substr(7, std::string(spec).find('=') - 7);
    CHECK_THAT(message, Catch::Contains(field));
  }
}

}  // namespace DABENCH_TEST_FILE
