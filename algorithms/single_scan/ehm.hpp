#pragma once
// Efficient hypothesis management: exact marginal association probabilities p(a_i = j) of the
// single-scan model of Williams & Lau 2014 (bp-marginal-association, eqs 9-13), computed on a
// net of partial hypotheses that exploits mutual exclusion (EHM: Maskell, Briers & Wright, Proc.
// SPIE 5428, 2004; EHM2: Horridge & Maskell, FUSION 2006). The marginals equal those of eq (12).
//
// Method (per cluster of the gating graph; clusters are independent, eq 9 factorises):
//  1. Targets are put in an order (`order`) and a tree of tracks is built on it: with
//     `tree = false` the path of the order (EHM); with `tree = true` (EHM2), built from the last
//     target back, target t becomes the parent of every subtree so far that shares a gated
//     measurement with t.
//  2. D(t) = measurements gated by the subtree of t; key space K(t) = D(t) ∩ (measurements gated
//     by ancestors of t). A node of layer t is a set S ⊆ K(t) of measurements used above t,
//     stored as a bitset over K(t) (std::uint64_t words). Only measurements gated by ≥ 2 targets
//     get bits; the others fold with the miss into choice 0, of weight 1 + Σ_excl ψ_t(j).
//  3. Backward: β_t(S) = Σ_{j ∈ {0} ∪ gate(t), j ∉ S} ψ_t(j) Π_{c child of t} β_c((S ∪ {j}) ∩ K(c))
//     Forward: α_root(∅) = 1, α_c(S') = Σ_{S, j → S'} α_t(S) ψ_t(j) Π_{c' ≠ c} β_c'(…). Then
//     p(a_t = j) ∝ Σ_{S ∈ layer t} α_t(S) ψ_t(j) Π_c β_c((S ∪ {j}) ∩ K(c)): eq (12), every row
//     summing to Z.
//  4. ψ_t(j) = w_tj / (w_t0 w_0j) (SingleScanProblem::normalized_weight); each row is divided by
//     max(1, max_j ψ_t(j)) and each layer of α and β by its largest entry (logs kept:
//     stats().log_partition = log Z of the normalised problem). Each layer carries a bound on what
//     underflow can have taken from it; a row whose sum is not 1e12 times its bound is refused
//     (skipped:numerical), never written.
// Options: `order` 0 = auto (the cheapest candidate by an estimate of its net), 1 = greedy minimum
// frontier, 2 = Cuthill–McKee BFS, 3 = input order; `tree` as in 1; `threshold` zeroes normalised
// weights below it first (as exact:threshold). A target that must be detected (w_i0 = 0) has a
// miss of weight 0; a problem no event can satisfy is skipped:infeasible before any net.
// Work limit: net_bound (ehm_bound.cpp) bounds every layer from the tree and the key spaces before
// anything is built; a solve whose bound passes `max_nodes` nodes (summed over its clusters) or a
// net whose edges pass 16 × max_nodes is refused at once as skipped:work_estimate, so no solve
// spends its budget and then gives up. A key space over 512 bits is skipped:key_width.
// Cost and memory: a layer holds up to 2^|K(t)| nodes; about 16 bytes plus 8 per key word per
// node, plus 4 per (node, choice, child) edge. Layers with |K| ≤ 22 are indexed by a
// direct-address table (16 MB), wider ones by a generation-stamped hash table; storage is flat and
// reused, and results are bit-identical across repeats.
// Background and our readings: docs/algorithms/single-scan.md, "EHM".
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "algorithms/single_scan/association_graph.hpp"
#include "harness/core/params.hpp"
#include "harness/single_scan/solver.hpp"

namespace dabench {

struct EhmOptions {
  double threshold = 0.0;              // weights ψ_i(j) below this are set to zero first
  std::int64_t max_nodes = 50000000;   // work limit: net nodes per solve (bounded above it: skipped:work_estimate)
  int order = 0;                       // target order: 0 auto, 1 greedy min-frontier, 2 Cuthill–McKee BFS, 3 input
  bool tree = true;                    // true: EHM2 tree of tracks; false: EHM net over the order (a path)

