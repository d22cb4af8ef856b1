#pragma once
// Loopy belief propagation for marginal association probabilities: the simplified algorithm of
// Williams & Lau 2014 (bp-marginal-association), Fig. 3.
//   L-R messages, eq (20):  μ_ij = ψ_i(j) / (1 + Σ_{j'≠j} ψ_i(j') ν_j'i)
//   R-L messages, eq (21):  ν_ji = 1 / (1 + Σ_{i'≠i} μ_i'j)
//   beliefs, eq (22):       p(a_i = j) = ψ_i(j) ν_ji / (1 + Σ_j' ψ_i(j') ν_j'i)
// Every N iterations the Theorem-3 test runs on d = max |log(ν/ν̃)| between the last two
// iterates, with contraction factor α = α(e^d, W*) of Lemmas 1–2 (Fig. 3 writes α(d, ·); the
// lemma's argument is L = exp(d)), and stops when α d/(1−α) < ½ log(1+δ), which by Lemma 4
// bounds every belief's deviation from the fixed point by δ. In floating point the messages
// can settle d few ulps apart before the bound is met (huge W*, tiny δ); d ≤ 32·ε also stops
// the iteration as converged, since no further iteration can move the messages.
//
// Sparse, allocation-free implementation: only gated pairs (ψ > 0) are stored. A measurement
// gated by a single target has ν ≡ 1 at every iteration, so those pairs are folded into a
// per-target constant and the loop runs over shared measurements only; zero weights stay
// exactly zero and cost nothing. When the remaining targets × shared measurements block is
// small and at least a quarter full, the iteration runs on that dense block instead (plain
// vector loops beat indexed ones there); both paths give bit-identical results. Where weights
// make a row or column sum reach 2^16, a guarded iteration keeps eqs (20)-(21) free of
// cancellation (the plain s − ψν is 0 for ψ ~ 1e20); it is bit-identical wherever none occurs.
#include <string>
#include <string_view>
#include <vector>

#include "harness/core/cache_aligned.hpp"
#include "harness/core/params.hpp"
#include "harness/single_scan/solver.hpp"

namespace dabench {

struct BpOptions {
  int check_every = 5;          // N of Fig. 3: iterations between convergence checks (paper: 5..20)
  double delta = 1e-3;          // δ: guaranteed bound on each belief's deviation from convergence
  int max_iterations = 100000;  // cap; reaching it reports converged = false
  int dense_cells = 1024;       // largest dense block for the dense kernel; 0 = always sparse

  void bind(ParamList& params) {
    params.add("check_every", check_every, "N: iterations between convergence checks (Fig. 3)");
    params.add("delta", delta, "belief deviation bound for the Theorem-3 stopping rule");
    params.add("max_iterations", max_iterations, "iteration cap (converged=0 if reached)");
    params.add("dense_cells", dense_cells, "largest dense block kernel (0 = sparse only; same results)");
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
  BeliefPropagation(const BeliefPropagation&) = delete;  // the message arrays point into arena_
  BeliefPropagation& operator=(const BeliefPropagation&) = delete;
  void solve(const SingleScanProblem& problem, MarginalTable& marginals, SolveReport& report) override;

 private:
  double build_edges(const SingleScanProblem& problem);  // returns W*
  void carve_arena(int targets, int measurements);       // points the message arrays into arena_
  void iterate_once();
  bool converged() const;  // Theorem-3 test on ν against ν̃
  void write_beliefs(int targets, int measurements, MarginalTable& marginals) const;

  Options options_;
  double w_star_ = 0.0;
  bool dense_ = false;               // iterate on the dense block (else on the edge lists)
  bool guarded_ = false;             // sums can reach 2^16: the cancellation-guarded iteration
  bool out_of_range_ = false;        // sums can overflow (ψ near 1e308): skipped:numerical
  int stride_ = 0;                   // dense row stride: shared measurements rounded up to 4
  int edges_ = 0;                    // shared edges of the current problem
  int active_ = 0;                   // targets with a shared edge
  int cells_ = 0;                    // message slots: edges, or block cells in dense mode
  int columns_ = 0;                  // column sums in use (shared measurements or stride)
  double stop_level_ = 0.0;          // ½ log(1 + δ)
  const double* weights_ = nullptr;  // normalised ψ of the current problem, row-major n×m
  // Index buffers only grow, so steady-state solves do not allocate.
  std::vector<double> normalized_;   // storage for weights_ when side weights are not all 1
  std::vector<int> column_degree_;   // gated targets per measurement
  std::vector<int> compact_column_;  // measurement → shared-measurement index, or -1
  // Targets with at least one shared measurement ("active"); their shared edges are stored
  // contiguously, target by target, in increasing measurement order.
  std::vector<int> active_target_;
  std::vector<int> active_begin_;    // size active+1
  std::vector<int> row_;             // active index of each shared edge's target
  std::vector<int> column_;          // shared-measurement index of each shared edge
  std::vector<int> measurement_;     // measurement of each shared edge
  std::vector<int> edge_cell_;       // dense mode: block cell of each shared edge
  std::vector<int> column_top_edge_; // guarded mode: the edge of each column's largest μ
  // The arrays the iteration touches, carved from one cache-aligned arena (it only grows) at
  // offsets fixed by the problem size, so their placement is the same on every solve.
  CacheAlignedVector<double> arena_;
  double* base_ = nullptr;           // 1 + Σ ψ over the target's exclusive measurements
  double* psi_ = nullptr;            // ψ per shared edge
  double* block_psi_ = nullptr;      // dense mode: ψ over the block, 0 where there is no edge
  double* block_product_ = nullptr;  // dense mode: ψ·ν scratch
  double* mu_ = nullptr;             // per shared edge, or per block cell in dense mode
  double* nu_ = nullptr;             // (likewise)
  double* nu_previous_ = nullptr;    // ν̃ of Fig. 3
  double* row_sum_ = nullptr;        // 1 + Σ_j ψ_ij ν_ji per active target
  double* column_sum_ = nullptr;     // 1 + Σ_i μ_ij per shared measurement
  double* column_top_ = nullptr;     // guarded mode: a column's largest μ, then its other terms' sum
};

}  // namespace dabench
