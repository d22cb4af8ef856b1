// The free-energy-maximising coupling of a Gauss–Markov chain (algorithms/tracking/gauss_markov_coupling.hpp).
#include "algorithms/tracking/gauss_markov_coupling.hpp"

#include <cmath>

#include <Eigen/SVD>

namespace dabench {

std::optional<Eigen::MatrixXd> gauss_markov_coupling(const Eigen::MatrixXd& now, const Eigen::MatrixXd& next,
                                                     const Eigen::MatrixXd& transition,
                                                     const Eigen::LLT<Eigen::MatrixXd>& process) {
  const Eigen::LLT<Eigen::MatrixXd> now_llt(now), next_llt(next);
  // (A NaN pivot passes Eigen's test: finiteness is checked too.)
  if (now_llt.info() != Eigen::Success || next_llt.info() != Eigen::Success || !now_llt.matrixLLT().allFinite() ||
      !next_llt.matrixLLT().allFinite())
    return std::nullopt;
  const Eigen::MatrixXd r = now_llt.matrixL(), s = next_llt.matrixL();
  // U = Sᵀ Q⁻¹ F R = Y diag(σ) Vᵀ.
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(s.transpose() * process.solve(transition * r),
                                              Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::VectorXd rho(svd.singularValues().size());
  for (Eigen::Index i = 0; i < rho.size(); ++i) {
    const double sigma = svd.singularValues()[i];
    const double root = std::hypot(1.0, 2.0 * sigma);  // √(1 + 4σ²) without overflow
    rho[i] = 2.0 / (1.0 + root) < kMinConditionalFraction ? std::sqrt(1.0 - kMinConditionalFraction)
                                                           : 2.0 * sigma / (1.0 + root);
  }
  // C = R V diag(ρ) Yᵀ Sᵀ (the SVD's U is Y here).
  return Eigen::MatrixXd(r * svd.matrixV() * rho.asDiagonal() * svd.matrixU().transpose() * s.transpose());
}

}  // namespace dabench
