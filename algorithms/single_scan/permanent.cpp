#include "algorithms/single_scan/permanent.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "harness/single_scan/registry.hpp"

namespace dabench {

namespace {
constexpr int kMaxSubsetSide = 30;
}  // namespace

bool SubsetPermanent::fits(int targets, int measurements, std::int64_t memory_mb) {
  const int q = std::min(targets, measurements), p = std::max(targets, measurements);
  if (q > kMaxSubsetSide) return false;
  const double bytes = (p + 3.0) * std::ldexp(1.0, q) * static_cast<double>(sizeof(double));
  return bytes <= static_cast<double>(memory_mb) * 1048576.0;
}

double SubsetPermanent::weight(int k, int l) const {
  const std::size_t row = static_cast<std::size_t>(targets_are_subsets_ ? l : k);
  const std::size_t column = static_cast<std::size_t>(targets_are_subsets_ ? k : l);
  return weights_[row * static_cast<std::size_t>(measurements_) + column];
}

double SubsetPermanent::forward(const double* weights, int targets, int measurements) {
  weights_ = weights;
  targets_ = targets;
  measurements_ = measurements;
  targets_are_subsets_ = targets <= measurements;
  q_ = std::min(targets, measurements);
  p_ = std::max(targets, measurements);
  const std::size_t states = std::size_t{1} << q_;
  gated_.resize(static_cast<std::size_t>(p_));
  for (int k = 0; k < p_; ++k) {
    gated_[k].clear();
    for (int l = 0; l < q_; ++l) {
      if (weight(k, l) > 0.0) gated_[k].push_back(l);
    }
  }
  forward_.assign(static_cast<std::size_t>(p_ + 1) * states, 0.0);
  log_scale_.assign(static_cast<std::size_t>(p_ + 1), 0.0);
  forward_[0] = 1.0;
  for (int k = 1; k <= p_; ++k) {
    const double* previous = forward_.data() + static_cast<std::size_t>(k - 1) * states;
    double* current = forward_.data() + static_cast<std::size_t>(k) * states;
    for (std::size_t s = 0; s < states; ++s) {
      const double f = previous[s];
      if (f == 0.0) continue;
      current[s] += f;  // element k − 1 takes nothing
      for (const int l : gated_[k - 1]) {
        const std::size_t bit = std::size_t{1} << l;
        if ((s & bit) == 0) current[s | bit] += f * weight(k - 1, l);
      }
    }
    const double largest = *std::max_element(current, current + states);  // ≥ F_{k−1}(∅)-derived mass > 0
    for (std::size_t s = 0; s < states; ++s) current[s] /= largest;
    log_scale_[k] = log_scale_[k - 1] + std::log(largest);
  }
  const double* last = forward_.data() + static_cast<std::size_t>(p_) * states;
  double total = 0.0;
  for (std::size_t s = 0; s < states; ++s) total += last[s];
  return log_scale_[p_] + std::log(total);
}

double SubsetPermanent::log_partition(const double* weights, int targets, int measurements) {
  return forward(weights, targets, measurements);
}

bool SubsetPermanent::marginals(const double* weights, int targets, int measurements, std::vector<double>& out) {
  const double log_z = forward(weights, targets, measurements);
  const std::size_t states = std::size_t{1} << q_;
  double largest_weight = 0.0;
  for (int k = 0; k < p_; ++k) {
    for (const int l : gated_[k]) largest_weight = std::max(largest_weight, weight(k, l));
  }
  // The largest of exp(log scale of F_j + log scale of B_j' − log Z) over the pairings used: what
  // an absolute loss in a scaled layer entry or product (underflow: below the smallest subnormal)
  // is multiplied by on its way into a probability.
  double log_amplification = -std::numeric_limits<double>::infinity();
  const std::size_t columns = static_cast<std::size_t>(measurements) + 1;
  out.assign(static_cast<std::size_t>(targets) * columns, 0.0);
  // Where "processed element k takes subset element l" and "k takes nothing" go in `out`.
  const auto pair_entry = [&](int k, int l) -> double& {
    return targets_are_subsets_ ? out[static_cast<std::size_t>(l) * columns + static_cast<std::size_t>(k) + 1]
                                : out[static_cast<std::size_t>(k) * columns + static_cast<std::size_t>(l) + 1];
  };
  backward_.assign(states, 1.0);  // B_p
  next_backward_.resize(states);
  double log_backward = 0.0;
  for (int k = p_; k >= 1; --k) {  // element e = k − 1, between F_{k−1} and B_k
    const int e = k - 1;
    const double* f = forward_.data() + static_cast<std::size_t>(k - 1) * states;
    const double log_factor = log_scale_[k - 1] + log_backward - log_z;
    const double factor = std::exp(log_factor);
    log_amplification = std::max(log_amplification, log_factor);
    if (!targets_are_subsets_) {  // a target taking nothing: its missed detection
      double nothing = 0.0;
      for (std::size_t s = 0; s < states; ++s) nothing += f[s] * backward_[s];
      out[static_cast<std::size_t>(e) * columns] = nothing * factor;
    }
    for (const int l : gated_[e]) {
      const std::size_t bit = std::size_t{1} << l;
      double sum = 0.0;
      for (std::size_t s = 0; s < states; ++s) {
        if ((s & bit) == 0) sum += f[s] * backward_[s | bit];
      }
      pair_entry(e, l) = sum * weight(e, l) * factor;
    }
    double largest = 0.0;
    for (std::size_t s = 0; s < states; ++s) {
      double b = backward_[s];
      for (const int l : gated_[e]) {
        const std::size_t bit = std::size_t{1} << l;
        if ((s & bit) == 0) b += weight(e, l) * backward_[s | bit];
      }
      next_backward_[s] = b;
      largest = std::max(largest, b);
    }
    for (std::size_t s = 0; s < states; ++s) next_backward_[s] /= largest;
    log_backward += std::log(largest);
    log_amplification = std::max(log_amplification, log_scale_[k - 1] + log_backward - log_z);  // F_{k−1} with B_{k−1}
    std::swap(backward_, next_backward_);
  }
  if (targets_are_subsets_) {  // a target no measurement took: its missed detection
    const double* last = forward_.data() + static_cast<std::size_t>(p_) * states;
    const double factor = std::exp(log_scale_[p_] - log_z);
    for (int l = 0; l < q_; ++l) {
      const std::size_t bit = std::size_t{1} << l;
      double sum = 0.0;
      for (std::size_t s = 0; s < states; ++s) {
        if ((s & bit) == 0) sum += last[s];
      }
      out[static_cast<std::size_t>(l) * columns] = sum * factor;
    }
  }
  // Every stored entry of F and B and every product of the passes is ≤ 1 after scaling (a
  // product with a weight ≤ largest_weight), so what underflow can take from one is below
  // (q + 2) subnormals, and at most p · 2^q of them feed a probability, each amplified as above.
  // Where that bound is not below 1e−12 (weights whose products leave double's range, e.g. ψ of
  // 1e300 and 1e30 in one cluster), the marginals are refused rather than returned wrong.
  const double lost = static_cast<double>(p_) * static_cast<double>(states) * (q_ + 2.0) *
                      std::numeric_limits<double>::denorm_min() * (1.0 + largest_weight);
  return std::log(lost) + log_amplification < std::log(1e-12);
}

std::string PermanentOptions::validate() const {
  if (memory_mb < 1) return "memory_mb must be >= 1";
  return {};
}

void PermanentMarginals::solve(const SingleScanProblem& problem, MarginalTable& marginals, SolveReport& report) {
  report.reset();
  if (!(problem.largest_weight_sum() < SingleScanProblem::kOutOfRangeSum)) {
    report.skipped = "numerical";
    return;
  }
  graph_.build(problem);
  graph_.find_clusters();
  const int n = graph_.targets(), m = graph_.measurements();
  local_measurement_.assign(static_cast<std::size_t>(m), -1);
  const std::vector<int>& members = graph_.cluster_targets();
  const auto gather = [&](int c) { graph_.cluster_measurements(c, cluster_measurements_, local_measurement_); };
  const auto release = [&] { AssociationGraph::release_cluster_measurements(cluster_measurements_, local_measurement_); };
  for (int c = 0; c < graph_.clusters(); ++c) {  // refuse before any work
    gather(c);
    const bool fits = SubsetPermanent::fits(graph_.cluster_start(c + 1) - graph_.cluster_start(c),
                                            static_cast<int>(cluster_measurements_.size()), options_.memory_mb);
    release();
    if (!fits) {
      report.skipped = "memory";
      return;
    }
  }
  marginals.reshape_zero(n, m);
  for (int c = 0; c < graph_.clusters(); ++c) {
    gather(c);
    const int targets = graph_.cluster_start(c + 1) - graph_.cluster_start(c);
    const int measurements = static_cast<int>(cluster_measurements_.size());
    dense_.assign(static_cast<std::size_t>(targets) * static_cast<std::size_t>(measurements), 0.0);
    for (int t = 0; t < targets; ++t) {
      const int i = members[graph_.cluster_start(c) + t];
      for (int e = graph_.row_begin(i); e < graph_.row_end(i); ++e) {
        dense_[static_cast<std::size_t>(t) * static_cast<std::size_t>(measurements) +
               static_cast<std::size_t>(local_measurement_[graph_.edge_measurement(e)])] = graph_.edge_weight(e);
      }
    }
    if (!permanent_.marginals(dense_.data(), targets, measurements, cluster_marginals_)) {
      report.skipped = "numerical";
      return;
    }
    for (int t = 0; t < targets; ++t) {
      const int i = members[graph_.cluster_start(c) + t];
      const double* local = cluster_marginals_.data() + static_cast<std::size_t>(t) * static_cast<std::size_t>(measurements + 1);
      double sum = 0.0;
      for (int k = 0; k <= measurements; ++k) sum += local[k];
      double* row = marginals.row(i);
      row[0] = local[0] / sum;
      for (int k = 0; k < measurements; ++k) row[cluster_measurements_[k] + 1] = local[k + 1] / sum;
    }
    release();
  }
}

DABENCH_REGISTER_SINGLE_SCAN_ALGORITHM(PermanentMarginals);

}  // namespace dabench
