#pragma once
// damped-bp: a toy algorithm written outside dabench, on its SingleScanSolver interface.
// Loopy BP of Williams & Lau 2014 (bp-marginal-association), Fig. 3, with damped messages:
//   L-R messages, eq (20):  μ_ij = ψ_i(j) / (1 + Σ_{j'≠j} ψ_i(j') ν_j'i)
//   R-L messages, eq (21):  ν̂_ji = 1 / (1 + Σ_{i'≠i} μ_i'j),  then  ν_ji ← (1 − d) ν̂_ji + d ν_ji
//   beliefs, eq (22):       p(a_i = j) = ψ_i(j) ν_ji / (1 + Σ_j' ψ_i(j') ν_j'i),  j = 0: ψ_i(0) ν = 1
// with damping d ∈ [0, 1). A fixed point of the damped update is one of eqs (20)-(21), so the
// beliefs are BP's: exact when the gating graph is a tree, approximate when it has cycles.
// Damping slows each step but calms oscillating messages. It stops when no message changed by
// more than `tolerance` (relative) in one iteration: a plain rule, not BP's Theorem-3 bound.
// Dense n×m loops, for clarity rather than speed.
#include <string>
#include <string_view>

#include "harness/core/matrix_types.hpp"
#include "harness/core/params.hpp"
#include "harness/single_scan/solver.hpp"

namespace outside {

struct DampedBpOptions {
  double damping = 0.5;        // d: weight of the previous message in each R-L update
  double tolerance = 1e-12;    // stop when max |ν_new − ν_old| / ν_old over one iteration is below this
  int max_iterations = 10000;  // cap; reaching it reports converged = false

  void bind(dabench::ParamList& params) {
    params.add("damping", damping, "d in [0, 1): weight of the previous R-L message (0 = plain BP)");
    params.add("tolerance", tolerance, "stop when no message changes by more than this (relative)");
    params.add("max_iterations", max_iterations, "iteration cap (converged=0 if reached)");
  }
  std::string validate() const;
};

class DampedBp final : public dabench::SingleScanSolver {
 public:
  using Options = DampedBpOptions;
  static constexpr std::string_view kName = "damped-bp";
  static constexpr std::string_view kSummary = "outside example: loopy BP eqs (20)-(22) with damped R-L messages";

  explicit DampedBp(const Options& options) : options_(options) {}
  void solve(const dabench::SingleScanProblem& problem, dabench::MarginalTable& marginals,
             dabench::SolveReport& report) override;

 private:
  Options options_;
  dabench::RowMatrix psi_;  // ψ_i(j) in the ψ_i(0) = 1 normalisation
  dabench::RowMatrix mu_;   // μ_ij, target i → measurement j
  dabench::RowMatrix nu_;   // ν_ji, measurement j → target i, stored at (i, j)
};

}  // namespace outside
