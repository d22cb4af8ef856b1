#include "algorithms/single_scan/mcmcda.hpp"

#include <algorithm>

#include "harness/single_scan/registry.hpp"

namespace dabench {

std::string McmcdaOptions::validate() const {
  if (samples < 1) return "samples must be >= 1";
  if (burnin < 0) return "burnin must be >= 0";
  return {};
}

std::uint64_t Mcmcda::stream_seed(std::uint64_t trial_seed, std::int64_t option_seed) {
  return algorithm_stream_seed(trial_seed, option_seed);
}

void MatchingChain::build(const AssociationGraph& graph) {
  targets_ = graph.targets();
  measurements_ = graph.measurements();
  edges_.resize(graph.edges());
  for (int i = 0; i < targets_; ++i) {
    for (int e = graph.row_begin(i); e < graph.row_end(i); ++e) {
      edges_[e] = Edge{i, graph.edge_measurement(e), graph.edge_weight(e)};
    }
  }
  target_edge_.resize(targets_);
  measurement_edge_.resize(measurements_);
  counts_.resize(static_cast<std::size_t>(targets_) * static_cast<std::size_t>(measurements_ + 1));
  since_.resize(targets_);
}

void MatchingChain::start(const std::vector<int>& assignment) {
  std::fill(target_edge_.begin(), target_edge_.end(), -1);
  std::fill(measurement_edge_.begin(), measurement_edge_.end(), -1);
  // Edges are ordered by target, then measurement: find each assigned pair's edge.
  for (int e = 0; e < static_cast<int>(edges_.size()); ++e) {
    if (assignment[edges_[e].target] == edges_[e].measurement) {
      target_edge_[edges_[e].target] = e;
      measurement_edge_[edges_[e].measurement] = e;
    }
  }
  step_ = 0;
  restart_counts();
}

void MatchingChain::restart_counts() {
  std::fill(counts_.begin(), counts_.end(), std::int64_t{0});
  count_from_ = step_ + 1;
  std::fill(since_.begin(), since_.end(), count_from_);
}

void MatchingChain::run(RandomStream& rng, std::int64_t steps) {
  const std::int64_t end = step_ + steps;
  const std::uint32_t edge_count = static_cast<std::uint32_t>(edges_.size());
  if (edge_count == 0 || steps <= 0) {  // no move is possible: the state is fixed
    step_ = std::max(step_, end);
    return;
  }
  // Lemire's multiply-shift: low word of x·|E| below (2^32 − |E|) mod |E| is rejected.
  const std::uint32_t reject_below = (0u - edge_count) % edge_count;
  const Edge* const edges = edges_.data();
  int* const target_edge = target_edge_.data();
  int* const measurement_edge = measurement_edge_.data();
  std::int64_t* const counts = counts_.data();
  std::int64_t* const since = since_.data();
  const std::int64_t stride = measurements_ + 1;
  // Target i leaves state `from` (0 = missed, j+1 = measurement j) at step t: the state was
  // X_since .. X_{t-1}.
  const auto leave = [&](int i, int from, std::int64_t t) {
    counts[i * stride + from] += t - since[i];
    since[i] = t;
  };

  for (std::int64_t t = step_ + 1; t <= end; ++t) {
    const std::uint64_t word = rng.next_u64();
    if (word >> 63) continue;  // lazy half
    std::uint64_t product = (word & 0xFFFFFFFFull) * edge_count;
    while (static_cast<std::uint32_t>(product) < reject_below) {
      product = (rng.next_u64() & 0xFFFFFFFFull) * edge_count;
    }
    const int e = static_cast<int>(product >> 32);
    const Edge edge = edges[e];
    const int matched_i = target_edge[edge.target];
    const int matched_j = measurement_edge[edge.measurement];
    if (matched_i == e) {
      // Deletion: π'/π = 1/ψ.
      if (edge.weight > 1.0 && !(rng.uniform() * edge.weight < 1.0)) continue;
      target_edge[edge.target] = -1;
      measurement_edge[edge.measurement] = -1;
      leave(edge.target, edge.measurement + 1, t);
    } else if (matched_i < 0) {
      if (matched_j < 0) {
        // Addition: π'/π = ψ.
        if (edge.weight < 1.0 && !(rng.uniform() < edge.weight)) continue;
      } else {
        // Switch: measurement j moves from target i' to target i; π'/π = ψ_ij / ψ_i'j.
        const Edge old = edges[matched_j];
        if (edge.weight < old.weight && !(rng.uniform() * old.weight < edge.weight)) continue;
        target_edge[old.target] = -1;
        leave(old.target, old.measurement + 1, t);
      }
      target_edge[edge.target] = e;
      measurement_edge[edge.measurement] = e;
      leave(edge.target, 0, t);
    } else if (matched_j < 0) {
      // Switch: target i moves from measurement j' to j; π'/π = ψ_ij / ψ_ij'.
      const Edge old = edges[matched_i];
      if (edge.weight < old.weight && !(rng.uniform() * old.weight < edge.weight)) continue;
      measurement_edge[old.measurement] = -1;
      target_edge[edge.target] = e;
      measurement_edge[edge.measurement] = e;
      leave(edge.target, old.measurement + 1, t);
    }
    // else: i and j both matched elsewhere, ω' = ω.
  }
  step_ = end;
}

void MatchingChain::flush() {
  for (int i = 0; i < targets_; ++i) {
    const int state = target_edge_[i] < 0 ? 0 : edges_[target_edge_[i]].measurement + 1;
    counts_[static_cast<std::size_t>(i) * (measurements_ + 1) + state] += step_ + 1 - since_[i];
    since_[i] = step_ + 1;
  }
}

void MatchingChain::write_frequencies(MarginalTable& marginals) {
  flush();
  const std::int64_t counted = step_ + 1 - count_from_;
  const double inverse = counted > 0 ? 1.0 / static_cast<double>(counted) : 0.0;
  for (int i = 0; i < targets_; ++i) {
    double* row = marginals.row(i);
    const std::int64_t* count = counts_.data() + static_cast<std::size_t>(i) * (measurements_ + 1);
    for (int j = 0; j <= measurements_; ++j) row[j] = static_cast<double>(count[j]) * inverse;
  }
}

void Mcmcda::solve(const SingleScanProblem& problem, MarginalTable& marginals, SolveReport& report) {
  report.reset();
  graph_.build(problem);
  graph_.find_clusters();
  map_.solve(problem, graph_, assignment_);
  chain_.build(graph_);
  chain_.start(assignment_);
  RandomStream rng(stream_seed(problem.trial_key.seed, options_.seed), problem.trial_key.point,
                   problem.trial_key.trial);
  chain_.run(rng, options_.burnin);
  chain_.restart_counts();
  chain_.run(rng, options_.samples);
  marginals.reshape(graph_.targets(), graph_.measurements());
  chain_.write_frequencies(marginals);
}

DABENCH_REGISTER_SINGLE_SCAN_ALGORITHM(Mcmcda);

}  // namespace dabench