  void bind(ParamList& params) {
    params.add("threshold", threshold, "weights below this are treated as zero");
    params.add("max_nodes", max_nodes, "work limit in net nodes per solve (skipped:work_estimate when its bound is above)");
    params.add("order", order, "target order: 0 auto (cheapest of 1-3), 1 greedy min-frontier, 2 Cuthill-McKee BFS, 3 input");
    params.add("tree", tree, "1: EHM2 tree of tracks; 0: plain EHM net over the order");
  }
  std::string validate() const;
};

// Diagnostics of the last solve (for tests and benchmarks).
struct EhmStats {
  std::int64_t nodes = 0;     // net nodes over all clusters
  std::int64_t edges = 0;     // stored (node, choice, child) links
  int max_layer_width = 0;    // largest number of nodes in one layer
  int max_key_bits = 0;       // largest key space |K(t)|
  int largest_cluster = 0;    // targets in the largest cluster
  int clusters = 0;
  double node_bound = 0.0;     // bounds on the nodes and edges (net_bound), summed over the
  double edge_bound = 0.0;     //   clusters bounded (all of them, unless one was refused first)
  double log_partition = 0.0; // log Z of the normalised problem (ψ_i(0) = 1 form)
};

class Ehm final : public SingleScanSolver {
 public:
  using Options = EhmOptions;
  static constexpr std::string_view kName = "ehm";
  static constexpr std::string_view kSummary =
      "exact marginals by efficient hypothesis management (EHM/EHM2 net over measurement sets)";

  explicit Ehm(const Options& options) : options_(options) {}
  void solve(const SingleScanProblem& problem, MarginalTable& marginals, SolveReport& report) override;
  bool accepts_must_detect() const override { return true; }
  const EhmStats& stats() const { return stats_; }

 private:
  struct Slot {
    std::uint32_t stamp;
    std::int32_t node;
  };

  // A cluster of several targets: prepare_cluster (gate tables, order, tree, net tables), then
  // add_to_bound, then solve_cluster. Each returns "" or the reason the solve is refused.
  const char* prepare_cluster(int first, int last, bool saved_order);
  const char* add_to_bound();
  const char* solve_cluster(MarginalTable& marginals);
  void solve_single(int target, MarginalTable& marginals);
  // The target order and its estimated net (ehm_order.cpp).
  void choose_order();
  void order_greedy(const std::vector<int>& prefix);  // `prefix` first, then the greedy rule
  void order_bfs();
  double order_cost(const std::vector<int>& order);
  // The tree of tracks over the order and the net's per-position tables (ehm.cpp).
  void build_tree();
  int build_tables();  // returns the largest key space
  // Upper bounds on the current cluster's net from its tree and key spaces (ehm_bound.cpp).
  struct NetBound {
    double nodes = 0.0;
    double edges = 0.0;
  };
  NetBound net_bound();
  bool surely_within_caps() const;  // a coarse bound on every net of the problem is within the caps
  // The net of the current cluster (ehm_net.cpp): run_net = build_net, backward_pass, forward_pass.
  // Returns "" or "numerical".
  template <int W>
  [[nodiscard]] const char* run_net(MarginalTable& marginals);
  template <int W>
  void build_net();
  template <int W>
  void build_child_direct(int p, int ci);
  template <int W>
  void build_child_hashed(int p, int ci);
  template <int W>
  double backward_pass();
  template <int W>
  [[nodiscard]] bool forward_pass(MarginalTable& marginals);  // false: underflow (see write_row)
  template <int W>
  void forward_layer(int p);
  [[nodiscard]] bool write_row(int p, MarginalTable& marginals);
  double layer_weight_bound(int p) const;  // max(1, largest choice weight of p's target)
  template <int W>
  std::int32_t find_or_insert(const std::uint64_t* key);
  template <int W>
  void grow_table(std::int32_t layer_first);

