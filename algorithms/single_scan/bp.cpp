#include "algorithms/single_scan/bp.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <utility>

#include "harness/core/grow_buffer.hpp"
#include "harness/core/target_clones.hpp"
#include "harness/single_scan/registry.hpp"

namespace dabench {

std::string BpOptions::validate() const {
  if (check_every < 1) return "check_every must be >= 1";
  if (!(delta > 0.0)) return "delta must be > 0";
  if (max_iterations < 1) return "max_iterations must be >= 1";
  if (dense_cells < 0) return "dense_cells must be >= 0";
  return {};
}

namespace {

// One BP iteration over the shared edges. The flat loops with indexed loads vectorise (AVX2
// gathers where the CPU has them: one clone per ISA, chosen at load time); the arithmetic and
// its order are the same in every clone, so results are bit-identical on every machine.
DABENCH_AVX2_CLONES void bp_iteration(
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

// The same iteration on a small dense block (active targets × shared measurements, row stride
// a multiple of 4, zeros where there is no edge), for problems where most pairs are gated:
// every loop is a plain vector loop, with no index loads. Zeros change nothing: ψ = 0 gives
// μ = 0, and adding 0 leaves every sum bit-identical to the sparse loop, whose order (row
// sums by measurement, column sums by target) is kept.
DABENCH_AVX2_CLONES void bp_iteration_dense(
    int active, int stride, const double* __restrict base, const double* __restrict psi,
    double* __restrict product, double* __restrict column_sum, double* __restrict mu, double* __restrict nu) {
  constexpr int kLanes = 4;  // stride is a multiple of this: the inner loops are single vector ops
  for (int a = 0; a < active; ++a) {
    const int row = a * stride;
    for (int c = 0; c < stride; c += kLanes) {
      for (int k = c; k < c + kLanes; ++k) product[row + k] = psi[row + k] * nu[row + k];
    }
    double s = base[a];
    for (int c = 0; c < stride; ++c) s += product[row + c];
    for (int c = 0; c < stride; c += kLanes) {
      for (int k = c; k < c + kLanes; ++k) mu[row + k] = psi[row + k] / (s - product[row + k]);
    }
  }
  for (int c = 0; c < stride; ++c) column_sum[c] = 1.0;
  for (int a = 0; a < active; ++a) {
    for (int c = 0; c < stride; c += kLanes) {
      for (int k = c; k < c + kLanes; ++k) column_sum[k] += mu[a * stride + k];
    }
  }
  for (int a = 0; a < active; ++a) {
    for (int c = 0; c < stride; c += kLanes) {
      for (int k = c; k < c + kLanes; ++k) nu[a * stride + k] = 1.0 / (column_sum[k] - mu[a * stride + k]);
    }
  }
}

// Eqs (20)-(21) divide by a sum minus one of its terms, s − t. Only the sum's largest term can
// cancel (any other t has s − t ≥ s/2), and s − t ≥ 1 (the missed detection's or the unassigned
// measurement's 1), so more than 16 bits can be lost only where s > 2^16: with ψ ~ 1e20 the
// plain form gives μ = ψ / 0. Problems whose sums can reach that run this iteration, which
// recomputes the largest term's message from the sum of the others, accumulated separately,
// wherever s − t < 2^-16 s, and is otherwise the plain iteration's arithmetic, bit for bit.
constexpr double kCancelling = 0x1p-16;

void bp_iteration_guarded(int active, int edges, int columns, const int* active_begin, const double* base,
                          const double* psi, const int* column, double* row_sum, double* column_sum, double* column_top,
                          int* column_top_edge, double* mu, double* nu) {
  for (int a = 0; a < active; ++a) {
    double s = base[a], top = -1.0;
    int top_edge = -1;
    for (int e = active_begin[a]; e < active_begin[a + 1]; ++e) {
      const double t = psi[e] * nu[e];
      s += t;
      if (t > top) top = t, top_edge = e;
    }
    row_sum[a] = s;
    for (int e = active_begin[a]; e < active_begin[a + 1]; ++e) mu[e] = psi[e] / (s - psi[e] * nu[e]);
    if (s - top < kCancelling * s) {
      double rest = base[a];
      for (int e = active_begin[a]; e < active_begin[a + 1]; ++e) rest += e == top_edge ? 0.0 : psi[e] * nu[e];
      mu[top_edge] = psi[top_edge] / rest;
    }
  }
  for (int c = 0; c < columns; ++c) column_sum[c] = 1.0, column_top[c] = -1.0;
  for (int e = 0; e < edges; ++e) {
    const int c = column[e];
    column_sum[c] += mu[e];
    if (mu[e] > column_top[c]) column_top[c] = mu[e], column_top_edge[c] = e;
  }
  for (int e = 0; e < edges; ++e) nu[e] = 1.0 / (column_sum[column[e]] - mu[e]);
  bool cancelling = false;  // column_top becomes the other terms' sum where the column cancels, else −1
  for (int c = 0; c < columns; ++c) {
    const bool here = column_sum[c] - column_top[c] < kCancelling * column_sum[c];
    column_top[c] = here ? 1.0 : -1.0;
    cancelling |= here;
  }
  if (!cancelling) return;
  for (int e = 0; e < edges; ++e) {
    const int c = column[e];
    if (column_top[c] > 0.0 && e != column_top_edge[c]) column_top[c] += mu[e];
  }
  for (int c = 0; c < columns; ++c) {
    if (column_top[c] > 0.0) nu[column_top_edge[c]] = 1.0 / column_top[c];
  }
}

}  // namespace

double BeliefPropagation::build_edges(const SingleScanProblem& problem) {
  const int n = problem.targets();
  const int m = problem.measurements();
  // ψ_i(j) in the ψ_i(0) = 1 normalisation, row-major n×m.
  if (problem.has_unit_side_weights()) {
    weights_ = problem.psi.data();
  } else {
    normalized_.resize(static_cast<std::size_t>(n) * m);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < m; ++j) normalized_[static_cast<std::size_t>(i) * m + j] = problem.normalized_weight(i, j);
    }
    weights_ = normalized_.data();
  }
  column_degree_.assign(m, 0);
  double w_star = 0.0;  // W* = max_i Σ_j ψ_i(j) (Lemma 2)
  for (int i = 0; i < n; ++i) {
    const double* row = weights_ + static_cast<std::size_t>(i) * m;
    double w = 0.0;
    for (int j = 0; j < m; ++j) {
      w += row[j];
      column_degree_[j] += row[j] > 0.0;
    }
    w_star = std::max(w_star, w);
  }
  compact_column_.resize(m);
  int shared_columns = 0;
  for (int j = 0; j < m; ++j) compact_column_[j] = column_degree_[j] > 1 ? shared_columns++ : -1;

