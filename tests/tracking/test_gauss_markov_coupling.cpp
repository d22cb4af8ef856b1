// Tests of the free-energy-maximising coupling of a Gauss–Markov chain with fixed marginals
// (algorithms/tracking/gauss_markov_coupling.hpp), each against something computed another way:
// the RTS smoother's G_k P_{k+1|K} of a linear Gaussian model (a Kalman filter and RTS smoother
// written out here), the Q-whitened closed form, the free energy's own terms
// (add_gauss_markov_energy) under random perturbations of the coupling, and its gradient by
// finite differences.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "algorithms/tracking/gauss_markov_coupling.hpp"
#include "algorithms/tracking/jdt_vb_free_energy_terms.hpp"

namespace DABENCH_TEST_FILE {

namespace {

using dabench::Gaussian;
using dabench::Vector;
using Eigen::MatrixXd;

MatrixXd random_matrix(std::mt19937_64& rng, int rows, int cols) {
  std::normal_distribution<double> z;
  return MatrixXd::NullaryExpr(rows, cols, [&](Eigen::Index, Eigen::Index) { return z(rng); });
}

MatrixXd random_covariance(std::mt19937_64& rng, int n) {
  const MatrixXd a = random_matrix(rng, n, n);
  return a * a.transpose() + 0.1 * MatrixXd::Identity(n, n);
}

MatrixXd coupling(const MatrixXd& now, const MatrixXd& next, const MatrixXd& f, const MatrixXd& q) {
  const auto c = dabench::gauss_markov_coupling(now, next, f, Eigen::LLT<MatrixXd>(q));
  REQUIRE(c.has_value());
  return *c;
}

// B's Gauss–Markov terms of the two-state chain with marginals N(0, now), N(0, next) and coupling c
// under x_2 = F x_1 + N(0, Q) (the head's term does not depend on c).
double chain_energy(const MatrixXd& now, const MatrixXd& next, const MatrixXd& c, const MatrixXd& f, const MatrixXd& q) {
  const int n = static_cast<int>(now.rows());
  dabench::GaussMarkovChain chain;
  chain.marginal = {Gaussian{Vector::Zero(n), now}, Gaussian{Vector::Zero(n), next}};
  chain.coupling = {c};
  return dabench::add_gauss_markov_energy(0.0, chain, {{Vector::Zero(n), now}, f, Eigen::LLT<MatrixXd>(q)});
}

// Whether [[now, c], [cᵀ, next]] is a covariance (positive definite, by Cholesky).
bool joint_is_gaussian(const MatrixXd& now, const MatrixXd& next, const MatrixXd& c) {
  const int n = static_cast<int>(now.rows());
  MatrixXd joint(2 * n, 2 * n);
  joint << now, c, c.transpose(), next;
  return Eigen::LLT<MatrixXd>(joint).info() == Eigen::Success;
}

// The least 1 − ρ² over the canonical correlations ρ of the joint: the least eigenvalue of
// I − Ρ Ρᵀ, Ρ = R⁻¹ C S⁻ᵀ (Σ = R Rᵀ, Σ' = S Sᵀ).
double conditional_fraction(const MatrixXd& now, const MatrixXd& next, const MatrixXd& c) {
  const MatrixXd r = Eigen::LLT<MatrixXd>(now).matrixL(), s = Eigen::LLT<MatrixXd>(next).matrixL();
  const MatrixXd rho = r.triangularView<Eigen::Lower>().solve(s.triangularView<Eigen::Lower>().solve(c.transpose()).transpose());
  const MatrixXd identity = MatrixXd::Identity(c.rows(), c.rows());
  return Eigen::SelfAdjointEigenSolver<MatrixXd>(identity - rho * rho.transpose()).eigenvalues().minCoeff();
}

// The natural scale of coupling entry (i, j): √(Σ_ii Σ'_jj).
MatrixXd entry_scale(const MatrixXd& now, const MatrixXd& next) {
  return (now.diagonal().cwiseSqrt() * next.diagonal().cwiseSqrt().transpose()).eval();
}

// ∂B/∂c_ij by central differences, times the entry's scale (so dimensionless). The step is
// 10⁻⁵ of the entry's scale times the least 1 − ρ² of the joint (B's curvature grows as 1/(1 − ρ²)).
MatrixXd scaled_gradient(const MatrixXd& now, const MatrixXd& next, const MatrixXd& c, const MatrixXd& f,
                         const MatrixXd& q) {
  const MatrixXd scale = entry_scale(now, next);
  const double gap = conditional_fraction(now, next, c);
  MatrixXd g(c.rows(), c.cols());
  for (Eigen::Index i = 0; i < c.rows(); ++i)
    for (Eigen::Index j = 0; j < c.cols(); ++j) {
      const double h = 1e-5 * gap * scale(i, j);
      MatrixXd up = c, down = c;
      up(i, j) += h;
      down(i, j) -= h;
      g(i, j) = (chain_energy(now, next, up, f, q) - chain_energy(now, next, down, f, q)) / (2.0 * h) * scale(i, j);
    }
  return g;
}

// The closed form in Q-whitened coordinates (needs F invertible): L = chol Q, M = L⁻¹F,
// A = M Σ Mᵀ, B = L⁻¹ Σ' L⁻ᵀ, G = B^{-½}[(B^{½} A B^{½} + I/4)^{½} − I/2]B^{-½}, C = M⁻¹ G B Lᵀ.
MatrixXd whitened_closed_form(const MatrixXd& now, const MatrixXd& next, const MatrixXd& f, const MatrixXd& q) {
  const int n = static_cast<int>(now.rows());
  const MatrixXd l = Eigen::LLT<MatrixXd>(q).matrixL();
  const MatrixXd m = l.triangularView<Eigen::Lower>().solve(f);
  const MatrixXd a = m * now * m.transpose();
  const MatrixXd l_inverse = l.inverse();
  const MatrixXd b = l_inverse * next * l_inverse.transpose();
  const Eigen::SelfAdjointEigenSolver<MatrixXd> b_eigen(b);
  const MatrixXd b_half = b_eigen.operatorSqrt(), b_inverse_half = b_eigen.operatorInverseSqrt();
  const MatrixXd k = b_half * a * b_half + 0.25 * MatrixXd::Identity(n, n);
  const MatrixXd root = Eigen::SelfAdjointEigenSolver<MatrixXd>(k).operatorSqrt();
  const MatrixXd g = b_inverse_half * (root - 0.5 * MatrixXd::Identity(n, n)) * b_inverse_half;
  return m.inverse() * g * b * l.transpose();
}

// The OTHR motion model (scenarios/tracking/othr.cpp): near-constant velocity in ground range
// and in bearing, T_s = 16 s, q_g = 10⁻⁸ km²/s³, q_ϑ = q_g / 1750² ≈ 3·10⁻¹⁵ rad²/s³.
struct LinearModel {
  MatrixXd f, q, h, r;
  Gaussian head;
};

LinearModel othr_like_model() {
  const double t = 16.0, qg = 1e-8, qb = 1e-8 / (1750.0 * 1750.0);
  Eigen::Matrix2d f1, q1;
  f1 << 1.0, t, 0.0, 1.0;
  q1 << t * t * t / 3.0, t * t / 2.0, t * t / 2.0, t;
  LinearModel m;
  m.f = MatrixXd::Zero(4, 4);
  m.q = MatrixXd::Zero(4, 4);
  m.f.block(0, 0, 2, 2) = f1;
  m.f.block(2, 2, 2, 2) = f1;
  m.q.block(0, 0, 2, 2) = qg * q1;
  m.q.block(2, 2, 2, 2) = qb * q1;
  m.h = MatrixXd::Zero(3, 4);  // range, range rate, bearing
  m.h(0, 0) = m.h(1, 1) = m.h(2, 2) = 1.0;
  m.r = Eigen::Vector3d(25.0, 1e-6, 9e-6).asDiagonal();
  m.head = {Eigen::Vector4d(1750.0, 0.1, 0.48, 8.7e-5), Eigen::Vector4d(400.0, 1e-4, 1e-3, 4e-8).asDiagonal()};
  return m;
}

// Kalman filter and RTS smoother of `model` over `scans` scans (a measurement where `observed`),
// measurements drawn from the model; returns the smoothed covariances and the smoother's
// couplings G_k P_{k+1|K}, G_k = P_{k|k} Fᵀ P_{k+1|k}⁻¹.
struct Smoothed {
  std::vector<MatrixXd> covariance, coupling;
};

Smoothed kalman_rts(const LinearModel& model, const std::vector<bool>& observed, std::mt19937_64& rng) {
  const int scans = static_cast<int>(observed.size());
  const int n = static_cast<int>(model.f.rows()), ny = static_cast<int>(model.h.rows());
  const MatrixXd q_root = Eigen::LLT<MatrixXd>(model.q).matrixL(), r_root = Eigen::LLT<MatrixXd>(model.r).matrixL();
  Vector x = model.head.mean;
  std::vector<Vector> mean(scans);
  std::vector<MatrixXd> filtered(scans), predicted(scans);
  for (int k = 0; k < scans; ++k) {
    Vector m;
    MatrixXd p;
    if (k == 0) {
      m = model.head.mean;
      p = model.head.covariance;
    } else {
      x = model.f * x + q_root * random_matrix(rng, n, 1);
      m = model.f * mean[k - 1];
      p = model.f * filtered[k - 1] * model.f.transpose() + model.q;
    }
    predicted[k] = p;
    if (observed[k]) {
      const Vector y = model.h * x + r_root * random_matrix(rng, ny, 1);
      const MatrixXd s = model.h * p * model.h.transpose() + model.r;
      const MatrixXd gain = p * model.h.transpose() * s.inverse();
      m += gain * (y - model.h * m);
      p = (MatrixXd::Identity(n, n) - gain * model.h) * p;
      p = 0.5 * (p + p.transpose()).eval();
    }
    mean[k] = m;
    filtered[k] = p;
  }
  Smoothed out;
  out.covariance.resize(scans);
  out.coupling.resize(scans - 1);
  out.covariance[scans - 1] = filtered[scans - 1];
  for (int k = scans - 2; k >= 0; --k) {
    const MatrixXd g = filtered[k] * model.f.transpose() * predicted[k + 1].inverse();
    const MatrixXd p = filtered[k] + g * (out.covariance[k + 1] - predicted[k + 1]) * g.transpose();
    out.covariance[k] = 0.5 * (p + p.transpose());
    out.coupling[k] = g * out.covariance[k + 1];
  }
  return out;
}

}  // namespace

TEST_CASE("gauss-markov coupling: on RTS smoother marginals it is the smoother's G P_{k+1|K}", "[jdt_vb]") {
  std::mt19937_64 rng(53);
  // Random linear Gaussian models (F invertible or not) and the OTHR motion model, with missed scans.
  std::vector<LinearModel> models;
  for (int n : {1, 2, 4}) {
    LinearModel m;
    m.f = MatrixXd::Identity(n, n) + 0.4 * random_matrix(rng, n, n);
    m.q = 0.3 * random_covariance(rng, n);
    m.h = random_matrix(rng, 1, n);
    m.r = MatrixXd::Constant(1, 1, 0.5);
    m.head = {random_matrix(rng, n, 1), random_covariance(rng, n)};
    models.push_back(m);
  }
  models.push_back(models.back());
  models.back().f.col(1).setZero();  // singular F
  models.push_back(othr_like_model());
  const std::vector<bool> observed = {true, true, false, true, false, false, true, true, true, false, true, true};
  for (std::size_t which = 0; which < models.size(); ++which) {
    const LinearModel& m = models[which];
    const Smoothed s = kalman_rts(m, observed, rng);
    for (std::size_t k = 0; k + 1 < s.covariance.size(); ++k) {
      const MatrixXd& now = s.covariance[k];
      const MatrixXd& next = s.covariance[k + 1];
      const MatrixXd c = coupling(now, next, m.f, m.q);
      const MatrixXd scale = entry_scale(now, next);
      INFO("model " << which << " step " << k);
      // Entrywise on the scale √(Σ_ii Σ'_jj) of each entry (the OTHR model's span 10⁻¹⁸..10²).
      CHECK((c - s.coupling[k]).cwiseQuotient(scale).cwiseAbs().maxCoeff() < 1e-7);
    }
  }
}

TEST_CASE("gauss-markov coupling: it maximises the chain's terms of B (a valid joint, zero gradient, "
          "no better perturbation, the issue's closed form)", "[jdt_vb]") {
  std::mt19937_64 rng(59);
  for (int trial = 0; trial < 40; ++trial) {
    const int n = 1 + trial % 4;
    const MatrixXd now = random_covariance(rng, n), next = random_covariance(rng, n);
    MatrixXd f = MatrixXd::Identity(n, n) + 0.5 * random_matrix(rng, n, n);
    const bool singular = n > 1 && trial % 3 == 0;
    if (singular) f.row(0) = 2.0 * f.row(n - 1);  // rank n − 1
    const MatrixXd q = std::pow(10.0, -1.0 + (trial % 5) * 0.5) * random_covariance(rng, n);
    const MatrixXd c = coupling(now, next, f, q);
    INFO("trial " << trial << " n " << n);
    REQUIRE(joint_is_gaussian(now, next, c));
    const double best = chain_energy(now, next, c, f, q);
    REQUIRE(std::isfinite(best));
    // The objective: B(C) − B(0) = tr(Q⁻¹ F C) + ½ log|Σ − C Σ'⁻¹ Cᵀ| − ½ log|Σ|.
    const MatrixXd q_inverse = q.inverse();
    const double objective = (q_inverse * f * c).trace() +
                             0.5 * std::log((now - c * next.inverse() * c.transpose()).determinant() / now.determinant());
    CHECK(best - chain_energy(now, next, MatrixXd::Zero(n, n), f, q) == Approx(objective).epsilon(1e-9).margin(1e-9));
    // Zero gradient; the same finite differences at C = 0 give the linear term's gradient Fᵀ Q⁻¹.
    const MatrixXd scale = entry_scale(now, next);
    const MatrixXd linear = (f.transpose() * q_inverse).cwiseProduct(scale);
    const MatrixXd at_zero = scaled_gradient(now, next, MatrixXd::Zero(n, n), f, q);
    CHECK((at_zero - linear).cwiseAbs().maxCoeff() < 1e-6 * (1.0 + linear.cwiseAbs().maxCoeff()));
    CHECK(scaled_gradient(now, next, c, f, q).cwiseAbs().maxCoeff() < 1e-6 * (1.0 + linear.cwiseAbs().maxCoeff()));
    // No valid perturbation of any size does better, and the independent chain does worse.
    const MatrixXd r = Eigen::LLT<MatrixXd>(now).matrixL(), s = Eigen::LLT<MatrixXd>(next).matrixL();
    for (int p = 0; p < 200; ++p) {
      // 10⁻⁴ .. 1 of the whitened scale, halved until the joint is a Gaussian.
      const MatrixXd direction = r * random_matrix(rng, n, n) * s.transpose();
      double size = std::pow(10.0, -4.0 + (p % 5));
      while (!joint_is_gaussian(now, next, c + size * direction)) size /= 2.0;
      CHECK(chain_energy(now, next, c + size * direction, f, q) <= best + 1e-12 * (1.0 + std::abs(best)));
    }
    CHECK(chain_energy(now, next, MatrixXd::Zero(n, n), f, q) < best);
    // The Q-whitened form agrees where F is invertible.
    if (!singular) CHECK((whitened_closed_form(now, next, f, q) - c).cwiseQuotient(scale).cwiseAbs().maxCoeff() < 1e-8);
  }
}

TEST_CASE("gauss-markov coupling: degenerate inputs give a finite coupling of a valid joint", "[jdt_vb]") {
  const LinearModel othr = othr_like_model();
  std::mt19937_64 rng(61);
  const MatrixXd base = random_covariance(rng, 4);
  const Eigen::Vector4d othr_scales(5.0, 1e-3, 1e-3, 1e-6);  // s.d.: km, km/s, rad, rad/s
  struct Case {
    const char* what;
    MatrixXd now, next, q;
  };
  const MatrixXd wide = othr_scales.asDiagonal() * base * othr_scales.asDiagonal();
  std::vector<Case> cases = {
      {"OTHR-scaled marginals, OTHR Q", wide, 1.3 * wide, othr.q},
      {"OTHR-scaled marginals, Q 1e-6 of OTHR's", wide, 1.3 * wide, 1e-6 * othr.q},
      {"marginals and Q all 1e-30 of the OTHR case", 1e-30 * wide, 1.3e-30 * wide, 1e-30 * othr.q},
      {"tiny variances against OTHR Q", 1e-20 * base, 1e-20 * base, othr.q},
      {"Q 1e-14 of the marginals (sigma beyond the floor)", base, base, 1e-14 * MatrixXd::Identity(4, 4)},
      {"Q with eigenvalues 1 and 1e-16", base, base, Eigen::Vector4d(1.0, 1.0, 1.0, 1e-16).asDiagonal()},
  };
  for (const Case& t : cases) {
    INFO(t.what);
    const MatrixXd c = coupling(t.now, t.next, othr.f, t.q);
    CHECK(c.allFinite());
    CHECK(joint_is_gaussian(t.now, t.next, c));
    CHECK(conditional_fraction(t.now, t.next, c) > 0.5 * dabench::kMinConditionalFraction);
    CHECK(std::isfinite(chain_energy(t.now, t.next, c, othr.f, t.q)));
    CHECK(chain_energy(t.now, t.next, c, othr.f, t.q) > chain_energy(t.now, t.next, MatrixXd::Zero(4, 4), othr.f, t.q));
  }
  // Scaling Σ, Σ' and Q together scales C alike.
  const MatrixXd unit = coupling(wide, 1.3 * wide, othr.f, othr.q);
  const MatrixXd tiny = coupling(1e-30 * wide, 1.3e-30 * wide, othr.f, 1e-30 * othr.q);
  CHECK((tiny * 1e30 - unit).cwiseQuotient(entry_scale(wide, 1.3 * wide)).cwiseAbs().maxCoeff() < 1e-10);
  // Marginals that are no covariance have no coupling.
  MatrixXd not_pd = base;
  not_pd(0, 0) = -1.0;
  CHECK_FALSE(dabench::gauss_markov_coupling(not_pd, base, othr.f, Eigen::LLT<MatrixXd>(othr.q)).has_value());
  CHECK_FALSE(dabench::gauss_markov_coupling(base, not_pd, othr.f, Eigen::LLT<MatrixXd>(othr.q)).has_value());
}

}  // namespace DABENCH_TEST_FILE
