#pragma once
// Loopy belief propagation for marginal association probabilities: the simplified algorithm of
// Williams & Lau 2014 (bp-marginal-association), Fig. 3.
//   L-R messages, eq (20):  μ_ij = ψ_i(j) / (1 + Σ_{j'≠j} ψ_i(j') ν_j'i)
//   R-L messages, eq (21):  ν_ji = 1 / (1 + Σ_{i'≠i} μ_i'j)
//   beliefs, eq (22):       p(a_i = j) = ψ_i(j) ν_ji / (1 + Σ_j' ψ_i(j') ν_j'i)
// Every N iterations the Theorem-3 test runs on d = max |log(ν/ν̃)| between the last two
// iterates, with contraction factor α = α(e^d, W*) of Lemmas 1–2 (Fig. 3 writes α(d, ·); the
// lemma's argument is L = exp(d)), and stops when α d/(1−α) < ½ log(1+δ), which by Lemma 4
// bounds every belief's deviation from the fixed point by δ.
//
// Sparse, allocation-free implementation: only gated pairs (ψ > 0) are stored. A measurement
// gated by a single target has ν ≡ 1 at every iteration, so those pairs are folded into a
// per-target constant and the loop runs over shared measurements only; zero weights stay
// exactly zero and cost nothing.
#include <string>
#include <string_view>
#include <vector>

#include "algorithms/association_graph.hpp"
#include "harness/params.hpp"
#include "harness/single_scan_solver.hpp"

namespace dabench {

struct BpOptions {
  int check_every = 5;          // N of Fig. 3: iterations between convergence checks (paper: 5..20)
  double delta = 1e-3;          // δ: guaranteed bound on each belief's deviation from convergence
  int max_iterations = 100000;  // cap; reaching it reports converged = false

  void bind(ParamList& params) {
    params.add("check_every", check_every, "N: iterations between convergence checks (Fig. 3)");
    params.add("delta", delta, "belief deviation bound for the Theorem-3 stopping rule");
    params.add("max_iterations", max_iterations, "iteration cap (converged=0 if reached)");
  }
  std::string validate() const;
};

class BeliefPropagation final : public SingleScanSolver {
 public:
  using Options = BpOptions;
  static constexpr std::string_view kName = "bp";
  static constexpr std::string_view kSummary =
      "loopy BP, simplified messages eqs (20)-(22), Fig. 3 with the Theorem-3 stopping rule";

  explicit BeliefPropagation(const Options& options) : options_(options) {}
  void solve(const SingleScanProblem& problem, MarginalTable& marginals, SolveReport& report) override;

 private:
  void build_shared_edges();
  void iterate_once();
  double message_distance() const;  // d = max |log(ν/ν̃)|
  bool converged(double distance, double w_star) const;

  Options options_;
  AssociationGraph graph_;
  // Targets with at least one shared measurement, and their edges to shared measurements.
  std::vector<int> active_target_;
  std::vector<int> active_begin_;   // size active+1, into the shared-edge arrays
  std::vector<double> base_;        // 1 + Σ ψ over the target's exclusive measurements
  std::vector<double> psi_;         // shared-edge arrays
  std::vector<int> column_;         // compact index of the shared measurement
  std::vector<double> mu_;
  std::vector<double> nu_;
  std::vector<double> nu_previous_;
  std::vector<double> column_sum_;  // 1 + Σ_i μ_ij per shared measurement
  std::vector<int> compact_column_; // measurement → compact shared index or -1
  std::vector<int> edge_slot_;      // graph edge → shared-edge slot or -1
};

}  // namespace dabench