  stride_ = (shared_columns + 3) / 4 * 4;
  carve_arena(n, m);

  // Shared edges, target by target.
  grow_buffer(active_target_, n);
  grow_buffer(active_begin_, n + 1);
  grow_buffer(row_, static_cast<std::size_t>(n) * m);
  grow_buffer(column_, static_cast<std::size_t>(n) * m);
  grow_buffer(measurement_, static_cast<std::size_t>(n) * m);
  int edges = 0, active = 0;
  active_begin_[0] = 0;
  if (shared_columns > 0) {
    // Every gated pair is written at the next slot, which only a shared one keeps.
    for (int i = 0; i < n; ++i) {
      const double* row = weights_ + static_cast<std::size_t>(i) * m;
      double base = 1.0;
      const int first = edges;
      for (int j = 0; j < m; ++j) {
        const double psi = row[j];
        if (!(psi > 0.0)) continue;
        const int c = compact_column_[j];
        base += c < 0 ? psi : 0.0;  // exclusive measurement: ν ≡ 1
        psi_[edges] = psi;
        row_[edges] = active;
        column_[edges] = c;
        measurement_[edges] = j;
        edges += c >= 0;
      }
      active_target_[active] = i;
      base_[active] = base;
      active += edges != first;
      active_begin_[active] = edges;
    }
  }
  edges_ = edges;
  active_ = active;
  // Can a row sum 1 + Σ ψν or a column sum 1 + Σ μ reach 2^16 (ν ≤ 1 and μ ≤ ψ, since the sums
  // less a term are ≥ 1)? Then the guarded iteration runs (see bp_iteration_guarded).
  // The same bounds with the row's base show whether a sum can overflow (ψ near 1e308).
  double largest_sum = 0.0, largest_total = 0.0;
  std::fill_n(column_top_, shared_columns, 0.0);  // here: Σ_i ψ_ij per shared measurement
  for (int a = 0; a < active; ++a) {
    double sum = 0.0;
    for (int e = active_begin_[a]; e < active_begin_[a + 1]; ++e) sum += psi_[e], column_top_[column_[e]] += psi_[e];
    largest_sum = std::max(largest_sum, sum);
    largest_total = std::max(largest_total, base_[a] + sum);
  }
  for (int c = 0; c < shared_columns; ++c) largest_sum = std::max(largest_sum, column_top_[c]);
  guarded_ = !(largest_sum + 1.0 < 0x1p16);  // NaN-safe: ψ = inf runs guarded too
  out_of_range_ = !(std::max(largest_total, largest_sum + 1.0) < SingleScanProblem::kOutOfRangeSum);
  if (guarded_) grow_buffer(column_top_edge_, shared_columns);
  dense_ = !guarded_ && edges > 0 && active * stride_ <= options_.dense_cells && active * stride_ <= 4 * edges;
  cells_ = dense_ ? active * stride_ : edges;
  if (dense_) {
    grow_buffer(edge_cell_, edges);
    std::fill_n(block_psi_, cells_, 0.0);
    for (int e = 0; e < edges; ++e) {
      edge_cell_[e] = row_[e] * stride_ + column_[e];
      block_psi_[edge_cell_[e]] = psi_[e];
    }
  }
  std::fill_n(nu_, cells_, 1.0);  // ν_{j→i,0} = 1 (Fig. 3)
  columns_ = dense_ ? stride_ : shared_columns;
  return w_star;
}

