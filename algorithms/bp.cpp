#include "algorithms/bp.hpp"

#include <algorithm>
#include <cmath>

#include "harness/registry.hpp"

namespace dabench {

std::string BpOptions::validate() const {
  if (check_every < 1) return "check_every must be >= 1";
  if (!(delta > 0.0)) return "delta must be > 0";
  if (max_iterations < 1) return "max_iterations must be >= 1";
  return {};
}

void BeliefPropagation::build_shared_edges() {
  const int m = graph_.measurements();
  compact_column_.assign(m, -1);
  int shared_columns = 0;
  for (int j = 0; j < m; ++j) {
    if (graph_.measurement_degree(j) > 1) compact_column_[j] = shared_columns++;
  }
  active_target_.clear();
  active_begin_.assign(1, 0);
  base_.clear();
  psi_.clear();
  column_.clear();
  edge_slot_.assign(graph_.edges(), -1);
  for (int i = 0; i < graph_.targets(); ++i) {
    double base = 1.0;
    const auto first_shared = psi_.size();
    for (int e = graph_.row_begin(i); e < graph_.row_end(i); ++e) {
      const int c = compact_column_[graph_.edge_measurement(e)];
      if (c < 0) {
        base += graph_.edge_weight(e);  // exclusive measurement: ν ≡ 1
      } else {
        edge_slot_[e] = static_cast<int>(psi_.size());
        psi_.push_back(graph_.edge_weight(e));
        column_.push_back(c);
      }
    }
    if (psi_.size() != first_shared) {
      active_target_.push_back(i);
      active_begin_.push_back(static_cast<int>(psi_.size()));
      base_.push_back(base);
    }
  }
  const std::size_t shared_edges = psi_.size();
  mu_.resize(shared_edges);
  nu_.assign(shared_edges, 1.0);  // ν_{j→i,0} = 1 (Fig. 3)
  nu_previous_.resize(shared_edges);
  column_sum_.resize(shared_columns);
}

void BeliefPropagation::iterate_once() {
  const int active = static_cast<int>(active_target_.size());
  const double* psi = psi_.data();
  double* mu = mu_.data();
  double* nu = nu_.data();
  // L-R messages, eq (20), as in Fig. 3: s = 1 + Σ_j ψν, μ_ij = ψ_ij / (s − ψ_ij ν_ji).
  for (int a = 0; a < active; ++a) {
    const int begin = active_begin_[a];
    const int end = active_begin_[a + 1];
    double s = base_[a];
    for (int e = begin; e < end; ++e) s += psi[e] * nu[e];
    for (int e = begin; e < end; ++e) mu[e] = psi[e] / (s - psi[e] * nu[e]);
  }
  // R-L messages, eq (21): s_j = 1 + Σ_i μ_ij, ν_ji = 1 / (s_j − μ_ij).
  std::fill(column_sum_.begin(), column_sum_.end(), 1.0);
  const int* column = column_.data();
  double* column_sum = column_sum_.data();
  const int edges = static_cast<int>(psi_.size());
  for (int e = 0; e < edges; ++e) column_sum[column[e]] += mu[e];
  for (int e = 0; e < edges; ++e) nu[e] = 1.0 / (column_sum[column[e]] - mu[e]);
}

double BeliefPropagation::message_distance() const {
  double worst_ratio = 1.0;
  for (std::size_t e = 0; e < nu_.size(); ++e) {
    const double ratio = nu_[e] / nu_previous_[e];
    worst_ratio = std::max(worst_ratio, std::max(ratio, 1.0 / ratio));
  }
  return std::log(worst_ratio);
}

bool BeliefPropagation::converged(double d, double w_star) const {
  if (d <= 0.0) return true;
  // α(L, W*) = log((1 + W* L)/(1 + W*)) / log L with L = e^d (Lemma 1, eq 26).
  const double alpha = std::log1p(w_star * std::expm1(d) / (1.0 + w_star)) / d;
  return alpha * d / (1.0 - alpha) < 0.5 * std::log1p(options_.delta);
}

void BeliefPropagation::solve(const SingleScanProblem& problem, MarginalTable& marginals, SolveReport& report) {
  report.reset();
  graph_.build(problem);
  const int n = graph_.targets();

  double w_star = 0.0;  // W* = max_i Σ_j ψ_i(j) (Lemma 2)
  for (int i = 0; i < n; ++i) {
    double w = 0.0;
    for (int e = graph_.row_begin(i); e < graph_.row_end(i); ++e) w += graph_.edge_weight(e);
    w_star = std::max(w_star, w);
  }
  report.w_star = w_star;

  build_shared_edges();
  int iterations = 0;
  bool done = psi_.empty();  // no measurement shared by two targets: BP is exact at once
  while (!done && iterations < options_.max_iterations) {
    const int block = std::min(options_.check_every, options_.max_iterations - iterations);
    for (int k = 1; k < block; ++k) iterate_once();
    std::copy(nu_.begin(), nu_.end(), nu_previous_.begin());  // ν̃ for the check
    iterate_once();
    iterations += block;
    done = converged(message_distance(), w_star);
  }
  report.iterations = iterations;
  report.converged = done;

  // Beliefs, eq (22): p_ij = ψ_ij ν_ji / s, p_i0 = 1/s, s = 1 + Σ_j ψ_ij ν_ji.
  marginals.reshape_zero(n, graph_.measurements());
  for (int i = 0; i < n; ++i) {
    double* row = marginals.row(i);
    double s = 1.0;
    for (int e = graph_.row_begin(i); e < graph_.row_end(i); ++e) {
      const int slot = edge_slot_[e];
      const double value = graph_.edge_weight(e) * (slot < 0 ? 1.0 : nu_[slot]);
      row[graph_.edge_measurement(e) + 1] = value;
      s += value;
    }
    const double inverse = 1.0 / s;
    row[0] = inverse;
    for (int e = graph_.row_begin(i); e < graph_.row_end(i); ++e) row[graph_.edge_measurement(e) + 1] *= inverse;
  }
}

DABENCH_REGISTER_SINGLE_SCAN(BeliefPropagation);

}  // namespace dabench