  static constexpr double kEdgesPerNode = 16.0;   // a net may store at most this × max_nodes edges
  static constexpr int kMaxKeyWords = 8;          // key spaces up to 512 shared measurements

  Options options_;
  EhmStats stats_;
  AssociationGraph graph_;

  // Cluster, indexed by local target li (cluster order) and local shared measurement id.
  int cluster_size_ = 0;
  int shared_ = 0;
  std::vector<int> targets_;          // li → global target
  std::vector<int> local_id_;         // global measurement → local shared id, or -1
  std::vector<int> gate_begin_;       // li → shared gate entries [gate_begin_[li], gate_begin_[li+1])
  std::vector<int> gate_meas_;        //   local shared id
  std::vector<int> gate_edge_;        //   graph edge (for the output column)
  std::vector<double> gate_weight_;   //   ψ / row scale
  std::vector<double> stay_weight_;   // li → (1 + Σ_exclusive ψ) / row scale; without the 1 when it must be detected
  std::vector<char> must_detect_;     // per target of the problem: no missed detection (w_i0 = 0)
  std::vector<double> exclusive_sum_; // li → Σ_exclusive ψ (unscaled)
  std::vector<double> row_scale_;     // li → max(1, max_j ψ)
  std::vector<int> meas_begin_;       // local shared id → gating targets (li, ascending)
  std::vector<int> meas_targets_;

  // Order and tree, indexed by position p (0 = root).
  std::vector<int> order_;            // p → li
  std::vector<int> saved_order_;      // the bounding pass's orders, at each cluster's target range
  int cluster_bits_ = 0;              // the current cluster's widest key space
  std::vector<int> best_order_, prefix_targets_;
  int bfs_start_ = 0;
  std::vector<int> position_;         // li → p
  std::vector<int> parent_;           // p → parent position or -1
  std::vector<int> child_begin_;      // p → children [child_begin_[p], child_begin_[p+1]) in child_list_
  std::vector<int> child_list_;
  std::vector<int> tin_, tout_;       // preorder interval of each position's subtree

  // Per-position tables of the net.
  std::vector<int> key_begin_, key_size_;  // K(p) = key_list_[key_begin_[p] ..+ key_size_[p]]
  std::vector<int> key_list_;
  std::vector<int> choice_begin_;     // p → choices (0 = miss/exclusive, then shared gate entries)
  std::vector<double> choice_weight_;
  std::vector<int> choice_test_;      // bit of the choice's measurement in K(p), or -1
  std::vector<int> set_begin_;        // p → [child slot][choice] bit in K(child), or -1
  std::vector<int> set_bit_;
  std::vector<int> remap_begin_;      // p → [child slot][bit of K(p)] bit in K(child), or -1
  std::vector<int> remap_bit_;
  std::vector<double> layer_bound_;   // p → upper bound on its layer's nodes (net_bound)

  // Net storage.
  std::vector<std::int64_t> layer_begin_;  // p → first node id (size positions + 1)
  std::vector<std::int64_t> edge_begin_;   // p → first edge
  std::vector<std::uint64_t> keys_;
  std::vector<double> alpha_, beta_;
  // Per position: a bound on the absolute error that underflow can have put in each stored
  // (scaled) α and β of the layer (see backward_pass).
  std::vector<double> alpha_error_, beta_error_;
  std::vector<std::int32_t> edges_;
  std::vector<double> row_accumulator_;    // per choice of the current position
  std::vector<double> child_beta_, prefix_;  // per child slot
  std::vector<std::int32_t> direct_;       // direct-address index of small key spaces, -1 = none
  std::vector<Slot> slots_;
  std::uint32_t generation_ = 0;
  std::uint64_t mask_ = 0;
  std::int64_t nodes_total_ = 0;

  // Scratch.
  std::vector<int> mark_, mark2_, count_, queue_, degree_, private_, uf_;
  std::vector<char> touched_, done_;
};

}  // namespace dabench
