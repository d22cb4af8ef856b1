#pragma once
// Junction-tree algorithm ("jt") on the pairwise formulation of Williams & Lau 2014
// (bp-marginal-association), Section IV-A, eqs (37)-(39):
//
//   p(a^1, ..., a^n) ∝ Π_i ψ_i(a^i) · Π_{(i,i') ∈ E} ψ_c(a^i, a^i')                     (37)
//   ψ_c(a^i, a^i') = 0 if a^i = a^i' > 0, else 1                                          (38)
//   E = {(i, i') : i ≠ i', ∃ j with ψ_i(j) ψ_i'(j) > 0}                                   (39)
//
// with associations whose weight (see threshold_on) is below τ removed first: a^i ranges over
// {0} ∪ {j : weight_ij ≥ τ}. The textbook algorithm (Koller & Friedman ch. 10, Hugin passes),
// written from scratch, per cluster of the gating graph (the joint factorises over clusters):
//
//  1. Elimination order by min-fill, ties by min-weight, then lowest index. When the maximal
//     cliques hold more than 2^16 entries in all, min-fill with index ties (libDAI JTree's rule),
//     min-weight and weighted min-fill are tried too, and the order with the fewest entries kept.
//  2. Clique tree: maximum-weight spanning tree (Prim, weight = shared variables), which has the
//     running-intersection property; disconnected parts are joined by empty separators.
//  3. Memory budget: the dense clique, separator and scratch tables (doubles, saturating 64-bit
//     sizes) are totalled BEFORE anything is allocated; above `memory_mb` (per cluster) the solve
//     reports skipped:memory.
//  4. Sum-product, Hugin style: collect, then distribute (child × new/old separator, 0/0 = 0).
//     Messages are scaled to max 1 with the log of the scale accumulated (log_partition()); a
//     clique whose product would underflow is recomputed in the log domain; a separator state
//     emptied by underflow that the parent sends mass to makes the solve skipped:numerical.
//  5. Marginals of each target from the smallest clique containing it.
//
// Tables are dense with strides (first variable fastest), but every pass walks only the
// consistent configurations of a clique (no two variables on one measurement) by a depth-first
// odometer: since ψ_c is 0/1 the other entries are exactly zero and are never read or written.
// This pruning is not part of a plain junction tree (libDAI's JTree, the paper's): memory and
// clique states compare with it, time does not.
//
// threshold_on, since the paper only says "thresholds applied to ψ_i(j)": 0 (default) τ on ψ_i(j)
// of eq (11); 1 on g_ij = ψ_ij λ_fa (1 − Pd) / Pd and 3 on (1 − Pd) ψ_ij (both need
// problem.context, else skipped:no_context); 2 on p_ij = ψ_ij / (1 + Σ_j' ψ_ij'). With τ = 0 every
// reading keeps every ψ > 0, and jt equals `exact`.
// Background and our readings: docs/algorithms/single-scan.md, "Junction tree".
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "algorithms/single_scan/association_graph.hpp"
#include "harness/core/params.hpp"
#include "harness/single_scan/solver.hpp"

namespace dabench {

struct JtOptions {
  double threshold = 0.0;          // τ: associations whose weight (see threshold_on) is below τ are removed
  int threshold_on = 0;            // 0: ψ (eq 11), 1: g = ψ λ_fa (1−Pd)/Pd, 2: ψ/(1+Σψ), 3: (1−Pd) ψ
  // Budget for one cluster's tables (cliques + separators + scratch, MiB). The default, 3.5 GiB =
  // 4.7e8 doubles, takes every clique tree within libDAI JTree's bound of 1.5e8 clique states:
  // each separator is smaller than its child clique and the scratch than the separators, so the
  // tables total at most 3× the clique states.
  std::int64_t memory_mb = 3584;

  void bind(ParamList& params) {
    params.add("threshold", threshold, "weights below this are removed before the junction tree is built");
    params.add("threshold_on", threshold_on,
               "what the threshold applies to: 0 psi (eq 11), 1 Gaussian likelihood psi*lambda_fa*(1-pd)/pd, "
               "2 PDA probability psi/(1+sum psi), 3 (1-pd)*psi");
    params.add("memory_mb", memory_mb, "table memory budget per cluster in MiB (skipped:memory above)");
  }
  std::string validate() const;
};

// Triangulation and clique tree of a small undirected graph over variables 0..n-1 with given
// domain sizes (step 1-2 above). Public so tests can check the running-intersection property.
// Storage is reused between builds.
class JunctionTreeBuilder {
 public:
  // Starts a graph with `vars` variables and no edges; domain[v] >= 1.
  void reset(int vars, const int* domain);
  void add_edge(int a, int b);  // a != b; repeated edges are fine
  // Triangulates (step 1 above) and builds the clique tree. Returns false if no order keeps the
  // maximal cliques within `max_total_entries` table entries in all (an order is abandoned as
  // soon as one of its cliques alone exceeds that).
  [[nodiscard]] bool build(std::uint64_t max_total_entries);

