#pragma once
// Correlation decay for marginal association probabilities: S. Oh, "A distributed deterministic
// approximation algorithm for data association", DCOSS 2011 (ref [24] of Williams & Lau 2014),
// in the form Williams & Lau give it in Section IV-B of bp-marginal-association, eqs (40)-(41):
//
//   Φ(T, M, i, t) = 1 / (1 + Σ_{j∈M} ψ_i(j) Φ(T−{i}, M, j, t−1))        target i ∈ T     (40)
//   Φ(T, M, j, t) = 1 / (1 + Σ_{i∈T} ψ_i(j) Φ(T, M−{j}, i, t−1))        measurement j ∈ M (41)
//   Φ(·, ·, ·, 0) = 1
//
// T and M are the nodes still present: the recursion runs over the self-avoiding walks of the
// gating graph (Bayati et al.'s computation tree for the monomer-dimer model, ref [60]), and
// untruncated Φ(T, M, v) is the exact probability that v is unassigned within T ∪ M.
// Marginals of target i, with s_i = 1 + Σ_j ψ_i(j) Φ_j and Φ_j = Φ(T−{i}, M, j, t−1):
//   p(a_i = 0) = 1/s_i (= Φ_i by 40),   p(a_i = j) = ψ_i(j) Φ_j / s_i,
// so every row sums to one to rounding, at every depth.
//
// Depth t counts recursion levels, one node (alternately a target and a measurement) per level:
// depth 1 is PDA, and depth ≥ n + m is exact. For t ≥ |G| − 1 (G = nodes still present) the
// recursion does the same operations for every such t, so t is clamped to |G| − 1 (bit-identical).
// Sums run over gated pairs only (ψ > 0, ψ = w_ij/(w_i0 w_0j)), so each cluster of the gating
// graph (AssociationGraph) is solved on its own, with local nodes: targets 0..n_c−1, then
// measurements.
//
// Memoisation (option memo, default on): Φ depends only on (set of nodes removed so far, node,
// clamped t), so a table keyed on exactly that is sound and memo on/off results are bit-identical.
// Keys: one 64-bit word for clusters of up to 64 nodes, else ⌈nodes/64⌉ words. Entries are kept
// only where reuse is possible: at least 3 nodes removed and remaining depth ≥ 2. The table is
// cleared per cluster by a generation stamp, grows by doubling, and stops accepting entries at
// memo_entries.
//
// Work limit: `budget` bounds the evaluations of (40)/(41) with t ≥ 1 per problem (roots and memo
// hits count, the constant leaves Φ(·,·,·,0) = 1 do not); past it the solve stops and reports
// skipped:budget.
// Background and our readings: docs/algorithms/single-scan.md, "Correlation decay".
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "algorithms/single_scan/association_graph.hpp"
#include "harness/core/params.hpp"
#include "harness/single_scan/solver.hpp"

namespace dabench {

struct CorrelationDecayOptions {
  int depth = 5;                          // t: recursion levels of (40)-(41) (paper: 3, 5, 7)
  std::int64_t budget = 100000000;        // evaluations of (40)/(41) per problem (skipped:budget above)
  bool memo = true;                       // memoise Φ on (removed set, node, t); same results
  std::int64_t memo_entries = 1 << 20;    // memo cap in entries (table ≤ 2 slots/entry, 32 B/slot at ≤64 nodes)

  void bind(ParamList& params) {
    params.add("depth", depth, "t: recursion depth of eqs (40)-(41); 1 = PDA, >= nodes-1 = exact");
    params.add("budget", budget, "work limit in recursion evaluations per problem (skipped:budget above)");
    params.add("memo", memo, "memoise Phi on (removed set, node, depth); results are identical");
    params.add("memo_entries", memo_entries, "memo table capacity in entries");
  }
  std::string validate() const;
};

class CorrelationDecay final : public SingleScanSolver {
 public:
  using Options = CorrelationDecayOptions;
  static constexpr std::string_view kName = "cd";
  static constexpr std::string_view kSummary =
      "correlation decay (Oh 2011): truncated self-avoiding recursion eqs (40)-(41)";

  explicit CorrelationDecay(const Options& options) : options_(options) {}
  void solve(const SingleScanProblem& problem, MarginalTable& marginals, SolveReport& report) override;

  // Diagnostics of the last solve (for tests and benchmarks): evaluations counted against the
  // budget, and memo lookups that hit.
  std::int64_t evaluations() const { return calls_; }
  std::int64_t memo_hits() const { return memo_hits_; }

 private:
  // Open-addressing hash table (linear probing) from (removed-set words, tag = node·2³² + t)
  // to Φ. Storage persists across solves; reset() invalidates every entry in O(1).
  class Memo {
   public:
    void reset(int words, std::int64_t max_entries);
    const double* find(const std::uint64_t* key, std::uint64_t tag, std::uint64_t hash) const;
    void insert(const std::uint64_t* key, std::uint64_t tag, std::uint64_t hash, double value);

   private:
    void grow();
    bool same_key(std::size_t slot, const std::uint64_t* key, std::uint64_t tag) const;
    struct Slot {  // one cache line holds two slots; a probe touches one
      std::uint64_t key0 = 0;         // first word of the removed set
      std::uint64_t tag = 0;
      double value = 0.0;
      std::uint32_t stamp = 0;        // == generation_ ⇒ the slot holds a live entry
    };
    std::vector<Slot> slots_;
    std::vector<std::uint64_t> extra_;  // words_ − 1 further key words per slot (wide keys)
    std::uint32_t generation_ = 0;
    std::size_t mask_ = 0;              // capacity − 1 (capacity a power of two, or 0)
    std::size_t size_ = 0;
    std::size_t max_entries_ = 0;
    int words_ = 1;
  };

  void build_cluster(int first, int last);
  template <bool kWide>
  void solve_cluster(MarginalTable& marginals);
  template <bool kWide>
  double phi(int node, int t, int level);
  template <bool kWide>
  double phi_one(int node) const;

  Options options_;
  AssociationGraph graph_;
  // The current cluster: local nodes 0..targets−1 are its targets (global index in
  // cluster_target_), then its measurements; adjacency in CSR with both directions stored.
  int nodes_ = 0;
  int cluster_targets_ = 0;
  std::vector<int> cluster_target_;      // local target → global target
  std::vector<int> cluster_measurement_; // local measurement (minus cluster_targets_) → global
  std::vector<int> local_of_measurement_;  // global measurement → local node, or −1
  std::vector<int> adj_begin_;
  std::vector<int> adj_node_;
  std::vector<double> adj_weight_;
  std::vector<int> fill_;                // CSR fill cursors
  std::vector<double> root_terms_;       // ψ_i(j) Φ_j of the current root
  // The removed set (the walk from the root): one word for ≤ 64 nodes, else removed_words_.
  std::uint64_t removed_ = 0;
  std::vector<std::uint64_t> removed_words_;
  int words_ = 1;
  bool use_memo_ = false;
  Memo memo_;
  std::int64_t calls_ = 0;
  std::int64_t memo_hits_ = 0;
};

}  // namespace dabench
