// Tests of the TBD-BP message passing between potential objects and data cells
// (algorithms/tbd/cell_messages.hpp; docs/models/track-before-detect.md §3.3): a PO's messages where no other PO
// of the same run speaks, against the model of harness/tbd/problem.hpp restated independently
// (tests/support/cell_messages.hpp):
//  - New POs (TbdBp's serial stage) are evaluated against the field, which add_to_field extends
//    by a belief; log_ratios_at gives the final messages at any positions.
//  - interaction = false: a PO's λ does not depend on the other POs.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <vector>

#include <Eigen/Dense>

#include "algorithms/tbd/cell_messages.hpp"
#include "algorithms/tbd/particle_object.hpp"
#include "harness/core/random_stream.hpp"
#include "harness/tbd/problem.hpp"
#include "tests/support/cell_messages.hpp"

namespace DABENCH_TEST_FILE {

namespace {

using namespace dabench;
using namespace dabench::test::cell_messages;
using dabench::test::signal_name;

// λ_j(x) of a PO that alone explains cell j: log N(z_j; μ_j(x), (σ² + c_j(x)) I) − log N(z_j; 0, σ² I).
double lone_log_ratio(const Model& m, const Eigen::Matrix2Xd& frame, int j, double x, double y) {
  const Eigen::Matrix2d noise = m.sensor.noise_variance * Eigen::Matrix2d::Identity();
  return log_normal(frame.col(j), m.mu(j, x, y), noise + m.c(j, x, y) * Eigen::Matrix2d::Identity()) -
         log_normal(frame.col(j), Eigen::Vector2d::Zero(), noise);
}

}  // namespace

// New POs (TbdBp's serial stage): evaluate() runs one PO against the field — the legacy POs'
// outgoing messages plus the beliefs added so far — and log_ratios_at() evaluates the same
// messages anywhere. With no legacy PO the field starts empty: PO A sees the cells alone; after
// add_to_field(A), PO B sees A's belief moments (existence r̃_A, weights ∝ w exp(Σ_j λ_A)).
TEST_CASE("tbd cell messages: new POs are evaluated against the field, which add_to_field extends by a belief",
          "[tbd][cell_messages][births]") {
  for (const TbdSignal signal : {TbdSignal::fluctuating, TbdSignal::deterministic}) {
    INFO(signal_name(signal));
    Model m = small_model(signal);
    RandomStream rng(kSeed, 10, 0);
    const ParticleObject a = random_object(rng, 2.5, 2.5, 0.4, 6, 0.01, 0);
    const ParticleObject b = random_object(rng, 3.2, 2.8, 0.4, 5, 0.01, 1);
    const Eigen::Matrix2Xd frame = draw_frame(m, {{2.7, 2.6}}, rng);
    CellMessages messages;
    CellMessageOptions options;
    options.support_radius = 20.0;  // every cell in every window
    std::vector<ParticleObject> none;
    REQUIRE(messages.run(m.sensor, m.gamma, frame, pointers(none), options));
    messages.outgoing_field();
    const Eigen::Matrix2d noise = m.sensor.noise_variance * Eigen::Matrix2d::Identity();

    CellMessages::Work work_a, work_b;
    messages.prepare(a, work_a);
    messages.prepare(b, work_b);
    const double odds_a = messages.evaluate(a, work_a, true);
    std::vector<double> lambda_a(a.size(), 0.0), at_a;
    messages.log_ratios_at(work_a, a, at_a);
    for (int i = 0; i < a.size(); ++i) {
      for (int j = 0; j < m.cells(); ++j) {
        lambda_a[i] += lone_log_ratio(m, frame, j, a.x[i], a.y[i]);
      }
      CHECK(work_a.total[i] == close(lambda_a[i], 1e-10, 1e-9));
      CHECK(at_a[i] == close(lambda_a[i], 1e-10, 1e-9));
    }
    std::vector<double> la(a.size());
    for (int i = 0; i < a.size(); ++i) la[i] = std::log(a.weight[i]) + lambda_a[i];
    const double expected_odds_a = std::log(a.existence) - std::log1p(-a.existence) + log_sum_exp(la);
    CHECK(odds_a == close(expected_odds_a, 1e-10, 1e-9));

    // A's belief moments per cell, by hand.
    const double r_a = 1.0 / (1.0 + std::exp(-expected_odds_a));
    const double norm = log_sum_exp(la);
    std::vector<Eigen::Vector2d> mean(m.cells(), Eigen::Vector2d::Zero());
    std::vector<Eigen::Matrix2d> second(m.cells(), Eigen::Matrix2d::Zero());
    for (int i = 0; i < a.size(); ++i) {
      const double w = r_a * std::exp(la[i] - norm);
      for (int j = 0; j < m.cells(); ++j) {
        const Eigen::Vector2d mu = m.mu(j, a.x[i], a.y[i]);
        mean[j] += w * mu;
        second[j] += w * (m.c(j, a.x[i], a.y[i]) * Eigen::Matrix2d::Identity() + mu * mu.transpose());
      }
    }
    messages.add_to_field(a, work_a);
    messages.evaluate(b, work_b, true);
    for (int i = 0; i < b.size(); ++i) {
      double expected = 0.0;
      for (int j = 0; j < m.cells(); ++j) {
        const Eigen::Matrix2d v = noise + second[j] - mean[j] * mean[j].transpose();
        expected += log_normal(frame.col(j), mean[j] + m.mu(j, b.x[i], b.y[i]), v + m.c(j, b.x[i], b.y[i]) * Eigen::Matrix2d::Identity()) -
                    log_normal(frame.col(j), mean[j], v);
      }
      CHECK(work_b.total[i] == close(expected, 1e-9, 1e-8));
    }
  }
}

TEST_CASE("tbd cell messages: without interaction the log ratios of a PO ignore the other POs",
          "[tbd][cell_messages][interaction]") {
  for (const TbdSignal signal : {TbdSignal::fluctuating, TbdSignal::deterministic}) {
    INFO(signal_name(signal));
    Model m = small_model(signal);
    RandomStream rng(kSeed, 5, 0);
    ParticleObject a = random_object(rng, 2.5, 2.5, 0.4, 6, 0.6, 0);
    ParticleObject b = random_object(rng, 3.0, 3.0, 0.4, 5, 0.7, 1);
    ParticleObject c = random_object(rng, 2.0, 3.2, 0.4, 4, 0.4, 2);
    const Eigen::Matrix2Xd frame = draw_frame(m, {{2.5, 2.5}, {3.0, 3.0}}, rng);
    const double radius = 2.0;
    const CellWindow wa = expected_window(m, a, radius);

    const auto run = [&](std::vector<ParticleObject*> objects, bool interaction, int iterations, CellMessages& out) {
      CellMessageOptions options;
      options.iterations = iterations;
      options.support_radius = radius;
      options.interaction = interaction;
      REQUIRE(out.run(m.sensor, m.gamma, frame, objects, options));
    };
    for (const int iterations : {1, 2}) {
      INFO("iterations " << iterations);
      CellMessages alone, with_b, with_bc;
      run({&a}, false, iterations, alone);
      run({&a, &b}, false, iterations, with_b);
      run({&b, &a, &c}, false, iterations, with_bc);  // a is PO 1 here
      require_window(alone.window(0), wa);
      require_window(with_bc.window(1), wa);
      // a's λ alone on its window.
      for (int j = 0; j < m.cells(); ++j) {
        if (!in_window(m, wa, j)) continue;
        const int slot = window_slot(m, wa, j);
        for (int i = 0; i < a.size(); ++i) {
          const double expected = lone_log_ratio(m, frame, j, a.x[i], a.y[i]);
          CHECK(alone.log_ratio(0, slot, i) == close(expected, 1e-10, 1e-9));
          CHECK(with_b.log_ratio(0, slot, i) == alone.log_ratio(0, slot, i));
          CHECK(with_bc.log_ratio(1, slot, i) == alone.log_ratio(0, slot, i));
        }
      }
      CHECK(with_b.existence_log_odds(0) == alone.existence_log_odds(0));
      CHECK(with_bc.existence_log_odds(1) == alone.existence_log_odds(0));
      for (int i = 0; i < a.size(); ++i) CHECK(with_bc.total_log_ratio(1)[i] == alone.total_log_ratio(0)[i]);

      // Control: with interaction, adding b changes a's λ (b's signal is explained by b).
      CellMessages interacting_alone, interacting_with_b;
      run({&a}, true, iterations, interacting_alone);
      run({&a, &b}, true, iterations, interacting_with_b);
      CHECK(std::abs(interacting_with_b.existence_log_odds(0) - interacting_alone.existence_log_odds(0)) > 0.1);
      // ... and a PO alone sees no other PO: interaction changes nothing.
      CHECK(interacting_alone.existence_log_odds(0) == close(alone.existence_log_odds(0), 1e-12, 1e-12));
    }
  }
}

}  // namespace DABENCH_TEST_FILE
