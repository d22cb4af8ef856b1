#pragma once
// JPDA-BP: the baseline of Williams & Lau, "Multiple scan data association by convex
// variational inference" (multiscan-convex-variational), Sec. IV: JPDA with particle tracks,
// association probabilities by single-scan BP, sensors processed sequentially; the variational
// reading is the product-of-marginals approximation discussed in Sec. III (the remark before
// Theorem 3: "analogous to the approximation that JPDA makes").
//
// Scans are taken in the problem's order. With q^i the current belief of track i (initially its
// prior ψ^i normalised), each scan t:
//   1. single-scan weights   w^{i,j} = Σ_p q^i(p) ψ^i_t(p, j),  j = 0..m_t (j = 0: missed);
//   2. association marginals P(a_i = j) by `bp` on ψ_i(j) = w^{i,j} / w^{i,0} (eq 11's ψ_i(0) = 1
//      normalisation; this is the exact single-scan problem of the predicted tracks);
//   3. product-of-marginals update   q^i(p) ∝ q^i(p) Σ_j P(a_i = j) ψ^i_t(p, j) / w^{i,j}
//      (terms with w^{i,j} = 0 have P(a_i = j) = 0 and are left out).
// Outputs the final q^i and the scan's P(a_i = j) as the association beliefs q^{i,j}_t.
// With one track, or tracks that share no measurement, BP is exact and so is the result
// (the exact Bayes posterior). A track whose w^{i,0} is 0 (a scan no track can miss) cannot be
// put in the ψ_i(0) = 1 form: the solve is skipped (skipped:zero_miss_weight).
// Report: iterations = total BP iterations over the scans, converged = every BP converged.
#include <string>
#include <string_view>
#include <vector>

#include "algorithms/single_scan/bp.hpp"
#include "harness/core/params.hpp"
#include "harness/multi_scan/solver.hpp"

namespace dabench {

struct JpdaBpOptions {
  double delta = 1e-9;            // δ of the single-scan BP stopping rule (bp's Theorem-3 bound)
  int max_iterations = 100000;    // cap of each single-scan BP

  void bind(ParamList& params) {
    params.add("delta", delta, "single-scan BP belief deviation bound (Theorem-3 stopping rule)");
    params.add("max_iterations", max_iterations, "iteration cap of each single-scan BP");
  }
  std::string validate() const;
};

class JpdaBp final : public MultiScanSolver {
 public:
  using Options = JpdaBpOptions;
  static constexpr std::string_view kName = "jpda-bp";
  static constexpr std::string_view kSummary =
      "JPDA with particle tracks: scans in turn, single-scan BP marginals, product-of-marginals update (Sec. IV)";

  explicit JpdaBp(const Options& options);
  void solve(const MultiScanProblem& problem, MultiScanBeliefs& beliefs, SolveReport& report) override;

 private:
  Options options_;
  BeliefPropagation bp_;  // the single-scan BP of step 2, with delta and max_iterations
  SingleScanProblem scan_problem_;
  RowMatrix weights_;  // n × (m + 1): w^{i,j}
};

}  // namespace dabench
