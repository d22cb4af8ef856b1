// Tests of the terms of JDT-VB's free energy B (algorithms/tracking/jdt_vb_free_energy_terms.hpp),
// each against an independent computation on a tiny problem: the Bethe entropy and the clutter
// term against enumeration of every feasible association, eq (43) against the exact expectation
// (closed form and Monte Carlo) and a finite-difference linearisation of the OTHR model, the
// Gauss–Markov chain terms against the full joint Gaussian, the meta-state chain terms against
// enumeration of its 2^K sequences. (The tracker's own free-energy test cannot see a wrong term of
// Module 1's part: a Module-1 update that lowers B is rejected.)
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <numbers>
#include <random>

#include <Eigen/LU>

#include "algorithms/tracking/jdt_vb_free_energy_terms.hpp"
#include "algorithms/tracking/meta_state_chain.hpp"
#include "algorithms/tracking/multipath_association.hpp"
#include "scenarios/tracking/othr.hpp"

namespace DABENCH_TEST_FILE {

namespace {

using dabench::Gaussian;
using dabench::RowMatrix;
using dabench::Vector;
using Eigen::MatrixXd;

const double kLog2Pi = std::log(2.0 * std::numbers::pi);

double xlogx(double p) { return p > 0.0 ? p * std::log(p) : 0.0; }

// −Σ p log p of the listed probabilities.
double entropy(const std::vector<double>& p) {
  double h = 0.0;
  for (double v : p) h -= xlogx(v);
  return h;
}

// A single-scan pseudo-target association: χ per pair (−∞ = not gated), per miss, per clutter.
struct AssociationEvidence {
  RowMatrix detection;
  Vector miss, clutter;
};

// q(A) ∝ exp(χᵀA) over every feasible A (each row a miss or one gated column, each column used
// at most once), enumerated: its marginals, entropy, log Z and expected number of clutter columns.
struct Enumerated {
  dabench::MultipathAssociation marginals;
  double entropy = 0.0;
  double log_partition = 0.0;
  double clutter_count = 0.0;
};

Enumerated enumerate(const AssociationEvidence& chi) {
  const int rows = static_cast<int>(chi.detection.rows()), cols = static_cast<int>(chi.detection.cols());
  std::vector<std::vector<int>> events;  // per event: the column of each row, −1 = miss
  std::vector<double> log_weight;
  std::vector<int> pick(rows);
  std::vector<bool> used(cols, false);
  std::function<void(int)> assign = [&](int p) {
    if (p == rows) {
      double w = 0.0;
      for (int r = 0; r < rows; ++r) w += pick[r] < 0 ? chi.miss[r] : chi.detection(r, pick[r]);
      for (int c = 0; c < cols; ++c)
        if (!used[c]) w += chi.clutter[c];
      events.push_back(pick);
      log_weight.push_back(w);
      return;
    }
    pick[p] = -1;
    assign(p + 1);
    for (int c = 0; c < cols; ++c) {
      if (used[c] || !std::isfinite(chi.detection(p, c))) continue;
      pick[p] = c;
      used[c] = true;
      assign(p + 1);
      used[c] = false;
    }
  };
  assign(0);
  const double largest = *std::max_element(log_weight.begin(), log_weight.end());
  double total = 0.0;
  for (double w : log_weight) total += std::exp(w - largest);
  Enumerated e;
  e.log_partition = largest + std::log(total);
  e.marginals.detection = RowMatrix::Zero(rows, cols);
  e.marginals.miss = Vector::Zero(rows);
  e.marginals.clutter = Vector::Zero(cols);
  for (std::size_t a = 0; a < events.size(); ++a) {
    const double pi = std::exp(log_weight[a] - e.log_partition);
    e.entropy -= xlogx(pi);
    std::vector<bool> taken(cols, false);
    for (int r = 0; r < rows; ++r) {
      if (events[a][r] < 0) {
        e.marginals.miss[r] += pi;
      } else {
        e.marginals.detection(r, events[a][r]) += pi;
        taken[events[a][r]] = true;
      }
    }
    for (int c = 0; c < cols; ++c)
      if (!taken[c]) {
        e.marginals.clutter[c] += pi;
        e.clutter_count += pi;
      }
  }
  return e;
}

// Random χ on the gate `gated_columns` (rows × cols).
AssociationEvidence random_evidence(std::mt19937_64& rng, const std::vector<std::vector<int>>& gated_columns, int cols) {
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  const int rows = static_cast<int>(gated_columns.size());
  AssociationEvidence chi;
  chi.detection = RowMatrix::Constant(rows, cols, -HUGE_VAL);
  for (int p = 0; p < rows; ++p)
    for (int c : gated_columns[p]) chi.detection(p, c) = u(rng);
  chi.miss = Vector::NullaryExpr(rows, [&](Eigen::Index) { return u(rng); });
  chi.clutter = Vector::NullaryExpr(cols, [&](Eigen::Index) { return u(rng); });
  return chi;
}

MatrixXd random_matrix(std::mt19937_64& rng, int rows, int cols) {
  std::normal_distribution<double> z;
  return MatrixXd::NullaryExpr(rows, cols, [&](Eigen::Index, Eigen::Index) { return z(rng); });
}

MatrixXd random_covariance(std::mt19937_64& rng, int n) {
  const MatrixXd a = random_matrix(rng, n, n);
  return a * a.transpose() + 0.5 * MatrixXd::Identity(n, n);
}

// log N(y; m, S) with the inverse and determinant written out.
double log_normal(const Vector& y, const Vector& m, const MatrixXd& s) {
  const Vector d = y - m;
  return -0.5 * (static_cast<double>(y.size()) * kLog2Pi + std::log(s.determinant()) + d.dot(s.inverse() * d));
}

}  // namespace

TEST_CASE("jdt-vb free energy: the Bethe entropy on a forest gate is the exact entropy of q(A)", "[jdt_vb]") {
  std::mt19937_64 rng(17);
  // Gates whose bipartite pseudo-target/measurement graph has no cycle; the last column of each
  // is gated by nobody (a certain clutter measurement).
  const std::vector<std::vector<std::vector<int>>> gates = {
      {{0, 1}, {1}},                  // 2 × 2: one row gates both columns, the other one
      {{0, 1}, {1, 2}, {2}},          // a path p0–c1–p1–c2–p2
      {{0, 1, 2}, {0}, {1}, {3}},     // a star about p0, and a separate pair
  };
  for (const auto& gate : gates) {
    int cols = 0;
    for (const auto& g : gate)
      for (int c : g) cols = std::max(cols, c + 2);
    for (int draw = 0; draw < 3; ++draw) {
      const AssociationEvidence chi = random_evidence(rng, gate, cols);
      const Enumerated exact = enumerate(chi);
      CHECK(exact.marginals.clutter[cols - 1] == Approx(1.0).epsilon(1e-14));
      CHECK(dabench::bethe_entropy(exact.marginals, gate) == Approx(exact.entropy).epsilon(1e-12));
      // Module 3's LBP is exact on such a gate, and E[χᵀA] + H_Bethe is then log Z.
      dabench::MultipathEvidence evidence;
      evidence.targets = static_cast<int>(gate.size());
      evidence.paths = 1;
      evidence.detection = chi.detection;
      evidence.miss = chi.miss;
      evidence.clutter = chi.clutter;
      dabench::MultipathAssociation lbp;
      dabench::MultipathAssociationBp().solve(evidence, {}, lbp);
      double energy = chi.miss.dot(lbp.miss) + chi.clutter.dot(lbp.clutter);
      for (std::size_t p = 0; p < gate.size(); ++p)
        for (int c : gate[p]) {
          CHECK(lbp.detection(p, c) == Approx(exact.marginals.detection(p, c)).margin(1e-9));
          energy += chi.detection(p, c) * lbp.detection(p, c);
        }
      CHECK(energy + dabench::bethe_entropy(lbp, gate) == Approx(exact.log_partition).epsilon(1e-9));
    }
  }
}

TEST_CASE("jdt-vb free energy: the Bethe entropy on a loopy gate is the sum of its factor entropies", "[jdt_vb]") {
  std::mt19937_64 rng(23);
  const std::vector<std::vector<int>> gate = {{0, 1}, {0, 1}};  // 2 × 2, every pair gated: one cycle
  const AssociationEvidence chi = random_evidence(rng, gate, 2);
  const auto q = enumerate(chi);
  const auto& b = q.marginals.detection;
  const auto& m = q.marginals;
  const auto binary = [](double v) { return entropy({v, 1.0 - v}); };
  const double by_hand = entropy({m.miss[0], b(0, 0), b(0, 1)}) + entropy({m.miss[1], b(1, 0), b(1, 1)}) +
                         entropy({m.clutter[0], b(0, 0), b(1, 0)}) + entropy({m.clutter[1], b(0, 1), b(1, 1)}) -
                         binary(b(0, 0)) - binary(b(0, 1)) - binary(b(1, 0)) - binary(b(1, 1));
  const double bethe = dabench::bethe_entropy(q.marginals, gate);
  CHECK(bethe == Approx(by_hand).epsilon(1e-13));
  CHECK(std::abs(bethe - q.entropy) > 1e-3);  // on a cycle the Bethe form is not the entropy
  // A gated pair with E[a] = 0 adds nothing: the same marginals with a third, empty column.
  dabench::MultipathAssociation wider = q.marginals;
  wider.detection.conservativeResize(2, 3);
  wider.detection.col(2).setZero();
  wider.clutter.conservativeResize(3);
  wider.clutter[2] = 1.0;
  CHECK(dabench::bethe_entropy(wider, {{0, 1, 2}, {0, 1, 2}}) == Approx(bethe).epsilon(1e-15));
}

TEST_CASE("jdt-vb free energy: the clutter term counts the expected clutter, ungated measurements included", "[jdt_vb]") {
  std::mt19937_64 rng(29);
  const std::vector<std::vector<int>> gate = {{0, 1}, {1, 2}};
  const Enumerated q = enumerate(random_evidence(rng, gate, 3));
  const double log_density = std::log(125.0 / 2.0e4);
  // 3 gated measurements and 4 outside every gate.
  CHECK(dabench::clutter_energy(q.marginals.clutter, 4, log_density) == Approx((q.clutter_count + 4.0) * log_density).epsilon(1e-14));
  CHECK(dabench::clutter_energy(Vector(), 5, log_density) == Approx(5.0 * log_density).epsilon(1e-15));
}

TEST_CASE("jdt-vb free energy: eq (43) is the exact expected log-likelihood for a linear measurement", "[jdt_vb]") {
  std::mt19937_64 rng(31);
  const int nx = 4, ny = 3;
  const MatrixXd h = random_matrix(rng, ny, nx), r = random_covariance(rng, ny), p = random_covariance(rng, nx);
  const Vector mean = random_matrix(rng, nx, 1), y = h * mean + 2.0 * random_matrix(rng, ny, 1);
  const dabench::LinearisedLogLikelihood expected(Eigen::LLT<MatrixXd>(r), h * mean, h, p);
  // Closed form: E log N(y; Hx, R) = log N(y; Hx̂, R) − ½ tr(R⁻¹ H P Hᵀ).
  const double exact = log_normal(y, h * mean, r) - 0.5 * (r.inverse() * h * p * h.transpose()).trace();
  CHECK(expected(y) == Approx(exact).epsilon(1e-12));
  // Monte Carlo over x ~ N(x̂, P).
  const MatrixXd root = Eigen::LLT<MatrixXd>(p).matrixL();
  std::normal_distribution<double> z;
  const int samples = 200000;
  double sum = 0.0, sum2 = 0.0;
  for (int s = 0; s < samples; ++s) {
    const Vector x = mean + root * Vector::NullaryExpr(nx, [&](Eigen::Index) { return z(rng); });
    const double v = log_normal(y, h * x, r);
    sum += v;
    sum2 += v * v;
  }
  const double mc = sum / samples, se = std::sqrt((sum2 / samples - mc * mc) / samples);
  CHECK(std::abs(expected(y) - mc) < 4.0 * se);
  CHECK(se < 0.01 * std::abs(mc));
}

TEST_CASE("jdt-vb free energy: eq (43) for the OTHR model is the closed form at its linearisation", "[jdt_vb]") {
  const dabench::othr::OthrMeasurementModel sensor(5.0, 0.001, 0.003);
  const Vector x = dabench::othr::GroundState(1750.0, 0.1, 0.48, 8.7e-5);
  // q(x): s.d. 2 km in ground range, 0.5 m/s, 1 mrad, 1e-6 rad/s; correlation 0.5 between all.
  const Eigen::Vector4d sd(2.0, 5e-4, 1e-3, 1e-6);
  const MatrixXd correlation = 0.5 * (MatrixXd::Identity(4, 4) + MatrixXd::Ones(4, 4));
  const MatrixXd p = sd.asDiagonal() * correlation * sd.asDiagonal();
  const MatrixXd& r = sensor.noise_covariance(0);
  for (int path = 0; path < sensor.paths(); ++path) {
    // Jacobian by central differences (independent of the model's analytic one).
    MatrixXd jacobian(3, 4);
    for (int i = 0; i < 4; ++i) {
      const double step = 1e-4 * sd[i];
      Vector up = x, down = x;
      up[i] += step;
      down[i] -= step;
      jacobian.col(i) = (sensor.measure(path, up) - sensor.measure(path, down)) / (2.0 * step);
    }
    const Vector predicted = sensor.measure(path, x);
    Vector y = predicted;
    y += Eigen::Vector3d(4.0, -0.0008, 0.002);
    const double closed_form = -0.5 * (3.0 * kLog2Pi + std::log(r.determinant()) +
                                       (y - predicted).dot(r.inverse() * (y - predicted)) +
                                       (r.inverse() * jacobian * p * jacobian.transpose()).trace());
    const dabench::LinearisedLogLikelihood expected(Eigen::LLT<MatrixXd>(r), predicted, sensor.jacobian(path, x), p);
    CHECK(expected(y) == Approx(closed_form).epsilon(1e-7));
    // The trace term is of the same order as the others here, so a wrong H would show.
    const double trace = (r.inverse() * jacobian * p * jacobian.transpose()).trace();
    CHECK(trace > 0.1);
  }
}

namespace {

// A Gauss–Markov chain prior and the full-joint view of it: x = (x_1, …, x_K) ~ N(μ_p, Σ_p).
struct JointPrior {
  Vector mean;
  MatrixXd covariance;
};

JointPrior joint_prior(const dabench::GaussMarkovPrior& prior, int n, int scans) {
  const MatrixXd& f = prior.transition;
  const MatrixXd q = prior.process.reconstructedMatrix();
  JointPrior j{Vector(n * scans), MatrixXd(n * scans, n * scans)};
  j.mean.head(n) = prior.head.mean;
  j.covariance.block(0, 0, n, n) = prior.head.covariance;
  for (int k = 1; k < scans; ++k) {
    j.mean.segment(n * k, n) = f * j.mean.segment(n * (k - 1), n);
    for (int i = 0; i < k; ++i) {  // Cov(x_k, x_i) = F Cov(x_{k−1}, x_i)
      j.covariance.block(n * k, n * i, n, n) = f * j.covariance.block(n * (k - 1), n * i, n, n);
      j.covariance.block(n * i, n * k, n, n) = j.covariance.block(n * k, n * i, n, n).transpose();
    }
    j.covariance.block(n * k, n * k, n, n) = f * j.covariance.block(n * (k - 1), n * (k - 1), n, n) * f.transpose() + q;
  }
  return j;
}

// The chain's marginals and adjacent couplings read off a joint N(mean, covariance).
dabench::GaussMarkovChain chain_of(const Vector& mean, const MatrixXd& covariance, int n) {
  const int scans = static_cast<int>(mean.size()) / n;
  dabench::GaussMarkovChain q;
  for (int k = 0; k < scans; ++k) q.marginal.push_back({mean.segment(n * k, n), covariance.block(n * k, n * k, n, n)});
  for (int k = 0; k + 1 < scans; ++k) q.coupling.push_back(covariance.block(n * k, n * (k + 1), n, n));
  return q;
}

double gaussian_entropy(const MatrixXd& covariance) {
  return 0.5 * (static_cast<double>(covariance.rows()) * (1.0 + kLog2Pi) + std::log(covariance.determinant()));
}

}  // namespace

TEST_CASE("jdt-vb free energy: the Gauss-Markov chain terms equal E log p + H of the full joint", "[jdt_vb]") {
  std::mt19937_64 rng(37);
  for (const auto& [n, scans] : std::vector<std::pair<int, int>>{{1, 1}, {1, 3}, {2, 3}, {4, 2}}) {
    const int size = n * scans;
    dabench::GaussMarkovPrior prior{{random_matrix(rng, n, 1), random_covariance(rng, n)},
                                    MatrixXd::Identity(n, n) + 0.3 * random_matrix(rng, n, n),
                                    Eigen::LLT<MatrixXd>(random_covariance(rng, n))};
    const JointPrior p = joint_prior(prior, n, scans);
    const MatrixXd p_inverse = p.covariance.inverse();
    // q: a Markov joint, its precision block tridiagonal (L lower block bidiagonal, J = L Lᵀ).
    MatrixXd l = MatrixXd::Zero(size, size);
    for (int k = 0; k < scans; ++k) {
      MatrixXd d = random_matrix(rng, n, n).triangularView<Eigen::Lower>();
      d.diagonal() = d.diagonal().cwiseAbs().array() + 0.5;
      l.block(n * k, n * k, n, n) = d;
      if (k + 1 < scans) l.block(n * (k + 1), n * k, n, n) = random_matrix(rng, n, n);
    }
    const MatrixXd covariance = (l * l.transpose()).inverse();
    const Vector mean = p.mean + random_matrix(rng, size, 1);
    const Vector delta = mean - p.mean;
    const double expected_log_prior = -0.5 * ((p_inverse * covariance).trace() + delta.dot(p_inverse * delta) +
                                              size * kLog2Pi + std::log(p.covariance.determinant()));
    const dabench::GaussMarkovChain q = chain_of(mean, covariance, n);
    const double terms = dabench::add_gauss_markov_energy(0.0, q, prior);
    CHECK(terms == Approx(expected_log_prior + gaussian_entropy(covariance)).epsilon(1e-10));
    CHECK(dabench::add_gauss_markov_energy(-7.5, q, prior) == Approx(terms - 7.5).epsilon(1e-12));
    if (scans < 3) continue;
    // A joint that is not Markov: E log p sees only adjacent pairs, and H is that of the chain
    // with the same pairs, Σ_k H(x_k, x_{k+1}) − Σ_{1<k<K} H(x_k).
    const MatrixXd a = random_matrix(rng, size, size);
    const MatrixXd loopy = a * a.transpose() + 0.5 * MatrixXd::Identity(size, size);
    double chain_entropy = 0.0;
    for (int k = 0; k + 1 < scans; ++k) {
      chain_entropy += gaussian_entropy(loopy.block(n * k, n * k, 2 * n, 2 * n));
      if (k > 0) chain_entropy -= gaussian_entropy(loopy.block(n * k, n * k, n, n));
    }
    const double loopy_log_prior = -0.5 * ((p_inverse * loopy).trace() + delta.dot(p_inverse * delta) +
                                           size * kLog2Pi + std::log(p.covariance.determinant()));
    CHECK(dabench::add_gauss_markov_energy(0.0, chain_of(mean, loopy, n), prior) ==
          Approx(loopy_log_prior + chain_entropy).epsilon(1e-10));
    CHECK(chain_entropy > gaussian_entropy(loopy));  // the chain forgets the long-range dependence
  }
}

TEST_CASE("jdt-vb free energy: couplings that are no joint Gaussian give -inf", "[jdt_vb]") {
  dabench::GaussMarkovChain q;
  q.marginal = {{Vector::Zero(1), MatrixXd::Constant(1, 1, 1.0)}, {Vector::Zero(1), MatrixXd::Constant(1, 1, 1.0)}};
  q.coupling = {MatrixXd::Constant(1, 1, 1.5)};  // correlation 1.5
  const dabench::GaussMarkovPrior prior{{Vector::Zero(1), MatrixXd::Identity(1, 1)}, MatrixXd::Identity(1, 1),
                                        Eigen::LLT<MatrixXd>(MatrixXd::Identity(1, 1))};
  CHECK(dabench::add_gauss_markov_energy(0.0, q, prior) == -HUGE_VAL);
}

TEST_CASE("jdt-vb free energy: the meta-state chain terms equal enumeration of all sequences", "[jdt_vb]") {
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> u(0.05, 0.95), xi(-4.0, 1.0);
  const double stay = 0.85;
  // q(s_1) and q(s_{k+1} | s_k) (first = 1: s_1 = 1 for certain, p(s_1 = 1) = 1 too).
  for (const auto& [scans, certain_start] : std::vector<std::pair<int, bool>>{{3, false}, {3, true}, {1, false}, {4, false}}) {
    const double initial_active = certain_start ? 1.0 : 0.3;
    const double first = certain_start ? 1.0 : u(rng);
    std::vector<std::array<double, 2>> to_active(scans);  // q(s_{k+1} = 1 | s_k = 0, 1)
    for (auto& t : to_active) t = {u(rng), u(rng)};
    std::vector<std::array<double, 2>> evidence(scans);
    for (auto& e : evidence) e = {xi(rng), xi(rng)};
    dabench::MetaStateChain q;
    q.active.assign(scans, 0.0);
    q.pairwise.assign(scans - 1, {0, 0, 0, 0});
    double brute = 0.0;
    for (int mask = 0; mask < (1 << scans); ++mask) {
      const auto s = [&](int k) { return (mask >> k) & 1; };
      double qs = s(0) ? first : 1.0 - first;
      double log_p = std::log(s(0) ? initial_active : 1.0 - initial_active) + evidence[0][s(0)];
      for (int k = 1; k < scans; ++k) {
        const double up = to_active[k - 1][s(k - 1)];
        qs *= s(k) ? up : 1.0 - up;
        log_p += std::log(s(k) == s(k - 1) ? stay : 1.0 - stay) + evidence[k][s(k)];
      }
      if (qs == 0.0) continue;
      brute += qs * (log_p - std::log(qs));
      for (int k = 0; k < scans; ++k) q.active[k] += s(k) * qs;
      for (int k = 0; k + 1 < scans; ++k) q.pairwise[k][2 * s(k) + s(k + 1)] += qs;
    }
    CHECK(dabench::meta_state_energy(q, evidence, initial_active, stay) == Approx(brute).epsilon(1e-12));
  }
  // At Module 2's posterior for this ξ the terms are log Z of eq (38).
  std::vector<std::array<double, 2>> evidence(6);
  for (auto& e : evidence) e = {xi(rng), xi(rng)};
  dabench::MetaStateChain posterior;
  dabench::meta_state_forward_backward(evidence, 0.3, stay, posterior);
  CHECK(dabench::meta_state_energy(posterior, evidence, 0.3, stay) == Approx(posterior.log_partition).epsilon(1e-12));
}

}  // namespace DABENCH_TEST_FILE
