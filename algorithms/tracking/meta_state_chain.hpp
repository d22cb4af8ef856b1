#pragma once
// Module 2 of JDT-VB (jdt-vb-multipath-othr, Sec. III-C2, eqs (38)–(40), Appendix C): the
// posterior q(s_{1:K}) of one target's two-state meta-state chain (s = 1 active, 0 dormant) by
// the forward–backward algorithm, given the evidence ξ_k(s) of eq (39) per scan.
//
//   q(s_{1:K}) ∝ p(s_1) e^{ξ_1(s_1)} Π_{k≥2} p(s_k | s_{k−1}) e^{ξ_k(s_k)}          (38)
//   ξ_k(s) = Σ_τ E[d^τ_k] log p^τ_d(s) + (1 − E[d^τ_k]) log(1 − p^τ_d(s))          (39)
//   E[d^τ_k] = Σ_j E[a^{j,τ}_k]                                                    (40)
//
// The transition matrix is symmetric as in Sec. IV-A2: p(s_k = s_{k−1}) = stay (0.85 there).
// The recursions are Module 2's, run with per-scan normalisation (α̂_k sums to one, the scale
// factors give log Z); ξ is taken about its larger entry so no e^ξ under- or overflows.
// Outputs: marginals q(s_k = 1), pairwise marginals q(s_k, s_{k+1}) and log Z = log Σ_{s_{1:K}}
// of the right side of (38). At the optimum of q(S) for a fixed ξ the meta-state part of the
// variational free energy, E_q[log p(S) + Σ_k ξ_k(s_k)] + H(q(S)), equals log Z.
#include <array>
#include <vector>

namespace dabench {

struct MetaStateChain {
  std::vector<double> active;                          // q(s_k = 1), k = 0..K−1
  std::vector<std::array<double, 4>> pairwise;         // q(s_k = a, s_{k+1} = b) at [2a + b], k = 0..K−2
  double log_partition = 0.0;                          // log Z of eq (38)
};

// Forward–backward for one chain. `evidence[k]` = {ξ_k(0), ξ_k(1)} (finite or −∞, not both −∞),
// `initial_active` = p(s_1 = 1) in [0, 1], `stay` = p(s_k = s_{k−1}) in (0, 1). InputError on
// violations. Scratch-free apart from the result's vectors (reused when `result` is reused).
void meta_state_forward_backward(const std::vector<std::array<double, 2>>& evidence, double initial_active,
                                 double stay, MetaStateChain& result);

// Filtering only (the forward pass): q(s_k = 1 | ξ_1..ξ_k) of the newest scan from the
// previous scan's filtered value, as used by the sequential initialisation pass (Sec. III-E).
double meta_state_filter_step(double previous_active, double stay, const std::array<double, 2>& evidence);

}  // namespace dabench
