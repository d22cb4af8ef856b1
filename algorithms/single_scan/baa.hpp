#pragma once
// The Bakhtiar–Alavi–Amoozegar (BAA) approximation of the marginal association probabilities:
//   B. Bakhtiar, H. Alavi and F. Amoozegar, "Efficient algorithm for computing data association
//   probabilities for multitarget tracking", in Automated Target Tracking, Proc. SPIE 2756, 1996,
// ref. [16] of Williams & Lau 2014 (bp-marginal-association), the "BAA" baseline of Sec. V-A and
// Fig. 6, chosen there because the survey of K. Romeo, D. F. Crouse, Y. Bar-Shalom and P. Willett,
// "The JPDAF in practical systems: approximations", Proc. SPIE 7698, 2010 (ref. [12]) found it
// the approximation of choice.
//
// With S_i = 1 + Σ_k ψ_i(k) (ψ_i(0) = 1 normalisation of eq 9), two targets give exactly
//   p(a_1 = j) ∝ ψ_1(j) · (S_2 − ψ_2(j)),   p(a_1 = 0) ∝ S_2,
// since S_2 − ψ_2(j) sums the weights of every choice of target 2 that leaves j free. BAA extends
// this heuristically to n targets, per target t:
//   β_tj ∝ ψ_t(j) · Π_{i≠t} (S_i − ψ_i(j)),   β_t0 ∝ Π_{i≠t} S_i,   normalised over j = 0..m.
// Implemented in the equivalent ratio form (divide both by Π_{i≠t} S_i):
//   β_tj / β_t0 = ψ_t(j) · Π_{i≠t} f_ij,   f_ij = (S_i − ψ_i(j)) / S_i = 1 − ψ_i(j)/S_i ∈ (0, 1].
// A target i not gated to j has f_ij = 1, so the product runs over the targets gated to j only
// (in particular only over j's cluster); a measurement gated by one target has an empty product,
// so a target alone on its measurements gets plain PDA, p_0 = 1/(1 + Σψ), p_j = ψ_j/(1 + Σψ).
//
// Source check. We found no copy of the SPIE paper or of the Romeo et al. survey in the
// reference corpora we could search. The formula above agrees with the implementation in
// D. F. Crouse's Tracker Component Library, calc2DAssignmentProbsApprox.m, approxType 3
// ("The Bakhtiar and Alavi Algorithm", citing the same SPIE 2756 paper and the survey):
// beta(t,j) = G(t,j)·Π_{i≠t} Σ_{k≠j} G(i,k) with k over the measurements and i's missed-detection
// column, beta(t,0) = G(t,miss)·Π_{i≠t} Σ_k G(i,k), rows normalised. With G(i,miss) = 1 (our
// ψ normalisation), Σ_{k≠j} G(i,k) = S_i − ψ_i(j) and Σ_k G(i,k) = S_i: no difference. (That
// library names two authors, Bakhtiar and Alavi; the BP paper names three.)
//
// Side weights: applied to the normalised ψ_ij = w_ij/(w_i0 w_0j), in which form the two-target
// case is exact for any w_i0, w_0j (clutter weights do not appear in the product formula written
// on raw weights, which would not be exact).
//
// Numerics and cost, O(n + m + edges): S_i − ψ_i(j) is formed as 1 + Σ_{k≠j} ψ_i(k) from prefix
// and suffix sums (never by subtraction, so no cancellation when ψ_i(j) dominates S_i), on
// weights scaled by 1/max(1, max_k ψ_i(k)), which leaves f_ij unchanged and keeps any finite ψ
// from overflowing; 1 ≤ S_i − ψ_i(j) ≤ S_i gives f_ij ∈ [1/S_i, 1], never 0, and the product over
// the other targets gated to j is a leave-one-out product from prefix and suffix products (no
// division by the own factor). Such a product underflows only below ~1e-308, where β_tj ≤
// ψ_t(j)·1e-308 is invisible next to β_t0 = 1 anyway. (Sums of logs would also work; the
// prefix/suffix products are exact enough and need no log/exp.)
#include <string>
#include <string_view>
#include <vector>

#include "algorithms/single_scan/association_graph.hpp"
#include "harness/core/params.hpp"
#include "harness/single_scan/solver.hpp"

namespace dabench {

struct BaaOptions {
  // BAA has no parameters: it uses ψ alone.
  void bind(ParamList&) {}
  std::string validate() const { return {}; }
};

class BakhtiarAlaviAmoozegar final : public SingleScanSolver {
 public:
  using Options = BaaOptions;
  static constexpr std::string_view kName = "baa";
  static constexpr std::string_view kSummary =
      "Bakhtiar-Alavi-Amoozegar approximation (SPIE 1996): exact 2-target formula extended to n targets";

  explicit BakhtiarAlaviAmoozegar(const Options& options) : options_(options) {}
  void solve(const SingleScanProblem& problem, MarginalTable& marginals, SolveReport& report) override;

 private:
  Options options_;
  AssociationGraph graph_;
  std::vector<double> factor_;     // per edge (i, j): f_ij = (S_i − ψ_i(j)) / S_i
  std::vector<double> product_;    // per edge (t, j): Π_{i≠t} f_ij, then the unnormalised β_tj
};

}  // namespace dabench
