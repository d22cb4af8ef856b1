// Tests of the TBD-BP message passing between potential objects and data cells
// (algorithms/tbd/cell_messages.hpp; tbd-bp-supplement eqs (1)-(9); docs/models/track-before-detect.md §3.3):
// the Gaussian κ̃ against expected values computed here from the model of
// harness/tbd/problem.hpp restated independently (tests/support/cell_messages.hpp; the code
// under test is never asked for an expected value), every PO's window the whole grid:
//  - κ̃ is the moment match of the exact κ: the exact κ_{n,j}(x, r) of the letter's eq (5),
//    enumerated as a Gaussian mixture over the other POs' states, has κ̃'s mean and covariance
//    (eqs (5), (9)), for D1 and D2, at β = α; λ equals the log ratio of those Gaussians.
//  - Iteration 2 uses the extrinsic β^(2) ∝ α Π_{j'≠j} κ̃^(1): moments, e, V, λ and the belief,
//    against an independent Gaussian message passing (eqs (5), (9)).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <Eigen/Dense>

#include "algorithms/tbd/cell_messages.hpp"
#include "algorithms/tbd/particle_object.hpp"
#include "harness/tbd/problem.hpp"
#include "tests/support/cell_messages.hpp"

namespace DABENCH_TEST_FILE {

namespace {

using namespace dabench;
using namespace dabench::test::cell_messages;
using dabench::test::signal_name;

// ---- An independent Gaussian message passing (supplement eqs (5), (9)) with full windows ----

// λ[n][cell][i]
using Lambdas = std::vector<std::vector<std::vector<double>>>;

Lambdas zero_lambdas(const Model& m, const std::vector<ParticleObject>& objects) {
  Lambdas l(objects.size());
  for (std::size_t n = 0; n < objects.size(); ++n) {
    l[n].assign(m.cells(), std::vector<double>(objects[n].size(), 0.0));
  }
  return l;
}

// β^(ℓ)_{n,j}(x_i, 1) ∝ w_i r exp(Σ_{j'≠j} λ^(ℓ−1)_{n,j'}(x_i)), β(0) ∝ 1 − r, normalised; its
// moments. With λ^(0) = 0 this is β^(1) = α.
std::vector<std::vector<Moments>> beta_moments(const Model& m, const std::vector<ParticleObject>& objects,
                                               const Lambdas& previous) {
  std::vector<std::vector<Moments>> out(objects.size(), std::vector<Moments>(m.cells()));
  for (std::size_t n = 0; n < objects.size(); ++n) {
    const ParticleObject& o = objects[n];
    const int p = o.size();
    std::vector<double> total(p, 0.0);
    for (int j = 0; j < m.cells(); ++j) {
      for (int i = 0; i < p; ++i) total[i] += previous[n][j][i];
    }
    for (int j = 0; j < m.cells(); ++j) {
      std::vector<double> log_b(p + 1);
      for (int i = 0; i < p; ++i) log_b[i] = std::log(o.weight[i] * o.existence) + total[i] - previous[n][j][i];
      log_b[p] = std::log(1.0 - o.existence);
      const double norm = log_sum_exp(log_b);
      Moments& mo = out[n][j];
      for (int i = 0; i < p; ++i) {
        const double b = std::exp(log_b[i] - norm);
        const Eigen::Vector2d mu = m.mu(j, o.x[i], o.y[i]);
        mo.mu += b * mu;
        mo.R += b * (m.c(j, o.x[i], o.y[i]) * Eigen::Matrix2d::Identity() + mu * mu.transpose());
      }
    }
  }
  return out;
}

// κ̃(0) of PO n at cell j: mean Σ_{n'≠n} μ_{n',j}, covariance C_ε + Σ_{n'≠n} (R − μμᵀ).
struct Kappa0 {
  Eigen::Vector2d mean;
  Eigen::Matrix2d cov;
};

Kappa0 kappa0(const Model& m, const std::vector<std::vector<Moments>>& mo, int n, int j) {
  Kappa0 k{Eigen::Vector2d::Zero(), m.sensor.noise_variance * Eigen::Matrix2d::Identity()};
  for (std::size_t o = 0; o < mo.size(); ++o) {
    if (static_cast<int>(o) == n) continue;
    k.mean += mo[o][j].mu;
    k.cov += mo[o][j].R - mo[o][j].mu * mo[o][j].mu.transpose();
  }
  return k;
}

Lambdas gaussian_lambdas(const Model& m, const Eigen::Matrix2Xd& frame, const std::vector<ParticleObject>& objects,
                         const std::vector<std::vector<Moments>>& mo) {
  Lambdas l = zero_lambdas(m, objects);
  for (std::size_t n = 0; n < objects.size(); ++n) {
    const ParticleObject& o = objects[n];
    for (int j = 0; j < m.cells(); ++j) {
      const Kappa0 k = kappa0(m, mo, static_cast<int>(n), j);
      const Eigen::Vector2d z = frame.col(j);
      const double absent = log_normal(z, k.mean, k.cov);
      for (int i = 0; i < o.size(); ++i) {
        l[n][j][i] = log_normal(z, k.mean + m.mu(j, o.x[i], o.y[i]),
                                k.cov + m.c(j, o.x[i], o.y[i]) * Eigen::Matrix2d::Identity()) -
                     absent;
      }
    }
  }
  return l;
}

}  // namespace

TEST_CASE("tbd cell messages: kappa-tilde is the moment match of the exact kappa (eqs 2-9) at beta = alpha",
          "[tbd][cell_messages][kappa]") {
  for (const TbdSignal signal : {TbdSignal::fluctuating, TbdSignal::deterministic}) {
    for (std::uint32_t trial = 0; trial < 2; ++trial) {
      INFO(signal_name(signal) << ", trial " << trial);
      ThreeObjects t = three_objects(signal, trial);
      const Model& m = t.model;
      CellMessages messages;
      run_whole_grid(messages, t, 1);

      const int count = static_cast<int>(t.objects.size());
      for (int n = 0; n < count; ++n) {
        require_window(messages.window(n), CellWindow{0, 6, 0, 6});
        const ParticleObject& self = t.objects[n];
        // The other POs (two of them) and their α-weighted states: absent or one particle.
        std::vector<int> others;
        for (int o = 0; o < count; ++o) {
          if (o != n) others.push_back(o);
        }
        REQUIRE(others.size() == 2);
        const ParticleObject& a = t.objects[others[0]];
        const ParticleObject& b = t.objects[others[1]];
        const auto alpha = [](const ParticleObject& o, int s) { return s < 0 ? 1.0 - o.existence : o.existence * o.weight[s]; };

        std::vector<double> expected_total(self.size(), 0.0);
        for (int j = 0; j < m.cells(); ++j) {
          INFO("PO " << n << ", cell " << j);
          const Eigen::Vector2d z = t.frame.col(j);
          // Exact κ_{n,j}(y_n) as a mixture over (s_a, s_b) (eq (1) with β = α): weights π,
          // component means m_s + r_n μ_j(x_n), covariances (σ² + c_s + r_n c_j(x_n)) I.
          // Its moments for r_n = 0 (then add r_n's own term per particle below, recomputing
          // the whole mixture so that nothing is assumed about eq (5)/(9)).
          const auto mixture_moments = [&](const Eigen::Vector2d& own_mean, double own_variance) {
            double total_weight = 0.0;
            Eigen::Vector2d mean = Eigen::Vector2d::Zero();
            Eigen::Matrix2d second = Eigen::Matrix2d::Zero();
            for (int sa = -1; sa < a.size(); ++sa) {
              for (int sb = -1; sb < b.size(); ++sb) {
                const double pi = alpha(a, sa) * alpha(b, sb);
                Eigen::Vector2d mc = own_mean;
                double vc = m.sensor.noise_variance + own_variance;
                if (sa >= 0) {
                  mc += m.mu(j, a.x[sa], a.y[sa]);
                  vc += m.c(j, a.x[sa], a.y[sa]);
                }
                if (sb >= 0) {
                  mc += m.mu(j, b.x[sb], b.y[sb]);
                  vc += m.c(j, b.x[sb], b.y[sb]);
                }
                total_weight += pi;
                mean += pi * mc;
                second += pi * (vc * Eigen::Matrix2d::Identity() + mc * mc.transpose());
              }
            }
            REQUIRE(total_weight == Approx(1.0).epsilon(1e-14));
            return Kappa0{mean, second - mean * mean.transpose()};
          };
          const dabench::CellMessages::CellTerms& terms = messages.cell_terms(n, j);
          const Eigen::Vector2d tilde_mean0 = z - Eigen::Vector2d(terms.e_x, terms.e_y);
          Eigen::Matrix2d tilde_cov0;
          tilde_cov0 << terms.v_xx, terms.v_xy, terms.v_xy, terms.v_yy;

          // r_n = 0.
          const Kappa0 exact0 = mixture_moments(Eigen::Vector2d::Zero(), 0.0);
          CHECK(tilde_mean0.x() == close(exact0.mean.x()));
          CHECK(tilde_mean0.y() == close(exact0.mean.y()));
          CHECK(tilde_cov0(0, 0) == close(exact0.cov(0, 0)));
          CHECK(tilde_cov0(0, 1) == close(exact0.cov(0, 1)));
          CHECK(tilde_cov0(1, 1) == close(exact0.cov(1, 1)));
          const double log_absent = log_normal(z, exact0.mean, exact0.cov);

          // r_n = 1, at each of PO n's particles.
          for (int i = 0; i < self.size(); ++i) {
            INFO("particle " << i);
            const Eigen::Vector2d own = m.mu(j, self.x[i], self.y[i]);
            const double own_c = m.c(j, self.x[i], self.y[i]);
            const Kappa0 exact1 = mixture_moments(own, own_c);
            const Eigen::Vector2d tilde_mean1 = tilde_mean0 + own;
            const Eigen::Matrix2d tilde_cov1 = tilde_cov0 + own_c * Eigen::Matrix2d::Identity();
            CHECK(tilde_mean1.x() == close(exact1.mean.x()));
            CHECK(tilde_mean1.y() == close(exact1.mean.y()));
            CHECK(tilde_cov1(0, 0) == close(exact1.cov(0, 0)));
            CHECK(tilde_cov1(0, 1) == close(exact1.cov(0, 1)));
            CHECK(tilde_cov1(1, 1) == close(exact1.cov(1, 1)));
            // λ_{n,j}(x_i) = log N(z; exact1 moments) − log N(z; exact0 moments).
            const double lambda = log_normal(z, exact1.mean, exact1.cov) - log_absent;
            CHECK(messages.log_ratio(n, j, i) == close(lambda, 1e-10, 1e-9));
            expected_total[i] += lambda;
          }
        }
        // Σ_j λ and the belief's log odds log r/(1 − r) + log Σ_i w_i exp(Σ_j λ).
        std::vector<double> terms(self.size());
        for (int i = 0; i < self.size(); ++i) {
          CHECK(messages.total_log_ratio(n)[i] == close(expected_total[i], 1e-10, 1e-9));
          terms[i] = std::log(self.weight[i]) + expected_total[i];
        }
        const double log_odds = std::log(self.existence / (1.0 - self.existence)) + log_sum_exp(terms);
        CHECK(messages.existence_log_odds(n) == close(log_odds, 1e-10, 1e-9));
      }
    }
  }
}

TEST_CASE("tbd cell messages: iteration 2 uses the extrinsic beta of the iteration-1 kappa-tilde",
          "[tbd][cell_messages][iteration]") {
  for (const TbdSignal signal : {TbdSignal::fluctuating, TbdSignal::deterministic}) {
    INFO(signal_name(signal));
    ThreeObjects t = three_objects(signal, 7);
    const Model& m = t.model;
    CellMessages messages;
    run_whole_grid(messages, t, 2);

    // By hand: β^(1) = α → κ̃^(1) → λ^(1) → β^(2) (extrinsic) → κ̃^(2) → λ^(2).
    const auto moments1 = beta_moments(m, t.objects, zero_lambdas(m, t.objects));
    const Lambdas lambda1 = gaussian_lambdas(m, t.frame, t.objects, moments1);
    const auto moments2 = beta_moments(m, t.objects, lambda1);
    const Lambdas lambda2 = gaussian_lambdas(m, t.frame, t.objects, moments2);

    // The second iteration matters here: β^(2)'s moments move away from α's.
    double largest_move = 0.0;
    for (std::size_t n = 0; n < t.objects.size(); ++n) {
      for (int j = 0; j < m.cells(); ++j) {
        largest_move = std::max(largest_move, (moments2[n][j].R - moments1[n][j].R).cwiseAbs().maxCoeff());
      }
    }
    INFO("largest |R^(2) - R^(1)| = " << largest_move);
    REQUIRE(largest_move > 0.5);

    for (int n = 0; n < static_cast<int>(t.objects.size()); ++n) {
      const ParticleObject& o = t.objects[n];
      std::vector<double> total(o.size(), 0.0);
      for (int j = 0; j < m.cells(); ++j) {
        INFO("PO " << n << ", cell " << j);
        const auto& terms = messages.cell_terms(n, j);
        CHECK(terms.mean_x == close(moments2[n][j].mu.x(), 1e-10, 1e-11));
        CHECK(terms.mean_y == close(moments2[n][j].mu.y(), 1e-10, 1e-11));
        CHECK(terms.r_xx == close(moments2[n][j].R(0, 0), 1e-10, 1e-11));
        CHECK(terms.r_xy == close(moments2[n][j].R(0, 1), 1e-10, 1e-11));
        CHECK(terms.r_yy == close(moments2[n][j].R(1, 1), 1e-10, 1e-11));
        const Kappa0 k = kappa0(m, moments2, n, j);
        CHECK(terms.e_x == close(t.frame(0, j) - k.mean.x(), 1e-10, 1e-10));
        CHECK(terms.e_y == close(t.frame(1, j) - k.mean.y(), 1e-10, 1e-10));
        CHECK(terms.v_xx == close(k.cov(0, 0), 1e-10, 1e-10));
        CHECK(terms.v_xy == close(k.cov(0, 1), 1e-10, 1e-10));
        CHECK(terms.v_yy == close(k.cov(1, 1), 1e-10, 1e-10));
        for (int i = 0; i < o.size(); ++i) {
          CHECK(messages.log_ratio(n, j, i) == close(lambda2[n][j][i], 1e-9, 1e-8));
          total[i] += lambda2[n][j][i];
        }
      }
      std::vector<double> log_terms(o.size());
      for (int i = 0; i < o.size(); ++i) {
        CHECK(messages.total_log_ratio(n)[i] == close(total[i], 1e-9, 1e-8));
        log_terms[i] = std::log(o.weight[i]) + total[i];
      }
      CHECK(messages.existence_log_odds(n) ==
            close(std::log(o.existence / (1.0 - o.existence)) + log_sum_exp(log_terms), 1e-9, 1e-8));

    }
  }
}

}  // namespace DABENCH_TEST_FILE
