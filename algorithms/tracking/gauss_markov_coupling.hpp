#pragma once
// The coupling Cov(x_k, x_{k+1}) of a Gauss–Markov chain q(x_{1:K}) whose marginals are fixed,
// chosen to maximise the chain's terms of JDT-VB's free energy B (jdt-vb-multipath-othr, eq 6;
// the terms are algorithms/tracking/jdt_vb_free_energy_terms.hpp, add_gauss_markov_energy).
// Eq (32) fuses the per-path smoothers' marginals and says nothing of the joint; the coupling
// of the fused chain is then free, and this is its best value under the motion prior
// p(x_{k+1} | x_k) = N(F x_k, Q).
//
// Objective. Write Σ = Σ_k, Σ' = Σ_{k+1} for the marginal covariances and C for the coupling.
// Of E log p(x_{1:K}) + H(q(x_{1:K})) only two terms of step k depend on C:
//   E log N(x_{k+1}; F x_k, Q) contains −½ tr(Q⁻¹ E[e eᵀ]), E[e eᵀ] = Σ' − F C − (F C)ᵀ + F Σ Fᵀ + …,
//   H(q) contains H(x_k | x_{k+1}) = ½ log|D| + const, D = Σ − C Σ'⁻¹ Cᵀ,
// so, per step and independently of the others,
//   J(C) = tr(Q⁻¹ F C) + ½ log|Σ − C Σ'⁻¹ Cᵀ|,
// over the C for which the joint [[Σ, C], [Cᵀ, Σ']] is positive definite (a convex set). J is
// strictly concave there (log det of the joint, affine in C, plus a linear term), so a stationary
// point is the unique maximiser.
//
// Stationarity. dJ = tr(Q⁻¹ F dC) − tr(Σ'⁻¹ Cᵀ D⁻¹ dC), so ∇J = 0 is
//   D⁻¹ C Σ'⁻¹ = Fᵀ Q⁻¹,
// i.e. the off-diagonal block of the joint's precision equals the prior's, −Fᵀ Q⁻¹.
// An RTS smoother of this model satisfies it: with its gain G = P_f Fᵀ (F P_f Fᵀ + Q)⁻¹ and
// C = G P_{k+1|K}, D = P_f − G (F P_f Fᵀ + Q) Gᵀ = (P_f⁻¹ + Fᵀ Q⁻¹ F)⁻¹ and D⁻¹ G = Fᵀ Q⁻¹; so
// on smoother marginals the maximiser is the smoother's own G P_{k+1|K}.
//
// Closed form. With Cholesky factors Σ = R Rᵀ, Σ' = S Sᵀ write C = R Ρ Sᵀ (Ρ: the correlation
// of the whitened states). Then
//   J = tr(U Ρ) + ½ log|I − Ρ Ρᵀ| + log|R|,   U = Sᵀ Q⁻¹ F R,
// valid for ‖Ρ‖₂ < 1. With the SVD U = Y diag(σ) Vᵀ, von Neumann's trace inequality aligns the
// maximiser with it, Ρ = V diag(ρ) Yᵀ, and each canonical correlation maximises
// σ ρ + ½ log(1 − ρ²): σ ρ² + ρ − σ = 0, so
//   ρ(σ) = 2σ / (1 + √(1 + 4σ²)) ∈ [0, 1),   1 − ρ² = 2 / (1 + √(1 + 4σ²)),
//   C = R V diag(ρ) Yᵀ Sᵀ,   D = R V diag(1 − ρ²) Vᵀ Rᵀ.
// (Check: D⁻¹ C Σ'⁻¹ = R⁻ᵀ V diag(ρ / (1 − ρ²)) Yᵀ S⁻¹ = R⁻ᵀ V diag(σ) Yᵀ S⁻¹ = Fᵀ Q⁻¹.)
// Equivalently, in Q-whitened coordinates (L = chol Q, M = L⁻¹ F, A = M Σ Mᵀ, B = L⁻¹ Σ' L⁻ᵀ),
// G = B^{-½} [(B^{½} A B^{½} + I/4)^{½} − I/2] B^{-½} and C = M⁻¹ G B Lᵀ; that form needs F
// invertible, the one above does not (F enters only through U; a singular F gives σ = 0 in
// its null directions: those pairs are uncorrelated).
//
// Conditions: Σ, Σ' and Q positive definite (a singular Q is a deterministic step, whose E log p
// is −∞ unless Σ' = F Σ Fᵀ; the tracker skips such a problem). Only the product Q⁻¹ F enters, by a
// Cholesky solve, so a Q whose scales differ by many orders (the OTHR model: 10⁻⁸ km²/s³ in
// range, 3·10⁻¹⁵ rad²/s³ in bearing) costs nothing; and scaling Σ, Σ' and Q together leaves σ,
// Ρ and so the C of the whitened states unchanged. A near-singular Q against much larger
// marginals makes some σ huge and ρ → 1: the free energy then evaluates D = Σ − C Σ'⁻¹ Cᵀ by a
// difference that loses the digits of 1 − ρ², so 1 − ρ² is kept ≥ kMinConditionalFraction; that
// bound is met by the maximiser unless σ > 1 / kMinConditionalFraction (1 − ρ² ≈ 1/σ for large
// σ; measured in the OTHR runs of Table IV's settings, σ ≤ 6·10⁷, so it never binds there).
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
