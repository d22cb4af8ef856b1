#include "algorithms/bp.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>

#include "harness/registry.hpp"

namespace dabench {

std::string BpOptions::validate() const {
  if (check_every < 1) return "check_every must be >= 1";
  if (!(delta > 0.0)) return "delta must be > 0";
  if (max_iterations < 1) return "max_iterations must be >= 1";
  return {};
}

namespace {

// ψ_i(j) in the ψ_i(0) = 1 normalisation.
inline double weight(const SingleScanProblem& problem, bool unit, int i, int j) {
  return unit ? problem.psi(i, j) : problem.normalized_weight(i, j);
}

// One BP iteration over the shared edges. The flat loops with indexed loads vectorise (AVX2
// gathers where the CPU has them: one clone per ISA, chosen at load time); the arithmetic and
// its order are the same in every clone, so results are bit-identical on every machine.
__attribute__((target_clones("avx2", "default"))) void bp_iteration(
    int active, int edges, int columns, const int* __restrict active_begin, const double* __restrict base,
    const double* __restrict psi, const int* __restrict row, const int* __restrict column,
    double* __restrict row_sum, double* __restrict column_sum, double* __restrict mu, double* __restrict nu) {
  // L-R messages, eq (20), as in Fig. 3: s_i = 1 + Σ_j ψ_ij ν_ji, μ_ij = ψ_ij / (s_i − ψ_ij ν_ji).
  for (int a = 0; a < active; ++a) {
    double s = base[a];
    for (int e = active_begin[a]; e < active_begin[a + 1]; ++e) s += psi[e] * nu[e];
    row_sum[a] = s;
  }
  for (int e = 0; e < edges; ++e) mu[e] = psi[e] / (row_sum[row[e]] - psi[e] * nu[e]);
  // R-L messages, eq (21): s_j = 1 + Σ_i μ_ij, ν_ji = 1 / (s_j − μ_ij).
  for (int c = 0; c < columns; ++c) column_sum[c] = 1.0;
  for (int e = 0; e < edges; ++e) column_sum[column[e]] += mu[e];
  for (int e = 0; e < edges; ++e) nu[e] = 1.0 / (column_sum[column[e]] - mu[e]);
}

}  // namespace

double BeliefPropagation::build_edges(const SingleScanProblem& problem) {
  const int n = problem.targets();
  const int m = problem.measurements();
  const bool unit = problem.has_unit_side_weights();
  column_degree_.assign(m, 0);
  double w_star = 0.0;  // W* = max_i Σ_j ψ_i(j) (Lemma 2)
  for (int i = 0; i < n; ++i) {
    double w = 0.0;
    for (int j = 0; j < m; ++j) {
      const double psi = weight(problem, unit, i, j);
      w += psi;
      column_degree_[j] += psi > 0.0;
    }
    w_star = std::max(w_star, w);
  }
  compact_column_.resize(m);
  int shared_columns = 0;
  for (int j = 0; j < m; ++j) compact_column_[j] = column_degree_[j] > 1 ? shared_columns++ : -1;

  active_target_.clear();
  active_begin_.assign(1, 0);
  base_.clear();
  psi_.clear();
  row_.clear();
  column_.clear();
  active_of_target_.assign(n, -1);
  if (shared_columns > 0) {
    for (int i = 0; i < n; ++i) {
      double base = 1.0;
      const std::size_t first = psi_.size();
      for (int j = 0; j < m; ++j) {
        const double psi = weight(problem, unit, i, j);
        if (!(psi > 0.0)) continue;
        if (compact_column_[j] < 0) {
          base += psi;  // exclusive measurement: ν ≡ 1
        } else {
          psi_.push_back(psi);
          row_.push_back(static_cast<int>(active_target_.size()));
          column_.push_back(compact_column_[j]);
        }
      }
      if (psi_.size() != first) {
        active_of_target_[i] = static_cast<int>(active_target_.size());
        active_target_.push_back(i);
        active_begin_.push_back(static_cast<int>(psi_.size()));
        base_.push_back(base);
      }
    }
  }
  nu_.assign(psi_.size(), 1.0);  // ν_{j→i,0} = 1 (Fig. 3)
  mu_.resize(psi_.size());
  nu_previous_.resize(psi_.size());
  row_sum_.resize(active_target_.size());
  column_sum_.resize(shared_columns);
  return w_star;
}

void BeliefPropagation::iterate_once() {
  bp_iteration(static_cast<int>(active_target_.size()), static_cast<int>(psi_.size()),
               static_cast<int>(column_sum_.size()), active_begin_.data(), base_.data(), psi_.data(), row_.data(),
               column_.data(), row_sum_.data(), column_sum_.data(), mu_.data(), nu_.data());
}

bool BeliefPropagation::converged() const {
  double largest = 1.0, smallest = 1.0;  // extreme ratios ν/ν̃; d = log max(largest, 1/smallest)
  for (std::size_t e = 0; e < nu_.size(); ++e) {
    const double ratio = nu_[e] / nu_previous_[e];
    largest = std::max(largest, ratio);
    smallest = std::min(smallest, ratio);
  }
  const double ratio = std::max(largest, 1.0 / smallest);
  if (ratio <= 1.0 + 32.0 * DBL_EPSILON) return true;  // floating-point fixed point
  // α ≥ W*/(1+W*) (Lemma 1: α grows with L, limit at L → 1), so α d/(1−α) ≥ W*·d, and
  // d = log(ratio) ≥ 1 − 1/ratio: a cheap test that skips the logarithms while far away.
  if (w_star_ * (1.0 - 1.0 / ratio) >= stop_level_) return false;
  const double d = std::log(ratio);
  // α(L, W*) = log((1 + W* L)/(1 + W*)) / log L with L = e^d (Lemma 1, eq 26).
  const double alpha = std::log1p(w_star_ * std::expm1(d) / (1.0 + w_star_)) / d;
  return alpha * d / (1.0 - alpha) < stop_level_;
}

void BeliefPropagation::write_beliefs(const SingleScanProblem& problem, MarginalTable& marginals) const {
  // Beliefs, eq (22): p_ij = ψ_ij ν_ji / s, p_i0 = 1/s, s = 1 + Σ_j ψ_ij ν_ji.
  const int n = problem.targets();
  const int m = problem.measurements();
  const bool unit = problem.has_unit_side_weights();
  marginals.reshape(n, m);
  for (int i = 0; i < n; ++i) {
    double* row = marginals.row(i);
    const int a = active_of_target_[i];
    int edge = a < 0 ? 0 : active_begin_[a];  // shared edges of i, in measurement order
    double s = 1.0;
    for (int j = 0; j < m; ++j) {
      const double psi = weight(problem, unit, i, j);
      double value = 0.0;
      if (psi > 0.0) value = compact_column_[j] < 0 ? psi : psi * nu_[edge++];
      row[j + 1] = value;
      s += value;
    }
    const double inverse = 1.0 / s;
    row[0] = inverse;
    for (int j = 1; j <= m; ++j) row[j] *= inverse;
  }
}

void BeliefPropagation::solve(const SingleScanProblem& problem, MarginalTable& marginals, SolveReport& report) {
  report.reset();
  w_star_ = build_edges(problem);
  stop_level_ = 0.5 * std::log1p(options_.delta);
  report.w_star = w_star_;

  int iterations = 0;
  bool done = psi_.empty();  // no measurement shared by two targets: the graph is a forest
  while (!done && iterations < options_.max_iterations) {
    const int block = std::min(options_.check_every, options_.max_iterations - iterations);
    for (int k = 1; k < block; ++k) iterate_once();
    std::copy(nu_.begin(), nu_.end(), nu_previous_.begin());  // ν̃ of Fig. 3
    iterate_once();
    iterations += block;
    done = converged();
  }
  report.iterations = iterations;
  report.converged = done;
  write_beliefs(problem, marginals);
}

DABENCH_REGISTER_SINGLE_SCAN(BeliefPropagation);

}  // namespace dabench
