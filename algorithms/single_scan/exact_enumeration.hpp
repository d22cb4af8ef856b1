#pragma once
// Exact marginal association probabilities, eqs (12)-(13) of Williams & Lau 2014, by
// enumerating every feasible association event (each target takes one gated measurement or
// none, no measurement used twice). The joint of eq (9) factorises over the connected
// components of the gating graph, so each cluster is enumerated on its own; zero (gated-out)
// weights are never visited. Each target's row is scaled by its largest weight (which leaves
// the marginals unchanged) so products stay in range.
//
// This is the test oracle and the reference for experiments that fit: the cost is the number
// of feasible events, exponential in the cluster size. Past `max_events` the solve is refused
// with status skipped:work_limit instead of running for hours, and where the scaled products
// underflow (weights spanning more than double's range within one event) with
// skipped:numerical rather than marginals computed from a partition function of 0.
// A target that must be detected (a zero missed-detection weight, Pd = 1) has no missed branch;
// a problem where no event gives every such target a measurement is skipped:infeasible.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "algorithms/single_scan/association_graph.hpp"
#include "harness/core/params.hpp"
#include "harness/single_scan/solver.hpp"

namespace dabench {

struct ExactOptions {
  double threshold = 0.0;               // weights ψ_i(j) below this are set to zero first
  std::int64_t max_events = 100000000;  // work limit: feasible events enumerated per problem

  void bind(ParamList& params) {
    params.add("threshold", threshold, "weights below this are treated as zero");
    params.add("max_events", max_events, "work limit in association events (skipped:work_limit above)");
  }
  std::string validate() const;
};

class ExactEnumeration final : public SingleScanSolver {
 public:
  using Options = ExactOptions;
  static constexpr std::string_view kName = "exact";
  static constexpr std::string_view kSummary =
      "exact marginals by enumerating feasible events per cluster (test oracle)";

  explicit ExactEnumeration(const Options& options) : options_(options) {}
  void solve(const SingleScanProblem& problem, MarginalTable& marginals, SolveReport& report) override;
  bool accepts_must_detect() const override { return true; }

 private:
  // Empty, or why the cluster was refused: "work_limit", or "numerical" where underflow could
  // have lost more than 1e-12 of the partition function.
  [[nodiscard]] std::string_view enumerate_cluster(int first, int last, MarginalTable& marginals);
  double descend(int depth, double prefix);

  Options options_;
  AssociationGraph graph_;
  std::vector<double> row_scale_;     // 1 / max(1, max_j ψ_i(j)) per target
  std::vector<char> must_detect_;     // per target: no missed branch
  std::vector<int> order_;            // targets of the current cluster
  std::vector<char> used_;            // per measurement
  std::vector<double> accumulator_;   // per depth: summed event weight per choice, [0] = missed,
  std::vector<int> accumulator_row_;  //   [k+1] = k-th edge; accumulator_row_ = offset per depth
  std::int64_t events_ = 0;
};

}  // namespace dabench