void BeliefPropagation::carve_arena(int n, int m) {
  // Upper bounds: shared edges ≤ n·m, dense cells = active·stride ≤ n·stride. Every array
  // starts on a cache line (8 doubles); the arena only grows.
  const auto lines = [](std::size_t count) { return (count + 7) / 8 * 8; };
  const std::size_t targets = lines(static_cast<std::size_t>(n));
  const std::size_t pairs = lines(static_cast<std::size_t>(n) * m);
  const std::size_t cells = std::max(pairs, lines(static_cast<std::size_t>(n) * stride_));
  const std::size_t columns = lines(static_cast<std::size_t>(std::max(m, stride_)));
  const std::size_t total = 2 * targets + pairs + 5 * cells + 2 * columns;
  if (arena_.size() < total) arena_.resize(total);
  double* next = arena_.data();
  const auto take = [&next](std::size_t count) { return std::exchange(next, next + count); };
  base_ = take(targets);
  row_sum_ = take(targets);
  psi_ = take(pairs);
  block_psi_ = take(cells);
  block_product_ = take(cells);
  mu_ = take(cells);
  nu_ = take(cells);
  nu_previous_ = take(cells);
  column_sum_ = take(columns);
  column_top_ = take(columns);
}

void BeliefPropagation::iterate_once() {
  if (guarded_) {
    bp_iteration_guarded(active_, edges_, columns_, active_begin_.data(), base_, psi_, column_.data(), row_sum_,
                         column_sum_, column_top_, column_top_edge_.data(), mu_, nu_);
    return;
  }
  if (dense_) {
    bp_iteration_dense(active_, stride_, base_, block_psi_, block_product_, column_sum_, mu_, nu_);
    return;
  }
  bp_iteration(active_, edges_, columns_, active_begin_.data(), base_, psi_, row_.data(), column_.data(), row_sum_,
               column_sum_, mu_, nu_);
}