  // Greedy elimination rules (step 1 above).
  enum class EliminationRule { min_fill, min_fill_by_index, min_weight, weighted_min_fill };
  // The min-fill order is kept without trying the others when its cliques hold at most this
  // many entries (small problems keep one fixed order; their time: solve_grid_jt at 2×3 in
  // bench/single_scan/bench_jt.cpp).
  static constexpr std::uint64_t kTryOtherRulesAbove = std::uint64_t{1} << 16;
  EliminationRule rule() const { return rule_; }                              // of the last build
  std::uint64_t total_clique_entries() const { return total_clique_entries_; }  // Σ maximal cliques

  int vars() const { return vars_; }
  // Cliques are numbered so that parent(c) < c; clique 0 is the root (parent -1).
  int cliques() const { return static_cast<int>(clique_begin_.size()) - 1; }
  int clique_size(int c) const { return clique_begin_[c + 1] - clique_begin_[c]; }
  const int* clique_vars(int c) const { return clique_vars_.data() + clique_begin_[c]; }  // ascending
  int parent(int c) const { return parent_[c]; }
  std::uint64_t clique_entries(int c) const { return clique_entries_[c]; }  // Π domain, saturating
  const std::vector<int>& elimination_order() const { return elimination_order_; }

 private:
  std::uint64_t* row(std::vector<std::uint64_t>& bits, int v) { return bits.data() + static_cast<std::size_t>(v) * words_; }
  int vars_ = 0;
  int words_ = 0;
  std::vector<int> domain_;
  std::vector<std::uint64_t> adjacency_;       // vars × words bitsets: the graph
  std::vector<std::uint64_t> work_;            // its copy that elimination consumes
  std::vector<std::uint64_t> elim_cliques_;    // vars × words: clique created by each elimination
  std::vector<std::uint64_t> alive_;
  std::vector<int> elimination_order_;
  std::vector<int> maximal_;                   // indices (in elimination order) of maximal cliques
  // The order being tried; swapped into the three above when it is the best so far.
  std::vector<std::uint64_t> candidate_cliques_;
  std::vector<int> candidate_order_;
  std::vector<int> candidate_maximal_;
  EliminationRule rule_ = EliminationRule::min_fill;
  std::uint64_t total_clique_entries_ = 0;
  [[nodiscard]] bool eliminate(EliminationRule rule, std::uint64_t max_clique_entries);  // into candidate_*
  std::uint64_t find_maximal_cliques();        // candidate_maximal_; returns their total entries
  std::vector<int> key_;                       // Prim: best separator size to the tree, or -1
  std::vector<int> key_parent_;
  std::vector<int> new_index_;                 // maximal clique → position in the tree order
  std::vector<char> in_tree_;
  std::vector<int> clique_begin_;
  std::vector<int> clique_vars_;

 public:
  int clique_begin(int c) const { return clique_begin_[c]; }  // offset of clique c's variables

 private:
  std::vector<int> parent_;
  std::vector<std::uint64_t> clique_entries_;
};

class JunctionTree final : public SingleScanSolver {
 public:
  using Options = JtOptions;
  static constexpr std::string_view kName = "jt";
  static constexpr std::string_view kSummary =
      "junction tree on the pairwise formulation eqs (37)-(39), thresholded weights, memory budget";

  explicit JunctionTree(const Options& options) : options_(options) {}
  void solve(const SingleScanProblem& problem, MarginalTable& marginals, SolveReport& report) override;

  // Diagnostics of the last solve (for tests): log of the partition function Σ_a Π_i ψ_i(a_i)
  // of the thresholded problem in the ψ_i(0) = 1 normalisation (NaN if skipped), and the
  // largest per-cluster table size in doubles (cliques + separators + scratch).
  // Also the largest per-cluster total of clique states alone (libDAI's maxstates measure).
  double log_partition() const { return log_partition_; }
  std::uint64_t largest_table_entries() const { return largest_table_entries_; }
  std::uint64_t largest_clique_states() const { return largest_clique_states_; }
  const JunctionTreeBuilder& builder() const { return builder_; }  // of the last cluster built

