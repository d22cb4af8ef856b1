#pragma once
// k-best JPDA: marginal association probabilities from the k most probable joint association
// events of each cluster, found by Murty's ranked assignment (algorithms/assignment/murty.hpp) on
// costs −log ψ_ij (a missed detection costs −log 1 = 0; an ungated pair is forbidden):
//   p(a_i = j) ≈ Σ_{e kept, e_i = j} w(e) / Σ_{e kept} w(e),   w(e) = Π_i ψ_i(e_i)  (eq 12 on the kept events).
// As MATLAB's trackerJPDA limits the joint events of a cluster to the k best (its
// MaxNumEvents); exact when k covers every event of every cluster (clusters are independent:
// eq 9 factorises over them, so k per cluster loses nothing that k over the product would keep).
//
// Report: iterations = the events used in all; converged = 1 when every cluster had fewer than k
// events (all of them were used, so the marginals are exact); captured_mass = Π over clusters of
// the kept events' share of the cluster's partition function Z, with Z from the permanent
// (permanent.hpp) where the cluster fits in `mass_memory_mb` (NaN otherwise; `dabench solve
// --format json` and the Python report show it).
//
// Weights are the normalised ψ_ij = w_ij / (w_i0 w_0j); event weights are formed relative to the
// best event's, exp(−(cost − best cost)), so they cannot overflow. Cost: per cluster O(k · R)
// assignment solves of O(R² (C + R)) (Murty, Miller–Stone–Cox partitioning).
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "algorithms/assignment/murty.hpp"
#include "algorithms/single_scan/association_graph.hpp"
#include "algorithms/single_scan/permanent.hpp"
#include "harness/core/params.hpp"
#include "harness/single_scan/solver.hpp"

namespace dabench {

struct KBestJpdaOptions {
  int k = 100;                        // events per cluster
  std::int64_t mass_memory_mb = 64;   // the permanent that measures the captured mass, per cluster
  void bind(ParamList& params) {
    params.add("k", k, "joint events kept per cluster (Murty's k best)");
    params.add("mass_memory_mb", mass_memory_mb,
               "memory for the permanent that gives the captured mass, per cluster (0 = never computed)");
  }
  std::string validate() const;
};

class KBestJpda final : public SingleScanSolver {
 public:
  using Options = KBestJpdaOptions;
  static constexpr std::string_view kName = "kbest-jpda";
  static constexpr std::string_view kSummary =
      "k-best JPDA: marginals from the k most probable joint events per cluster (Murty), as MATLAB trackerJPDA";

  explicit KBestJpda(const Options& options) : options_(options) {}
  void solve(const SingleScanProblem& problem, MarginalTable& marginals, SolveReport& report) override;

 private:
  Options options_;
  AssociationGraph graph_;
  MurtyRanking murty_;
  RankedAssignments ranked_;
  SubsetPermanent permanent_;
  std::vector<int> cluster_measurements_;
  std::vector<int> local_measurement_;
  std::vector<double> cost_, miss_cost_, dense_;
};

}  // namespace dabench
