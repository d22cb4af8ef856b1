// Tests of the message schedules of TBD-BP (algorithms/tbd/cell_messages.hpp, tbd_bp.hpp):
//  - serial: the messages of the serial schedule (PO by PO, each against the others' newest
//    extrinsic messages) against an independent sequential computation of eqs (5), (9) written
//    here, for D1, D2, D3 and L = 1, 2, 3;
//  - flooding over the new POs (the letter's schedule read literally): every new PO around an
//    object claims it at L = 1 (duplicates), all give it up at L = 2, and claim it again at
//    L = 3 (period 2) — what tbd_bp.hpp's header says and why the new POs are taken serially;
//  - flooding over two legacy POs on one object keeps both or neither, alternately (period 2),
//    where the serial schedule lets exactly one keep it.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include <Eigen/Dense>

#include "algorithms/tbd/cell_messages.hpp"
#include "algorithms/tbd/new_objects.hpp"
#include "algorithms/tbd/particle_object.hpp"
#include "harness/core/random_stream.hpp"
#include "harness/tbd/problem.hpp"
#include "tests/support/tbd_frames.hpp"

namespace DABENCH_TEST_FILE {

namespace {

using dabench::CellMessageOptions;
using dabench::CellMessages;
using dabench::ParticleObject;
using dabench::RandomStream;
using dabench::TbdSensor;
using dabench::TbdSignal;

constexpr std::uint64_t kSeed = 20231206;

double log_normal(const Eigen::Vector2d& z, const Eigen::Vector2d& mean, const Eigen::Matrix2d& cov) {
  const Eigen::Vector2d d = z - mean;
  return -std::log(2.0 * std::numbers::pi) - 0.5 * std::log(cov.determinant()) - 0.5 * d.dot(cov.inverse() * d);
}

std::vector<ParticleObject*> pointers(std::vector<ParticleObject>& objects) {
  std::vector<ParticleObject*> out;
  for (ParticleObject& o : objects) out.push_back(&o);
  return out;
}

// The serial schedule restated: moments m[n][j] (μ_{n,j}) and s[n][j] (R_{n,j}) of each PO's
// newest message β_{n,j}; PO n in order computes λ_{n,j}(x_i) against the others' (eqs 5, 9),
// then replaces its own moments by those of β_{n,j} ∝ α_n Π_{j'≠j} κ̃_{n,j'}. Every cell is in
// every PO's window here. Returns per PO the Σ_j λ per particle and the belief's log-odds.
struct Serial {
  std::vector<std::vector<double>> total;
  std::vector<double> log_odds;
};

Serial serial_reference(const TbdSensor& s, double gamma, const Eigen::Matrix2Xd& frame,
                        const std::vector<ParticleObject>& objects, int iterations) {
  const int count = static_cast<int>(objects.size()), cells = s.cells();
  const auto signal = [&](int j, double px, double py, Eigen::Vector2d& mu, double& c) {
    dabench::test::cell_signal(s, gamma, j % s.columns, j / s.columns, px, py, mu, c);
  };
  std::vector<std::vector<Eigen::Vector2d>> m(count, std::vector<Eigen::Vector2d>(cells));
  std::vector<std::vector<Eigen::Matrix2d>> r(count, std::vector<Eigen::Matrix2d>(cells));
  std::vector<std::vector<std::vector<double>>> lambda(count);  // [n][j][i]
  // Moments of β_{n,j} with log weights log(w_i r) + Σ_{j'≠j} λ (none at ℓ = 0: β = α).
  const auto set_moments = [&](int n) {
    const ParticleObject& o = objects[n];
    for (int j = 0; j < cells; ++j) {
      std::vector<double> logs(o.size());
      double top = std::log1p(-o.existence);
      for (int i = 0; i < o.size(); ++i) {
        double others = 0.0;
        if (!lambda[n].empty()) {
          for (int k = 0; k < cells; ++k) others += k == j ? 0.0 : lambda[n][k][i];
        }
        logs[i] = std::log(o.weight[i] * o.existence) + others;
        top = std::max(top, logs[i]);
      }
      double mass = std::exp(std::log1p(-o.existence) - top);
      Eigen::Vector2d mean = Eigen::Vector2d::Zero();
      Eigen::Matrix2d second = Eigen::Matrix2d::Zero();
      for (int i = 0; i < o.size(); ++i) {
        const double b = std::exp(logs[i] - top);
        Eigen::Vector2d mu;
        double c = 0.0;
        signal(j, o.x[i], o.y[i], mu, c);
        mass += b;
        mean += b * mu;
        second += b * (c * Eigen::Matrix2d::Identity() + mu * mu.transpose());
      }
      m[n][j] = mean / mass;
      r[n][j] = second / mass;
    }
  };
  for (int n = 0; n < count; ++n) set_moments(n);
  for (int l = 0; l < iterations; ++l) {
    for (int n = 0; n < count; ++n) {
      const ParticleObject& o = objects[n];
      lambda[n].assign(cells, std::vector<double>(o.size()));
      for (int j = 0; j < cells; ++j) {
        Eigen::Vector2d e = Eigen::Vector2d::Zero();
        Eigen::Matrix2d v = s.noise_variance * Eigen::Matrix2d::Identity();
        for (int k = 0; k < count; ++k) {
          if (k == n) continue;
          e += m[k][j];
          v += r[k][j] - m[k][j] * m[k][j].transpose();
        }
        const double absent = log_normal(frame.col(j), e, v);
        for (int i = 0; i < o.size(); ++i) {
          Eigen::Vector2d mu;
          double c = 0.0;
          signal(j, o.x[i], o.y[i], mu, c);
          lambda[n][j][i] = log_normal(frame.col(j), e + mu, v + c * Eigen::Matrix2d::Identity()) - absent;
        }
      }
      set_moments(n);
    }
  }
  Serial out;
  for (int n = 0; n < count; ++n) {
    const ParticleObject& o = objects[n];
    std::vector<double> total(o.size(), 0.0);
    for (int j = 0; j < cells; ++j) {
      for (int i = 0; i < o.size(); ++i) total[i] += lambda[n][j][i];
    }
    double top = -1e300, sum = 0.0;
    for (int i = 0; i < o.size(); ++i) top = std::max(top, std::log(o.weight[i]) + total[i]);
    for (int i = 0; i < o.size(); ++i) sum += std::exp(std::log(o.weight[i]) + total[i] - top);
    out.total.push_back(total);
    out.log_odds.push_back(std::log(o.existence) - std::log1p(-o.existence) + top + std::log(sum));
  }
  return out;
}

// Existence log-odds of every PO after L iterations of `serial` or flooding messages, with the
// tracker's window margin 4σ_h.
std::vector<double> log_odds_after(const TbdSensor& s, const Eigen::Matrix2Xd& frame, std::vector<ParticleObject>& objects,
                                   int iterations, bool serial) {
  CellMessages messages;
  CellMessageOptions options;
  options.iterations = iterations;
  options.support_radius = 4.0 * std::sqrt(s.spread_variance);
  options.serial = serial;
  REQUIRE(messages.run(s, 60.0, frame, pointers(objects), options));
  std::vector<double> out;
  for (int n = 0; n < static_cast<int>(objects.size()); ++n) out.push_back(messages.existence_log_odds(n));
  return out;
}

TbdSensor small_sensor(TbdSignal signal) {
  TbdSensor s;
  s.columns = s.rows = 5;
  s.signal = signal;
  s.spread_variance = signal == TbdSignal::deterministic ? 1.5 : (signal == TbdSignal::mixed ? 0.58 : 0.5);
  s.mean_share = 0.66;
  return s;
}

}  // namespace

TEST_CASE("tbd cell messages: the serial schedule is the sequential computation of eqs (5), (9)",
          "[tbd][cell_messages][schedules]") {
  for (const TbdSignal signal : {TbdSignal::fluctuating, TbdSignal::deterministic, TbdSignal::mixed}) {
    const TbdSensor s = small_sensor(signal);
    RandomStream rng(kSeed, 1, static_cast<std::uint32_t>(signal));
    // Three POs with 7 particles each around (1.8, 2.1), (2.6, 2.4), (3.1, 3.3): all overlap.
    std::vector<ParticleObject> objects(3);
    const double centres[3][2] = {{1.8, 2.1}, {2.6, 2.4}, {3.1, 3.3}};
    for (int n = 0; n < 3; ++n) {
      objects[n].resize(7);
      double sum = 0.0;
      for (int i = 0; i < 7; ++i) {
        objects[n].x[i] = centres[n][0] + 0.3 * rng.normal();
        objects[n].y[i] = centres[n][1] + 0.3 * rng.normal();
        objects[n].vx[i] = objects[n].vy[i] = 0.0;
        sum += objects[n].weight[i] = rng.uniform(0.2, 1.0);
      }
      for (double& w : objects[n].weight) w /= sum;
      objects[n].existence = rng.uniform(0.3, 0.9);
    }
    const Eigen::Matrix2Xd frame = dabench::test::draw_frame(s, 60.0, {{2.0, 2.2}, {3.0, 3.0}}, rng);
    for (const int iterations : {1, 2, 3}) {
      INFO("signal " << static_cast<int>(signal) << ", L = " << iterations);
      CellMessages messages;
      CellMessageOptions options;
      options.iterations = iterations;
      options.support_radius = 10.0;  // every cell in every window
      options.serial = true;
      REQUIRE(messages.run(s, 60.0, frame, pointers(objects), options));
      const Serial expected = serial_reference(s, 60.0, frame, objects, iterations);
      for (int n = 0; n < 3; ++n) {
        INFO("PO " << n);
        REQUIRE(messages.window(n).cells() == s.cells());
        CHECK(messages.existence_log_odds(n) == Approx(expected.log_odds[n]).epsilon(1e-9).margin(1e-9));
        for (int i = 0; i < 7; ++i) {
          CHECK(messages.total_log_ratio(n)[i] == Approx(expected.total[n][i]).epsilon(1e-9).margin(1e-8));
        }
      }
    }
  }
}

TEST_CASE("tbd cell messages: flooding over the new POs duplicates an object at L = 1 and oscillates with period 2",
          "[tbd][cell_messages][schedules]") {
  // One object at a cell corner of a 12 × 12 D1 grid (γ = 60), the new POs of tbd_bp.hpp (one
  // per cell, a 4 × 4 quadrature, r = (μ_B/J)/(1 + μ_B/J), μ_B = 0.01), all updated in parallel.
  for (std::uint32_t trial = 0; trial < 3; ++trial) {
    INFO("trial " << trial);
    TbdSensor s;
    s.columns = s.rows = 12;
    RandomStream rng(kSeed, 2, trial);
    const Eigen::Matrix2Xd frame = dabench::test::draw_frame(s, 60.0, {{6.0, 6.0}}, rng);
    std::vector<ParticleObject> births;
    dabench::make_cell_objects(s, 4, births);
    const double birth = 0.01 / s.cells();
    for (ParticleObject& o : births) o.existence = birth / (1.0 + birth);
    std::vector<int> claims(4);
    std::vector<double> best(4);
    for (const int iterations : {1, 2, 3}) {
      const std::vector<double> log_odds = log_odds_after(s, frame, births, iterations, false);
      best[iterations] = *std::max_element(log_odds.begin(), log_odds.end());
      claims[iterations] = static_cast<int>(std::count_if(log_odds.begin(), log_odds.end(), [](double v) { return v > 0.0; }));
    }
    INFO("new POs with r > 0.5 at L = 1, 2, 3: " << claims[1] << ", " << claims[2] << ", " << claims[3]
                                                << "; best log-odds " << best[1] << ", " << best[2] << ", " << best[3]);
    CHECK(claims[1] >= 2);  // duplicates: the cells around the object each take it
    CHECK(best[2] < 0.0);   // each then sees the others' claims and all give it up
    CHECK(claims[2] == 0);
    CHECK(claims[3] >= 2);  // and claim it again
  }
}

TEST_CASE("tbd cell messages: flooding keeps two POs on one object both or neither, alternately; serial keeps one",
          "[tbd][cell_messages][schedules]") {
  TbdSensor s;
  s.columns = s.rows = 10;
  s.signal = TbdSignal::deterministic;
  s.spread_variance = 1.5;
  RandomStream rng(kSeed, 3, 0);
  const Eigen::Matrix2Xd frame = dabench::test::draw_frame(s, 60.0, {{5.0, 5.0}}, rng);
  std::vector<ParticleObject> objects(2);
  for (ParticleObject& o : objects) {
    o.resize(200);
    for (int i = 0; i < o.size(); ++i) {
      o.x[i] = 5.0 + 0.2 * rng.normal();
      o.y[i] = 5.0 + 0.2 * rng.normal();
      o.vx[i] = o.vy[i] = 0.0;
      o.weight[i] = 1.0 / o.size();
    }
    o.existence = 0.5;
  }
  for (const int iterations : {1, 2, 3, 4}) {
    INFO("L = " << iterations);
    const std::vector<double> flooding = log_odds_after(s, frame, objects, iterations, false);
    const std::vector<double> serial = log_odds_after(s, frame, objects, iterations, true);
    INFO("flooding log-odds " << flooding[0] << ", " << flooding[1] << "; serial " << serial[0] << ", " << serial[1]);
    // Flooding: both POs see the same thing, so both drop the object (at L = 1 each sees the
    // other's prior claim) or both keep it (at L = 2 each sees the other give it up): period 2.
    CHECK((flooding[0] > 0.0) == (flooding[1] > 0.0));
    CHECK((flooding[0] > 0.0) == (iterations % 2 == 0));
    // Serial: exactly one keeps it (at L = 1 the second, which sees the first give it up, and
    // from then on), the other sees it explained.
    CHECK((serial[0] > 0.0) != (serial[1] > 0.0));
    CHECK(serial[1] > 0.0);
  }
}

}  // namespace DABENCH_TEST_FILE