 private:
  enum class Weights { none, product, log_sum };

  [[nodiscard]] bool solve_cluster(int first, int last, MarginalTable& marginals);  // false = over budget
  void solve_single(int target, MarginalTable& marginals);
  void load_cluster(int first, int last);  // states, potentials and the graph of eq (39)
  [[nodiscard]] bool layout_tables();                    // false = over budget or allocation failed
  void setup_pass(int clique, bool collect);
  void collect(int clique);
  void collect_log_domain(int clique);
  void distribute(int clique);
  template <Weights kWeights, class Leaf>
  void walk(int level, std::size_t index, const std::size_t* in, double weight, Leaf& leaf);

  Options options_;
  AssociationGraph graph_;
  JunctionTreeBuilder builder_;
  double row_threshold_scalar_ = 0.0;
  bool per_row_threshold_ = false;
  std::vector<double> row_threshold_;      // reading 2: τ (1 + Σ_j ψ_ij)
  double log_partition_ = std::numeric_limits<double>::quiet_NaN();
  std::uint64_t budget_entries_ = 0;
  std::uint64_t largest_table_entries_ = 0;
  std::uint64_t largest_clique_states_ = 0;

  // Current cluster: local variable v = target cluster_target_[v]; its states
  // [state_begin_[v], state_begin_[v+1]) in state_measurement_ (−1 for state 0 = missed) and
  // state_potential_ (ψ scaled by 1/max(1, max_j ψ), so the largest is ≤ 1).
  std::vector<int> cluster_target_;
  std::vector<int> state_variable_;          // per state: its local variable
  std::vector<int> state_begin_;
  std::vector<int> state_measurement_;
  std::vector<double> state_potential_;
  std::vector<double> state_log_potential_;  // filled lazily for the log-domain fallback
  bool have_log_potential_ = false;
  bool underflow_lost_mass_ = false;  // a distribute pass met a separator state emptied by underflow
  std::vector<int> domain_;
  std::vector<int> measurement_head_;        // per measurement: last state using it, or −1
  std::vector<int> state_next_;              // linked list of states per measurement
  std::vector<int> touched_measurements_;
  std::vector<char> used_;                   // per measurement: taken in the current walk
  std::vector<double> ones_;                 // potential of a level that does not own its variable
  std::vector<double> zeros_;                // (the same in the log domain)
  double log_mantissa_ = 1.0;                // log Z accumulated as mantissa · 2^exponent + extra
  long log_exponent_ = 0;
  double log_extra_ = 0.0;
  void log_multiply(double factor);

  // Tables of the current cluster (offsets into pool_).
  std::vector<std::size_t> clique_offset_;
  std::vector<int> level_base_;              // per clique: offset of its levels
  std::vector<std::size_t> separator_offset_;  // per non-root clique: separator with its parent
  std::vector<std::size_t> separator_size_;
  std::vector<std::size_t> level_stride_all_;  // per clique level: stride in the clique table
  std::vector<std::size_t> child_side_stride_;   // per clique level: stride in its parent separator (0 if absent)
  std::vector<int> parent_side_begin_;           // per non-root clique: offset into parent_side_stride_
  std::vector<std::size_t> parent_side_stride_;  // per parent level: stride in the child's separator
  std::vector<int> children_begin_;
  std::vector<int> children_;
  std::vector<int> owner_clique_;            // per variable: smallest clique containing it
  std::vector<int> owner_level_;             // its level in that clique
  std::vector<int> owned_begin_;             // per clique: variables it owns
  std::vector<int> owned_var_;
  std::vector<int> cursor_;                  // scratch for filling CSR lists
  std::size_t scratch_offset_ = 0;
  std::unique_ptr<double[]> pool_;
  std::size_t pool_capacity_ = 0;
  std::vector<double> marginal_;             // per state

  // The current pass: per level of the clique walked.
  int channels_ = 0;
  std::vector<int> level_domain_;
  std::vector<const int*> level_measurement_;
  std::vector<const double*> level_potential_;
  std::vector<std::size_t> level_stride_;
  std::vector<std::size_t> level_channel_stride_;  // levels × channels
  std::vector<std::size_t> channel_index_;         // (levels + 1) × channels
  std::vector<int> state_;                         // chosen state per level
  std::vector<double*> channel_table_;
};

}  // namespace dabench
