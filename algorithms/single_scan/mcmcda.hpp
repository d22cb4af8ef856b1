#pragma once
// Single-scan Markov chain Monte Carlo data association (MCMCDA): S. Oh, S. Russell and
// S. Sastry, "Markov chain Monte Carlo data association for multi-target tracking", IEEE
// Trans. Automatic Control 54(3), 2009, single-scan algorithm — Jerrum & Sinclair's Metropolis
// chain over the matchings of the gating graph ("Approximating the permanent", SIAM J. Comput.
// 18(6), 1989). It estimates the marginals p(a_i = j) of Williams & Lau 2014
// (bp-marginal-association), eqs (9), (12), which compare it with BP in Sec. V (Fig. 6).
//
// State: a matching ω of the gating graph G = (targets ∪ measurements, E = {(i, j): ψ_i(j) > 0}),
// i.e. a feasible event of eq (9) (unmatched target = missed, unmatched measurement = false
// alarm). Target distribution π(ω) ∝ Π_{(i,j)∈ω} ψ_i(j), with side weights normalised as in
// SingleScanProblem::normalized_weight (ψ_i(j) = w_ij / (w_i0 w_0j)), which is eq (9).
// One step:
//   with probability 1/2: ω' = ω (lazy);
//   else pick e = (i, j) uniformly from E and propose
//     e ∈ ω                                 → deletion  ω' = ω − e
//     i and j both unmatched                → addition  ω' = ω + e
//     i matched to j' ≠ j, j unmatched      → switch    ω' = ω + e − (i, j')
//     j matched to i' ≠ i, i unmatched      → switch    ω' = ω + e − (i', j)
//     both matched elsewhere                → ω' = ω;
//   accept ω' with probability min(1, π(ω')/π(ω)) (else ω' = ω).
// The proposal is symmetric, so π is stationary; the lazy half makes the chain aperiodic.
//
// Initial state: the MAP event (map_association.hpp), as Williams & Lau did, so `burnin`
// defaults to 0. Marginals = visit frequencies of X_{B+1}, ..., X_{B+N} (B = burnin, N = samples),
// rejected and lazy steps included, counted as time spent per (target, state): a step that
// changes nothing costs O(1). One chain over the whole graph. Randomness: RandomStream(
// stream_seed(trial_key.seed, seed), trial_key.point, trial_key.trial), so output is a function
// of (problem, trial, options) and different `seed` options give independent chains. Each step
// draws one 64-bit word (bit 63: lazy; low 32 bits: the edge, by Lemire's multiply-shift with
// rejection); a 53-bit acceptance uniform is drawn only when π(ω') < π(ω), tested as
// u·π_old < π_new. No work limit: O(1) per step after the set-up (gating graph, MAP event).
// Background and our readings: docs/algorithms/single-scan.md, "MCMCDA".
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "algorithms/single_scan/association_graph.hpp"
#include "algorithms/single_scan/map_association.hpp"
#include "harness/core/params.hpp"
#include "harness/core/random_stream.hpp"
#include "harness/single_scan/solver.hpp"

namespace dabench {

struct McmcdaOptions {
  std::int64_t samples = 100000;  // N: chain steps counted after burn-in (paper: 1e5, 1e6, 1e7)
  std::int64_t burnin = 0;        // B: steps discarded first (0: the chain starts at the MAP event)
  std::int64_t seed = 0;          // S: stream selector; different values give independent chains

  void bind(ParamList& params) {
    params.add("samples", samples, "N: chain steps counted (visit frequencies), lazy/rejected steps included");
    params.add("burnin", burnin, "B: steps discarded before counting (chain starts at the MAP event)");
    params.add("seed", seed, "stream selector: another value gives an independent chain on the same trial");
  }
  std::string validate() const;
};

// The chain itself, exposed for tests and benchmarks. Steps are numbered 1, 2, ...; step t
// produces state X_t, and counting covers X_{first}, X_{first+1}, ... from restart_counts().
class MatchingChain {
 public:
  // Flat edge arrays from the graph (normalised weights). No allocation once grown.
  void build(const AssociationGraph& graph);
  // Sets X_0 (assignment[i] = measurement of target i or -1; must be a matching of the graph's
  // edges) and starts counting at X_1.
  void start(const std::vector<int>& assignment);
  // Runs `steps` steps.
  void run(RandomStream& rng, std::int64_t steps);
  // Discards the counts so far; counting restarts with the next step's state.
  void restart_counts();
  // Writes counts / (counted steps) into `marginals` (shape set by the caller, n×(m+1)).
  void write_frequencies(MarginalTable& marginals);

  int edges() const { return static_cast<int>(edges_.size()); }
  std::int64_t steps_done() const { return step_; }
  // Current measurement of target i (0-based), or -1 if missed.
  int target_measurement(int i) const { return target_edge_[i] < 0 ? -1 : edges_[target_edge_[i]].measurement; }

 private:
  struct Edge {
    int target;
    int measurement;
    double weight;  // normalised ψ_i(j) > 0
  };
  void flush();

  int targets_ = 0;
  int measurements_ = 0;
  std::vector<Edge> edges_;
  std::vector<int> target_edge_;          // matched edge of each target, or -1
  std::vector<int> measurement_edge_;     // matched edge of each measurement, or -1
  std::vector<std::int64_t> counts_;      // n×(m+1): counted steps per (target, state)
  std::vector<std::int64_t> since_;       // per target: first uncounted step of its current state
  std::int64_t step_ = 0;                 // steps done
  std::int64_t count_from_ = 1;           // first counted step
};

class Mcmcda final : public SingleScanSolver {
 public:
  using Options = McmcdaOptions;
  static constexpr std::string_view kName = "mcmcda";
  static constexpr std::string_view kSummary =
      "single-scan MCMCDA (Oh, Russell & Sastry 2009): lazy Metropolis chain over matchings from the MAP event";

  explicit Mcmcda(const Options& options) : options_(options) {}
  void solve(const SingleScanProblem& problem, MarginalTable& marginals, SolveReport& report) override;

  // Philox key of the chain's stream for trial seed `trial_seed` and option seed `option_seed`.
  static std::uint64_t stream_seed(std::uint64_t trial_seed, std::int64_t option_seed);

 private:
  Options options_;
  AssociationGraph graph_;
  MapAssignment map_;
  std::vector<int> assignment_;
  MatchingChain chain_;
};

}  // namespace dabench
