#pragma once
// Exact marginal association probabilities from the permanent of the cluster's weight matrix.
//
// The partition function of a cluster of eq (9) (bp-marginal-association; ψ_i(0) = 1) is the
// permanent of the n × (m + n) matrix [ψ | I]: Z = Σ over events Π_i ψ_i(a_i) = per[ψ | I], and
// p(a_i = j) = ψ_ij per[ψ | I]_(i,j) / Z with the row and the column removed (the minors are the
// derivatives of the permanent). The permanent is computed over the subsets of the smaller side
// of the cluster, q = min(n, m) elements, processing the p = max(n, m) elements of the other side
// one at a time — each takes nothing (its missed detection, or its clutter, weight 1) or one
// element of the subset side not taken yet:
//   F_k(S) = F_{k−1}(S) + Σ_{l ∈ S} F_{k−1}(S ∖ l) w(k, l),   F_0 = [S = ∅],   Z = Σ_S F_p(S),
// and backwards B_{k−1}(S) = B_k(S) + Σ_{l ∉ S} w(k, l) B_k(S ∪ l), B_p = 1, so that
//   p(k takes l) = Σ_{S ∌ l} F_{k−1}(S) w(k, l) B_k(S ∪ l) / Z,   p(k takes nothing) = Σ_S F_{k−1}(S) B_k(S) / Z,
//   p(l taken by nothing) = Σ_{S ∌ l} F_p(S) / Z.
// This is the subset recursion behind Ryser's formula (both cost O(2^q) terms per element of
// the other side: here O(p · 2^q · gated pairs per element)) without its inclusion–exclusion
// signs: every term is positive, so the result is exact to rounding. Ryser's (and Glynn's)
// alternating sums cancel catastrophically on these matrices: on [ψ | I] completed to a square
// matrix with rows of ones, a 6 × 10 cluster of exponential weights already loses 8 digits
// against enumeration (relative error 5.7e-9; 3 × 4: 2.6e-14), far from the 1e-12 the exact
// methods are held to. Compared with EHM (ehm.hpp), whose net is keyed by the measurements still
// relevant to later targets, the permanent's cost depends on q alone, not on the cluster's
// shape: it wins on small dense clusters where EHM's key spaces are wide (every target gating
// every measurement), and loses on wide sparse clusters (a long grid) where q is large but the
// relevant sets stay small.
//
// Numerics: every layer of F and B is divided by its largest entry and its log kept, so no
// product over- or underflows in range; weights are the normalised ψ_ij = w_ij / (w_i0 w_0j). A
// problem whose row or column sums overflow is refused (skipped:numerical), and so is a cluster
// where underflow in the scaled layers may have moved a probability by more than 1e-12 (a bound
// from the largest weight and the largest factor a scaled entry is multiplied by; exact methods
// agree to 1e-12 or refuse, as enumeration and EHM do).
// Work limit: a cluster needs (p + 3) · 2^q doubles; above `memory_mb` (or q > 30) the solve
// reports skipped:memory before allocating.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "algorithms/single_scan/association_graph.hpp"
#include "harness/core/params.hpp"
#include "harness/single_scan/solver.hpp"

namespace dabench {

// The subset recursion on one cluster's dense weights (targets × measurements, 0 = not gated).
class SubsetPermanent {
 public:
  // Whether a targets × measurements cluster fits in `memory_mb`.
  static bool fits(int targets, int measurements, std::int64_t memory_mb);
  // log Z of the cluster (weights row-major, targets × measurements).
  double log_partition(const double* weights, int targets, int measurements);
  // The cluster's marginals, targets × (measurements + 1) row-major, column 0 = missed detection;
  // false where underflow may have moved a probability by more than 1e-12 (then `out` is void).
  bool marginals(const double* weights, int targets, int measurements, std::vector<double>& out);

 private:
  // Sets the sides and runs the forward pass; returns log Z.
  double forward(const double* weights, int targets, int measurements);
  double weight(int k, int l) const;  // w(k, l): processed element k, subset element l

  const double* weights_ = nullptr;
  int targets_ = 0, measurements_ = 0;
  bool targets_are_subsets_ = false;  // the subset side is the targets (n ≤ m)
  int p_ = 0, q_ = 0;
  std::vector<double> forward_;       // (p + 1) layers of 2^q
  std::vector<double> log_scale_;     // per forward layer
  std::vector<double> backward_, next_backward_;
  std::vector<std::vector<int>> gated_;  // per processed element: its subset elements of w > 0
};

struct PermanentOptions {
  std::int64_t memory_mb = 1024;  // per cluster: (p + 3) · 2^q doubles
  void bind(ParamList& params) {
    params.add("memory_mb", memory_mb, "memory per cluster in MiB: (max(n,m) + 3) * 2^min(n,m) doubles (skipped:memory above)");
  }
  std::string validate() const;
};

class PermanentMarginals final : public SingleScanSolver {
 public:
  using Options = PermanentOptions;
  static constexpr std::string_view kName = "permanent";
  static constexpr std::string_view kSummary =
      "exact marginals from the permanent of [psi | I]: positive subset recursion over the smaller side, per cluster";

  explicit PermanentMarginals(const Options& options) : options_(options) {}
  void solve(const SingleScanProblem& problem, MarginalTable& marginals, SolveReport& report) override;

 private:
  Options options_;
  AssociationGraph graph_;
  SubsetPermanent permanent_;
  std::vector<int> cluster_measurements_;
  std::vector<int> local_measurement_;  // measurement → index in its cluster (−1 elsewhere)
  std::vector<double> dense_;
  std::vector<double> cluster_marginals_;
};

}  // namespace dabench
