// Tests of the TBD-BP message passing between potential objects and data cells
// (algorithms/tbd/cell_messages.hpp; tbd-bp-supplement eq (5); docs/models/track-before-detect.md §3.3) with the
// exact κ, against brute-force marginals computed here from the model of harness/tbd/problem.hpp
// restated independently (tests/support/cell_messages.hpp):
//  - On a tree (two POs sharing one cell), L = 2 gives the exact marginals of the joint
//    posterior, also where the densities underflow (log domain); a loopy pair differs
//    (documented); a cell reached by three POs makes run() refuse.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
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

// Two POs and a frame for the exact-κ tests; windows by support radius 1.2 m.
struct Pair {
  Model model;
  std::vector<ParticleObject> objects;
  Eigen::Matrix2Xd frame;
  double radius = 1.2;
};

// PO 1's particles in [c1 ± 0.15]², PO 2's in [c2 ± 0.15]², frame with both present. With
// c on a cell centre and radius 1.2 m, a window is exactly the 3 × 3 cells around c.
Pair make_two(TbdSignal signal, double c1, double c2, std::uint32_t trial) {
  Pair p;
  p.model = small_model(signal);
  RandomStream rng(kSeed, 3, trial);
  p.objects.push_back(random_object(rng, c1, c1, 0.15, 5, rng.uniform(0.3, 0.8), 0));
  p.objects.push_back(random_object(rng, c2, c2, 0.15, 5, rng.uniform(0.3, 0.8), 1));
  p.frame = draw_frame(p.model, {{c1 + 0.1, c1 - 0.1}, {c2 - 0.1, c2}}, rng);
  return p;
}

// Brute-force marginals of p(y1, y2 | z) ∝ α1(y1) α2(y2) Π_j p(z_j | y1, y2), where a PO
// contributes to cell j only if j is in its window. Returns, per PO, the existence probability
// and the weights of its particles given r = 1.
struct Marginal {
  double existence = 0.0;
  std::vector<double> weights;
};

std::vector<Marginal> brute_force(const Model& m, const std::vector<ParticleObject>& objects,
                                  const std::vector<CellWindow>& windows, const Eigen::Matrix2Xd& frame) {
  const ParticleObject& a = objects[0];
  const ParticleObject& b = objects[1];
  std::vector<double> log_joint;
  std::vector<std::pair<int, int>> states;
  for (int s1 = -1; s1 < a.size(); ++s1) {
    for (int s2 = -1; s2 < b.size(); ++s2) {
      double l = std::log(s1 < 0 ? 1.0 - a.existence : a.existence * a.weight[s1]) +
                 std::log(s2 < 0 ? 1.0 - b.existence : b.existence * b.weight[s2]);
      for (int j = 0; j < m.cells(); ++j) {
        Eigen::Vector2d mean = Eigen::Vector2d::Zero();
        double variance = m.sensor.noise_variance;
        if (s1 >= 0 && in_window(m, windows[0], j)) {
          mean += m.mu(j, a.x[s1], a.y[s1]);
          variance += m.c(j, a.x[s1], a.y[s1]);
        }
        if (s2 >= 0 && in_window(m, windows[1], j)) {
          mean += m.mu(j, b.x[s2], b.y[s2]);
          variance += m.c(j, b.x[s2], b.y[s2]);
        }
        l += log_normal(frame.col(j), mean, variance * Eigen::Matrix2d::Identity());
      }
      log_joint.push_back(l);
      states.push_back({s1, s2});
    }
  }
  const double norm = log_sum_exp(log_joint);
  std::vector<Marginal> out(2);
  out[0].weights.assign(a.size(), 0.0);
  out[1].weights.assign(b.size(), 0.0);
  for (std::size_t k = 0; k < states.size(); ++k) {
    const double p = std::exp(log_joint[k] - norm);
    const auto [s1, s2] = states[k];
    if (s1 >= 0) {
      out[0].existence += p;
      out[0].weights[s1] += p;
    }
    if (s2 >= 0) {
      out[1].existence += p;
      out[1].weights[s2] += p;
    }
  }
  for (Marginal& mg : out) {
    for (double& w : mg.weights) w /= mg.existence;
  }
  return out;
}

