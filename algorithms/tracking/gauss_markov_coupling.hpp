#pragma once
// The coupling C = Cov(x_k, x_{k+1}) of a Gauss–Markov chain q(x_{1:K}) whose marginals
// Σ = Σ_k, Σ' = Σ_{k+1} are fixed, chosen to maximise the chain's terms of JDT-VB's free energy
// B (jdt-vb-multipath-othr, eq 6; the terms: algorithms/tracking/jdt_vb_free_energy_terms.hpp,
// add_gauss_markov_energy) under the motion prior p(x_{k+1} | x_k) = N(F x_k, Q). Eq (32) fixes
// only the marginals of the fused chain; this is the best value of its free coupling.
//
// Per step, independently of the others, C maximises
//   J(C) = tr(Q⁻¹ F C) + ½ log|Σ − C Σ'⁻¹ Cᵀ|
// over the C for which the joint [[Σ, C], [Cᵀ, Σ']] is positive definite. J is strictly concave
// there; its unique maximiser is the stationary point
//   D⁻¹ C Σ'⁻¹ = Fᵀ Q⁻¹,   D = Σ − C Σ'⁻¹ Cᵀ
// (the joint precision's off-diagonal block equals the prior's, −Fᵀ Q⁻¹). On RTS-smoother
// marginals of this model it is the smoother's own G P_{k+1|K}.
//
// Closed form (what gauss_markov_coupling() computes): Cholesky Σ = R Rᵀ, Σ' = S Sᵀ, SVD
// U = Sᵀ Q⁻¹ F R = Y diag(σ) Vᵀ, and per canonical correlation
//   ρ(σ) = 2σ / (1 + √(1 + 4σ²)) ∈ [0, 1),   C = R V diag(ρ) Yᵀ Sᵀ,   D = R V diag(1 − ρ²) Vᵀ Rᵀ.
// F need not be invertible (a singular F gives σ = 0 in its null directions: uncorrelated).
//
// Conditions: Σ, Σ' and Q positive definite. Only Q⁻¹ F enters, by a Cholesky solve, so a Q
// whose scales differ by many orders (the OTHR model's) costs nothing. 1 − ρ² is kept
// ≥ kMinConditionalFraction so that D stays computable; the maximiser meets that bound unless
// σ > 1 / kMinConditionalFraction.
// Background and derivation: docs/algorithms/tracking.md, "Gauss–Markov coupling".
#include <optional>

#include <Eigen/Cholesky>
#include <Eigen/Core>

namespace dabench {

// Least 1 − ρ² of a canonical correlation ρ: the least conditional variance of the whitened
// x_k given x_{k+1} along a canonical direction (its marginal variance there is 1).
inline constexpr double kMinConditionalFraction = 1e-9;

// The coupling C = Cov(x_k, x_{k+1}) (rows x_k) maximising tr(Q⁻¹ F C) + ½ log|Σ − C Σ'⁻¹ Cᵀ|
// for marginal covariances `now` = Σ and `next` = Σ', `transition` = F and `process` the Cholesky
// factor of Q. std::nullopt when `now` or `next` is not positive definite or not finite (no
// coupling then makes a joint Gaussian).
std::optional<Eigen::MatrixXd> gauss_markov_coupling(const Eigen::MatrixXd& now, const Eigen::MatrixXd& next,
                                                     const Eigen::MatrixXd& transition,
                                                     const Eigen::LLT<Eigen::MatrixXd>& process);

}  // namespace dabench