bool BeliefPropagation::converged() const {
  // Division-free pre-test: the stopping rule below fails whenever some ratio ν/ν̃ (or ν̃/ν)
  // exceeds 1/(1 − stop/W*) (see the cheap test below); with a 1e-12 relative margin
  // against rounding, this only returns early where the full test would also say no.
  if (w_star_ > stop_level_) {
    const double bound = (1.0 + 1e-12) / (1.0 - stop_level_ / w_star_);
    for (int e = 0; e < edges_; ++e) {
      const int cell = dense_ ? edge_cell_[e] : e;
      if (nu_[cell] > bound * nu_previous_[cell] || nu_previous_[cell] > bound * nu_[cell]) return false;
    }
  }
  double largest = 1.0, smallest = 1.0;  // extreme ratios ν/ν̃; d = log max(largest, 1/smallest)
  for (int e = 0; e < edges_; ++e) {
    const int cell = dense_ ? edge_cell_[e] : e;  // cells without an edge are not messages
    const double ratio = nu_[cell] / nu_previous_[cell];
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

void BeliefPropagation::write_beliefs(int n, int m, MarginalTable& marginals) const {
  // Beliefs, eq (22): p_ij = ψ_ij ν_ji / s, p_i0 = 1/s, s = 1 + Σ_j ψ_ij ν_ji; ν ≡ 1 off the
  // shared edges, so the row starts as ψ and only shared edges are scaled.
  marginals.reshape(n, m);
  for (int i = 0; i < n; ++i) std::copy_n(weights_ + static_cast<std::size_t>(i) * m, m, marginals.row(i) + 1);
  for (int a = 0; a < active_; ++a) {
    double* row = marginals.row(active_target_[a]) + 1;
    for (int e = active_begin_[a]; e < active_begin_[a + 1]; ++e) row[measurement_[e]] *= nu_[dense_ ? edge_cell_[e] : e];
  }
  for (int i = 0; i < n; ++i) {
    double* row = marginals.row(i);
    double s = 1.0, missed = 1.0;
    for (int j = 1; j <= m; ++j) s += row[j];
    if (!(s <= std::numeric_limits<double>::max())) {  // terms near 1e308 overflowed: divide by the largest first
      const double top = *std::max_element(row + 1, row + m + 1);
      missed = s = 1.0 / top;
      for (int j = 1; j <= m; ++j) row[j] /= top, s += row[j];
    }
    const double inverse = 1.0 / s;
    row[0] = missed * inverse;
    for (int j = 1; j <= m; ++j) row[j] *= inverse;
  }
}

void BeliefPropagation::solve(const SingleScanProblem& problem, MarginalTable& marginals, SolveReport& report) {
  report.reset();
  w_star_ = build_edges(problem);
  stop_level_ = 0.5 * std::log1p(options_.delta);
  report.w_star = w_star_;

  if (out_of_range_) {  // eqs (20)-(21) would divide by an overflowed sum: μ = 0, silently wrong
    report.skipped = "numerical";
    return;
  }
  int iterations = 0;
  bool done = edges_ == 0;  // no measurement shared by two targets: the graph is a forest
  while (!done && iterations < options_.max_iterations) {
    const int block = std::min(options_.check_every, options_.max_iterations - iterations);
    for (int k = 1; k < block; ++k) iterate_once();
    std::copy_n(nu_, cells_, nu_previous_);  // ν̃ of Fig. 3
    iterate_once();
    iterations += block;
    done = converged();
  }
  report.iterations = iterations;
  report.converged = done;
  write_beliefs(problem.targets(), problem.measurements(), marginals);
}

DABENCH_REGISTER_SINGLE_SCAN_ALGORITHM(BeliefPropagation);

}  // namespace dabench