// The belief of PO n from the messages: weights w_i exp(Σ_j λ) normalised, existence logistic.
Marginal belief(const CellMessages& messages, const ParticleObject& o, int n) {
  Marginal b;
  const std::vector<double>& total = messages.total_log_ratio(n);
  const double top = *std::max_element(total.begin(), total.end());
  double sum = 0.0;
  for (int i = 0; i < o.size(); ++i) {
    b.weights.push_back(o.weight[i] * std::exp(total[i] - top));
    sum += b.weights.back();
  }
  for (double& w : b.weights) w /= sum;
  b.existence = 1.0 / (1.0 + std::exp(-messages.existence_log_odds(n)));
  return b;
}

double largest_difference(const Marginal& a, const Marginal& b) {
  double d = std::abs(a.existence - b.existence);
  for (std::size_t i = 0; i < a.weights.size(); ++i) d = std::max(d, std::abs(a.weights[i] - b.weights[i]));
  return d;
}

}  // namespace

TEST_CASE("tbd cell messages: exact kappa on a tree (one shared cell) gives the brute-force marginals at L = 2",
          "[tbd][cell_messages][exact]") {
  for (const TbdSignal signal : {TbdSignal::fluctuating, TbdSignal::deterministic}) {
    for (std::uint32_t trial = 0; trial < 3; ++trial) {
      INFO(signal_name(signal) << ", trial " << trial);
      // Particles in [1.35, 1.65]² and [3.35, 3.65]², radius 1.2 m: windows columns/rows 0..2 and
      // 2..4, sharing cell (2, 2) only.
      Pair p = make_two(signal, 1.5, 3.5, trial);
      const Model& m = p.model;
      const std::vector<CellWindow> windows{CellWindow{0, 3, 0, 3}, CellWindow{2, 5, 2, 5}};
      const std::vector<Marginal> exact = brute_force(m, p.objects, windows, p.frame);

      for (const int iterations : {1, 2, 3}) {
        INFO("iterations " << iterations);
        CellMessages messages;
        CellMessageOptions options;
        options.iterations = iterations;
        options.support_radius = p.radius;
        options.exact = true;
        REQUIRE(messages.run(m.sensor, m.gamma, p.frame, pointers(p.objects), options));
        for (int n = 0; n < 2; ++n) {
          require_window(messages.window(n), windows[n]);
          require_window(messages.window(n), expected_window(m, p.objects[n], p.radius));
        }
        for (int n = 0; n < 2; ++n) {
          INFO("PO " << n << ": exact existence " << exact[n].existence);
          const Marginal bp = belief(messages, p.objects[n], n);
          if (iterations >= 2) {
            // Tree: β^(2) into the shared cell carries all of the other PO's own cells.
            CHECK(bp.existence == close(exact[n].existence, 1e-10, 1e-12));
            for (std::size_t i = 0; i < bp.weights.size(); ++i) {
              CHECK(bp.weights[i] == close(exact[n].weights[i], 1e-10, 1e-12));
            }
          } else {
            // L = 1: β^(1) = α misses the other PO's own cells, so the marginals are not yet exact.
            CHECK(largest_difference(bp, exact[n]) > 1e-4);
          }
        }
      }
    }
  }
}

TEST_CASE("tbd cell messages: exact kappa is computed in the log domain: a bright shared cell at small noise",
          "[tbd][cell_messages][exact]") {
  // The tree of the test above with σ² = 0.05 and the shared cell (2, 2) at z = (60, 0): every
  // Gaussian of eq (5) in that cell is below e^{−3000}, so a sum of densities underflows to 0 and
  // λ = log 0 − log 0; the log-domain sums still give the brute-force marginals at L = 2.
  for (const TbdSignal signal : {TbdSignal::fluctuating, TbdSignal::deterministic}) {
  for (const double noise : {0.05, 0.01, 0.001}) {  // small noise: |λ| beyond 745, where exp(−λ) underflows too
    INFO(signal_name(signal) << ", noise variance " << noise);
    Pair p = make_two(signal, 1.5, 3.5, 0);
    p.model.sensor.noise_variance = noise;
    p.frame.col(2 * p.model.sensor.columns + 2) = Eigen::Vector2d(60.0, 0.0);
    const std::vector<CellWindow> windows{CellWindow{0, 3, 0, 3}, CellWindow{2, 5, 2, 5}};
    const std::vector<Marginal> exact = brute_force(p.model, p.objects, windows, p.frame);
    CellMessages messages;
    CellMessageOptions options;
    options.iterations = 2;
    options.support_radius = p.radius;
    options.exact = true;
    REQUIRE(messages.run(p.model.sensor, p.model.gamma, p.frame, pointers(p.objects), options));
    for (int n = 0; n < 2; ++n) {
      INFO("PO " << n << ": exact existence " << exact[n].existence);
      REQUIRE(std::isfinite(messages.existence_log_odds(n)));
      const Marginal bp = belief(messages, p.objects[n], n);
      CHECK(bp.existence == close(exact[n].existence, 1e-9, 1e-12));
      for (std::size_t i = 0; i < bp.weights.size(); ++i) CHECK(bp.weights[i] == close(exact[n].weights[i], 1e-9, 1e-12));
    }
  }
  }
}

