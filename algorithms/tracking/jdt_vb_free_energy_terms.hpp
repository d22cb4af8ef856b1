#pragma once
// The terms of JDT-VB's free energy B (jdt-vb-multipath-othr, eq 6; the sum is written out in
// algorithms/tracking/jdt_vb.hpp) as functions of plain inputs, so each can be checked against
// brute force on its own:
//  - per scan: the clutter term Σ_j E[a^{0,j}] log λ and the Bethe entropy of q(A_k);
//  - per (track, path, scan, measurement): E_q log N(y | h^τ(x), R^τ) linearised as in eq (43);
//  - per track: E log p(x_i) + H(q(x_i)) of the Gauss–Markov chain q(x_i), and
//    E log p(s_i) + Σ_k E ξ_{i,k}(s_{i,k}) + H(q(s_i)) of the meta-state chain (eqs 38–39).
// Each sum is accumulated in a fixed order (the order the tracker's free energy has always used),
// so B is reproducible to the last bit.
#include <array>
#include <vector>

#include <Eigen/Cholesky>

#include "algorithms/tracking/meta_state_chain.hpp"
#include "algorithms/tracking/multipath_association.hpp"
#include "algorithms/tracking/ukf.hpp"

namespace dabench {

// Σ_j E[a^{0,j}] log λ of one scan: `clutter` holds E[a^{0,j}] of the measurements gated by some
// pseudo-target; the `ungated` others are clutter with certainty. λ: clutter density (per unit volume).
double clutter_energy(const Vector& clutter, int ungated, double log_clutter_density);

// H_Bethe(q(A_k)) of one scan's association on a sparse gate (Module 3's factor graph, eq 44
// without page factors): a binary a^{p,c} per gated pair, one row factor per pseudo-target p
// (a miss or one measurement) and one column factor per measurement c (clutter or one source):
//   H_Bethe = Σ_p H(row p) + Σ_c H(column c) − Σ_{gated (p,c)} H_2(E[a^{p,c}]),
// H(row p) the entropy of (E[a^{p,0}], E[a^{p,c}] for c in its gate), H(column c) likewise with
// E[a^{0,c}], H_2 the binary entropy (each pair variable sits in two factors). Exact on a gate
// whose bipartite graph is a forest. `gated_columns[p]`: the columns of q.detection gated by p.
double bethe_entropy(const MultipathAssociation& q, const std::vector<std::vector<int>>& gated_columns);

// Eq (43)'s linearised expected log-likelihood of one (track, path) at one scan: for
// q(x) = N(x̂, P), y = h(x) + v, v ~ N(0, R) and H the Jacobian of h at x̂,
//   E_q log N(y | h(x), R) ≈ −½ [n_y log 2π + log|R| + tr(R⁻¹ H P Hᵀ)] − ½ (y − h(x̂))ᵀ R⁻¹ (y − h(x̂)),
// exact when h is affine. (Eq 43 prints the constant as log(2π|R|^{−½}); the Gaussian's is the above.)
class LinearisedLogLikelihood {
 public:
  // `noise`: Cholesky factor of R; `predicted`: h(x̂); `jacobian`: H; `covariance`: P.
  LinearisedLogLikelihood(const Eigen::LLT<Eigen::MatrixXd>& noise, const Vector& predicted,
                          const Eigen::MatrixXd& jacobian, const Eigen::MatrixXd& covariance);
  double operator()(const Vector& y) const;  // the approximation of E_q log N(y | h(x), R)

 private:
  Eigen::LLT<Eigen::MatrixXd> noise_;
  Vector predicted_;
  double constant_;  // −½ [n_y log 2π + log|R| + tr(R⁻¹ H P Hᵀ)]
};

// A Gauss–Markov chain q(x_{1:K}): its marginals and the couplings Cov(x_k, x_{k+1}) (n × n, rows
// x_k), k = 1..K−1, which fix the joint Gaussian with the Markov property.
struct GaussMarkovChain {
  std::vector<Gaussian> marginal;
  std::vector<Eigen::MatrixXd> coupling;
};

// The motion prior p(x_{1:K}) = N(x_1; head) Π_k N(x_{k+1}; F x_k, Q).
struct GaussMarkovPrior {
  Gaussian head;
  Eigen::MatrixXd transition;          // F
  Eigen::LLT<Eigen::MatrixXd> process; // Cholesky factor of Q
};

// `sum` + E_q log p(x_{1:K}) + H(q(x_{1:K})), the terms added to `sum` one by one in chain order:
//   E log N(x_1; m, P₀) = −½ [tr(P₀⁻¹ Σ₁) + (x̂₁ − m)ᵀ P₀⁻¹ (x̂₁ − m) + n log 2π + log|P₀|],
//   E log N(x_{k+1}; F x_k, Q) = −½ [tr(Q⁻¹ E[e eᵀ]) + n log 2π + log|Q|], e = x_{k+1} − F x_k,
//     E[e eᵀ] = Σ_{k+1} − F C_k − (F C_k)ᵀ + F Σ_k Fᵀ + (x̂_{k+1} − F x̂_k)(…)ᵀ,
//   H(q) = Σ_{k<K} H(x_k | x_{k+1}) + H(x_K), Cov(x_k | x_{k+1}) = Σ_k − C_k Σ_{k+1}⁻¹ C_kᵀ,
//     H of an n-dimensional Gaussian = ½ [n (1 + log 2π) + log|Σ|].
// −∞ when a conditional covariance is not positive definite (the couplings are no joint Gaussian).
double add_gauss_markov_energy(double sum, const GaussMarkovChain& q, const GaussMarkovPrior& prior);

// E log p(s_{1:K}) + Σ_k E ξ_k(s_k) + H(q(s_{1:K})) of a two-state chain (s = 1 active) from q's
// single and pairwise marginals (`q.active`, `q.pairwise`), with p(s_1 = 1) = `initial_active`,
// p(s_{k+1} = s_k) = `stay` and `evidence[k]` = {ξ_k(0), ξ_k(1)} of eq (39):
//   H(q) = Σ_k H(s_k, s_{k+1}) − Σ_{1<k<K} H(s_k)   (H(s_1) when K = 1).
// At q = Module 2's posterior for this ξ this equals log Z of eq (38).
double meta_state_energy(const MetaStateChain& q, const std::vector<std::array<double, 2>>& evidence,
                         double initial_active, double stay);

}  // namespace dabench
