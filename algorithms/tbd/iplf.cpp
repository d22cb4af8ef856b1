#include "algorithms/tbd/iplf.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Cholesky>

#include "harness/core/special_values.hpp"

namespace dabench {

namespace {

constexpr int kStateSize = 4;
constexpr int kUColumns = SigmaPoints::kCount + kStateSize;  // U = [√w_s e_s, A L_P]
constexpr int kColumnA = SigmaPoints::kCount;                 // the whitened M = [√w_s e_s, A, z − ẑ]
constexpr int kColumnInnovation = kColumnA + kStateSize;

// The inverse of the top-left q × q block of `b` (q = 1 or 2) into `inverse`; returns its log
// determinant (NaN if the block is not positive definite).
double block_inverse(const Eigen::Matrix2d& b, int q, Eigen::Matrix2d& inverse) {
  if (q == 1) {
    inverse(0, 0) = 1.0 / b(0, 0);
    return b(0, 0) > 0.0 ? std::log(b(0, 0)) : std::numeric_limits<double>::quiet_NaN();
  }
  const double det = b(0, 0) * b(1, 1) - b(0, 1) * b(1, 0);
  inverse << b(1, 1) / det, -b(0, 1) / det, -b(1, 0) / det, b(0, 0) / det;
  return det > 0.0 && b(0, 0) > 0.0 ? std::log(det) : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

// ---- sigma points ------------------------------------------------------------------------------

bool make_sigma_points(const Eigen::Vector4d& mean, const Eigen::Matrix4d& covariance, SigmaPoints& out) {
  const double w0 = SigmaPoints::kCentreWeight;
  const Eigen::LLT<Eigen::Matrix4d> llt(kStateSize / (1.0 - w0) * covariance);
  if (llt.info() != Eigen::Success) return false;
  const Eigen::Matrix4d root = llt.matrixL();
  out.points[0] = mean;
  out.weights[0] = w0;
  for (int i = 0; i < kStateSize; ++i) {
    out.points[1 + i] = mean + root.col(i);
    out.points[1 + kStateSize + i] = mean - root.col(i);
    out.weights[1 + i] = out.weights[1 + kStateSize + i] = (1.0 - w0) / (2 * kStateSize);
  }
  return true;
}

double kl_divergence(const Eigen::Vector4d& m0, const Eigen::Matrix4d& p0, const Eigen::Vector4d& m1,
                     const Eigen::Matrix4d& p1) {
  const Eigen::LLT<Eigen::Matrix4d> l0(p0), l1(p1);
  if (l0.info() != Eigen::Success || l1.info() != Eigen::Success) return std::numeric_limits<double>::infinity();
  const Eigen::Vector4d diff = m1 - m0;
  const double log_det0 = 2.0 * l0.matrixL().toDenseMatrix().diagonal().array().log().sum();
  const double log_det1 = 2.0 * l1.matrixL().toDenseMatrix().diagonal().array().log().sum();
  return 0.5 * (log_det1 - log_det0 + l1.solve(p0).trace() + diff.dot(l1.solve(diff)) - kStateSize);
}

// ---- IPLF --------------------------------------------------------------------------------------

void IplfUpdate::reserve(int rows, int blocks) {
  if (h_.rows() < rows) {
    h_.resize(rows, Eigen::NoChange);
    m_.resize(rows, Eigen::NoChange);
    ybar_.resize(rows);
  }
  if (static_cast<int>(noise_.size()) < blocks) {
    noise_.resize(blocks, Eigen::Matrix2d::Zero());
    l00_.resize(blocks);
    l10_.resize(blocks);
    l11_.resize(blocks);
  }
}

// Block c of D = noise_[c] (q × q) = L Lᵀ; every column of `m` ← L⁻¹ (its rows of block c).
// Returns log det D (NaN if a block is not positive definite).
template <class Block>
double IplfUpdate::whiten(int q, int blocks, Block& m) {
  double log_det = 0.0;
  auto inverse00 = l00_.head(blocks);
  if (q == 1) {
    for (int c = 0; c < blocks; ++c) inverse00(c) = 1.0 / std::sqrt(noise_[c](0, 0));
    log_det = -2.0 * inverse00.array().log().sum();
    for (int k = 0; k < m.cols(); ++k) m.col(k).array() *= inverse00.array();
    return log_det;
  }
  auto lower10 = l10_.head(blocks);
  auto inverse11 = l11_.head(blocks);
  for (int c = 0; c < blocks; ++c) {
    const double l00 = std::sqrt(noise_[c](0, 0));
    const double l10 = noise_[c](1, 0) / l00;
    const double l11 = std::sqrt(noise_[c](1, 1) - l10 * l10);
    inverse00(c) = 1.0 / l00;
    lower10(c) = l10;
    inverse11(c) = 1.0 / l11;
  }
  log_det = -2.0 * (inverse00.array().log().sum() + inverse11.array().log().sum());
  using Strided = Eigen::Map<Eigen::VectorXd, 0, Eigen::InnerStride<2>>;
  for (int k = 0; k < m.cols(); ++k) {
    Strided first(m.col(k).data(), blocks), second(m.col(k).data() + 1, blocks);
    first.array() *= inverse00.array();
    second.array() = (second.array() - lower10.array() * first.array()) * inverse11.array();
  }
  return log_det;
}

IplfResult IplfUpdate::run(const Eigen::Vector4d& mean, const Eigen::Matrix4d& covariance,
                           IplfMeasurement& measurement, int max_iterations, double kl_threshold) {
  IplfResult result;
  result.mean = mean;
  result.covariance = covariance;
  const int q = measurement.q;
  const int blocks = measurement.cells;
  const int d = q * blocks;
  reserve(d, blocks);

  // L₀ = N(z; E[z | absent], Cov[z | absent]), block by block.
  for (int c = 0; c < blocks; ++c) {
    Eigen::Matrix2d inverse;
    const double log_det = block_inverse(measurement.absent_covariance[c], q, inverse);
    const auto r = measurement.residual.segment(q * c, q);
    result.log_absent -= 0.5 * (q * kLog2Pi + log_det + r.dot(inverse.topLeftCorner(q, q) * r));
  }
  result.log_present = result.log_absent;
  if (d == 0) return result;

  const Eigen::Matrix4d prior_root = Eigen::LLT<Eigen::Matrix4d>(covariance).matrixL();
  Eigen::Matrix<double, SigmaPoints::kCount, 1> weights;
  Eigen::Vector4d iterate_mean = mean;
  Eigen::Matrix4d iterate_covariance = covariance;
  SigmaPoints sigma;
  result.converged = false;
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    if (!make_sigma_points(iterate_mean, iterate_covariance, sigma)) break;
    for (int s = 0; s < SigmaPoints::kCount; ++s) weights(s) = sigma.weights[s];
    measurement.evaluate(sigma, h_, noise_);
    const auto h = h_.topRows(d);
    auto ybar = ybar_.head(d);
    auto m = m_.topRows(d);
    auto a = m.middleCols<kStateSize>(kColumnA);

    // SLR about the iterate: ȳ = Σ w_s h_s, Ψᵀ = Σ w_s (h_s − ȳ)(χ_s − u)ᵀ = Σ w_s h_s (χ_s − u)ᵀ
    // (the offsets' weighted sum is 0), A = Ψᵀ W⁻¹.
    ybar.noalias() = h * weights;
    Eigen::Matrix<double, SigmaPoints::kCount, kStateSize> offsets;
    for (int s = 0; s < SigmaPoints::kCount; ++s) {
      offsets.row(s) = sigma.weights[s] * (sigma.points[s] - iterate_mean).transpose();
    }
    const Eigen::Matrix4d iterate_inverse =
        Eigen::LLT<Eigen::Matrix4d>(iterate_covariance).solve(Eigen::Matrix4d::Identity());
    a.noalias() = h * (offsets * iterate_inverse);
    // Φ − A W Aᵀ = Σ w_s e_s e_sᵀ with the residuals e_s = h_s − ȳ − A (χ_s − u), so
    // S = A P Aᵀ + Ω + S_corr = D + U Uᵀ with U = [√w_s e_s, A L_P] (rank 13) and
    // D = Σ_s w_s Cov[z | χ_s] block diagonal (S_corr in it).
    for (int s = 0; s < SigmaPoints::kCount; ++s) {
      m.col(s).noalias() = std::sqrt(sigma.weights[s]) * (h.col(s) - ybar - a * (sigma.points[s] - iterate_mean));
    }
    // Innovation: z − ẑ, ẑ = E[z | absent] + A m + b, b = ȳ − A u.
    m.col(kColumnInnovation).noalias() = measurement.residual.head(d) - ybar - a * (mean - iterate_mean);

    // Whiten M = [√w e, A, z − ẑ] by D's block Cholesky factors (D = L Lᵀ, M ← L⁻¹M); then
    // Mᵀ M holds every product of S⁻¹ through Woodbury: S⁻¹ = D⁻¹ − D⁻¹U C⁻¹ UᵀD⁻¹ with
    // C = I + UᵀD⁻¹U, and det S = det D · det C.
    const double log_det_d = whiten(q, blocks, m);
    Eigen::Matrix<double, kWhitened, kWhitened> gram;
    gram.noalias() = m.transpose() * m;
    const auto ee = gram.topLeftCorner<SigmaPoints::kCount, SigmaPoints::kCount>();
    const auto ea = gram.block<SigmaPoints::kCount, kStateSize>(0, kColumnA);
    const Eigen::Matrix4d aa = gram.block<kStateSize, kStateSize>(kColumnA, kColumnA);
    const Eigen::Vector4d ar = gram.block<kStateSize, 1>(kColumnA, kColumnInnovation);
    Eigen::Matrix<double, kUColumns, kUColumns> capacitance = Eigen::Matrix<double, kUColumns, kUColumns>::Identity();
    capacitance.topLeftCorner<SigmaPoints::kCount, SigmaPoints::kCount>() += ee;
    capacitance.topRightCorner<SigmaPoints::kCount, kStateSize>() = ea * prior_root;
    capacitance.bottomLeftCorner<kStateSize, SigmaPoints::kCount>() = prior_root.transpose() * ea.transpose();
    capacitance.bottomRightCorner<kStateSize, kStateSize>() += prior_root.transpose() * aa * prior_root;
    Eigen::Matrix<double, kUColumns, kStateSize> ua;  // UᵀD⁻¹A
    ua << ea, prior_root.transpose() * aa;
    Eigen::Matrix<double, kUColumns, 1> ur;  // UᵀD⁻¹(z − ẑ)
    ur << gram.block<SigmaPoints::kCount, 1>(0, kColumnInnovation), prior_root.transpose() * ar;
    const Eigen::LLT<Eigen::Matrix<double, kUColumns, kUColumns>> cap(capacitance);
    const double log_det = log_det_d + 2.0 * cap.matrixL().toDenseMatrix().diagonal().array().log().sum();
    const Eigen::Matrix<double, kUColumns, kStateSize> cua = cap.solve(ua);
    const Eigen::Matrix4d at_s_a = aa - ua.transpose() * cua;   // Aᵀ S⁻¹ A
    const Eigen::Vector4d at_s_r = ar - cua.transpose() * ur;   // Aᵀ S⁻¹ (z − ẑ)
    const double r_s_r = gram(kColumnInnovation, kColumnInnovation) - ur.dot(cap.solve(ur));
    const double log_present = -0.5 * (d * kLog2Pi + log_det + r_s_r);

    // Kalman update of the prior: K = P Aᵀ S⁻¹.
    const Eigen::Vector4d next_mean = mean + covariance * at_s_r;
    Eigen::Matrix4d next_covariance = covariance - covariance * at_s_a * covariance;
    next_covariance = 0.5 * (next_covariance + next_covariance.transpose()).eval();
    if (!std::isfinite(log_present) || Eigen::LLT<Eigen::Matrix4d>(next_covariance).info() != Eigen::Success) break;
    const double kl = kl_divergence(iterate_mean, iterate_covariance, next_mean, next_covariance);
    iterate_mean = next_mean;
    iterate_covariance = next_covariance;
    result.log_present = log_present;
    ++result.iterations;
    if (kl < kl_threshold) {
      result.converged = true;
      break;
    }
  }
  result.mean = iterate_mean;
  result.covariance = iterate_covariance;
  return result;
}

}  // namespace dabench