TEST_CASE("tbd cell messages: exact kappa on a loopy pair runs but is not the brute-force marginal",
          "[tbd][cell_messages][exact]") {
  for (const TbdSignal signal : {TbdSignal::fluctuating, TbdSignal::deterministic}) {
    INFO(signal_name(signal));
    // Particles in [1.35, 1.65]² and [2.35, 2.65]², radius 1.2 m: windows 0..2 and 1..3 share 2 × 2 cells.
    Pair p = make_two(signal, 1.5, 2.5, 0);
    const Model& m = p.model;
    const std::vector<CellWindow> windows{CellWindow{0, 3, 0, 3}, CellWindow{1, 4, 1, 4}};
    const std::vector<Marginal> exact = brute_force(m, p.objects, windows, p.frame);
    CellMessages messages;
    CellMessageOptions options;
    options.iterations = 2;
    options.support_radius = p.radius;
    options.exact = true;
    REQUIRE(messages.run(m.sensor, m.gamma, p.frame, pointers(p.objects), options));
    for (int n = 0; n < 2; ++n) require_window(messages.window(n), windows[n]);
    double largest = 0.0;
    for (int n = 0; n < 2; ++n) {
      const Marginal bp = belief(messages, p.objects[n], n);
      REQUIRE(std::isfinite(bp.existence));
      for (double w : bp.weights) REQUIRE(std::isfinite(w));
      const double d = largest_difference(bp, exact[n]);
      INFO("PO " << n << ": existence " << bp.existence << " vs brute force " << exact[n].existence
                 << ", largest difference " << d);
      CHECK(d > 1e-5);
      largest = std::max(largest, d);
    }
    // Documented, not a requirement of the method: a loop makes BP approximate. Observed largest
    // differences (existence or particle weight): D1 1.9e-4 (PO 0) and 1.9e-4 (PO 1); D2 1.4e-2
    // and 3.6e-3.
    CHECK(largest < 0.1);
  }
}

TEST_CASE("tbd cell messages: exact kappa refuses a cell reached by three POs", "[tbd][cell_messages][exact]") {
  Model m = small_model(TbdSignal::deterministic);
  RandomStream rng(kSeed, 4, 0);
  std::vector<ParticleObject> objects;
  objects.push_back(random_object(rng, 1.5, 1.5, 0.15, 4, 0.5, 0));  // window 0..2 (radius 1.2 m)
  objects.push_back(random_object(rng, 2.5, 2.5, 0.15, 4, 0.5, 1));  // window 1..3
  objects.push_back(random_object(rng, 4.5, 4.5, 0.15, 4, 0.5, 2));  // window 3..5: meets PO 1 only
  const Eigen::Matrix2Xd frame = draw_frame(m, {{1.5, 1.5}}, rng);
  CellMessageOptions options;
  options.iterations = 2;
  options.support_radius = 1.2;
  options.exact = true;
  CellMessages messages;
  // Every cell is reached by at most two POs.
  REQUIRE(messages.run(m.sensor, m.gamma, frame, pointers(objects), options));
  require_window(messages.window(0), CellWindow{0, 3, 0, 3});
  require_window(messages.window(1), CellWindow{1, 4, 1, 4});
  require_window(messages.window(2), CellWindow{3, 6, 3, 6});
  REQUIRE(std::isfinite(messages.existence_log_odds(2)));
  // Moved to 3.5: window 2..4 shares cell (2, 2) with both others.
  for (int i = 0; i < objects[2].size(); ++i) {
    objects[2].x[i] -= 1.0;
    objects[2].y[i] -= 1.0;
  }
  CHECK_FALSE(messages.run(m.sensor, m.gamma, frame, pointers(objects), options));
  // The Gaussian κ̃ has no such limit.
  options.exact = false;
  CHECK(messages.run(m.sensor, m.gamma, frame, pointers(objects), options));
}

}  // namespace DABENCH_TEST_FILE
