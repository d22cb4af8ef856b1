#pragma once
// Cheap JPDA and its modification: closed-form approximations of the marginal association
// probabilities that need only row and column sums of ψ.
//
//   cheap-jpda  R. J. Fitzgerald, "Development of practical PDA logic for multitarget tracking by
//               microprocessor", in Multitarget-Multisensor Tracking: Advanced Applications
//               (Y. Bar-Shalom, ed.), Artech House, 1990, pp. 1-23:
//                 β_ij = ψ_ij / (S_i + T_j − ψ_ij + B),   β_i0 = 1 − Σ_j β_ij,
//               with S_i = Σ_j ψ_ij (target i's gated measurements), T_j = Σ_k ψ_kj (measurement
//               j's gated targets) and the bias B.
//   modified-cheap-jpda  P. Quan, Z. Hongcai, W. Peide and H. Zhou, "Development of new practical
//               multitarget data association algorithm", Proc. 1st IEEE Conf. on Control
//               Applications, 1992, pp. 1065-1066: T_j − ψ_ij is replaced by the weighted
//               Σ_{k≠i} r_kj ψ_kj with r_kj = ψ_kj / S_k (a target that spreads its weight over many
//               measurements competes less for each):
//                 β_ij = ψ_ij / (S_i + Σ_{k≠i} ψ_kj² / S_k + B),   β_i0 = 1 − Σ_j β_ij.
//
// Source check. We had neither publication. Both formulas are those of D. F. Crouse's Tracker
// Component Library, calc2DAssignmentProbsApprox.m, approxType 1 ("The cheap JPDA of [1]",
// Fitzgerald) and 2 ("The modified cheap JPDAF of [2]", Quan et al.), whose B is each target's
// missed-detection likelihood: in dabench's ψ form (ψ_i(0) = 1, eq 11 of bp-marginal-association)
// that is B = 1, the default of `bias`. Fitzgerald's B is a tuning constant of the clutter
// density; `bias` sets it (B = 0: no clutter and no missed detections beyond the remainder).
// The "modified cheap JPDA" attributed to Roecker & Phillis (IEEE TAES 29(2), 1993, "Suboptimal
// joint probabilistic data association") is a different method whose published form we could not
// consult; it is not implemented.
//
// Properties: with B > 0 every denominator exceeds S_i + B ≥ S_i, so Σ_j β_ij < S_i / (S_i + B) < 1
// and β_i0 > 0; a lone target (no other target gated to its measurements) gets exact PDA,
// β_ij = ψ_ij / (S_i + B) (exact for B = 1). Neither is exact for two targets sharing a measurement.
// Side weights: applied to the normalised ψ_ij = w_ij / (w_i0 w_0j).
//
// Numerics and cost, O(n + m + edges): the other targets' sum at measurement j (T_j − ψ_ij, or
// Σ_{k≠i} ψ_kj² / S_k) is a leave-one-out sum from prefix and suffix sums over j's gated targets,
// never a subtraction; ψ_kj² / S_k ≤ ψ_kj cannot overflow. A problem whose row or column sums of ψ
// overflow is refused (skipped:numerical), as bp and fbp refuse it.
#include <string>
#include <string_view>
#include <vector>

#include "algorithms/single_scan/association_graph.hpp"
#include "harness/core/params.hpp"
#include "harness/single_scan/solver.hpp"

namespace dabench {

struct CheapJpdaOptions {
  double bias = 1.0;  // B: the missed-detection term of every denominator (ψ_i(0) = 1 in dabench's form)
  void bind(ParamList& params) {
    params.add("bias", bias, "B >= 0: Fitzgerald's bias in every denominator (1 = the missed detection's weight)");
  }
  std::string validate() const;
};

// The two variants differ only in the competing sum at a measurement.
enum class CheapJpdaVariant { fitzgerald, quan };

class CheapJpdaSolver : public SingleScanSolver {
 public:
  CheapJpdaSolver(const CheapJpdaOptions& options, CheapJpdaVariant variant) : options_(options), variant_(variant) {}
  void solve(const SingleScanProblem& problem, MarginalTable& marginals, SolveReport& report) override;

 private:
  CheapJpdaOptions options_;
  CheapJpdaVariant variant_;
  AssociationGraph graph_;
  std::vector<double> row_sum_;   // S_i
  std::vector<double> term_;      // per edge (k, j): what k contributes at j (ψ_kj, or ψ_kj² / S_k)
  std::vector<double> others_;    // per edge (i, j): the other targets' terms at j
};

class CheapJpda final : public CheapJpdaSolver {
 public:
  using Options = CheapJpdaOptions;
  static constexpr std::string_view kName = "cheap-jpda";
  static constexpr std::string_view kSummary =
      "cheap JPDA (Fitzgerald 1990): beta_ij = psi_ij / (S_i + T_j - psi_ij + B) from row and column sums";
  explicit CheapJpda(const Options& options) : CheapJpdaSolver(options, CheapJpdaVariant::fitzgerald) {}
};

class ModifiedCheapJpda final : public CheapJpdaSolver {
 public:
  using Options = CheapJpdaOptions;
  static constexpr std::string_view kName = "modified-cheap-jpda";
  static constexpr std::string_view kSummary =
      "modified cheap JPDA (Quan, Hongcai, Peide & Zhou 1992): column term weighted by r_kj = psi_kj / S_k";
  explicit ModifiedCheapJpda(const Options& options) : CheapJpdaSolver(options, CheapJpdaVariant::quan) {}
};

}  // namespace dabench
