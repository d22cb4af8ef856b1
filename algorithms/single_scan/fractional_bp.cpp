#include "algorithms/single_scan/fractional_bp.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "harness/core/errors.hpp"
#include "harness/core/grow_buffer.hpp"
#include "harness/core/target_clones.hpp"
#include "harness/single_scan/registry.hpp"

namespace dabench {

std::string FractionalBpOptions::validate() const {
  if (!(gamma >= 0.0 && gamma <= 1.0)) return "gamma must be in [0, 1]";
  if (!(alpha > 0.5 && std::isfinite(alpha))) return "alpha must be finite and > 0.5";
  if (!(alpha >= gamma)) return "alpha must be >= gamma";
  if (!(beta > 0.5 && std::isfinite(beta))) return "beta must be finite and > 0.5";
  if (!(beta >= gamma)) return "beta must be >= gamma";
  if (!(tolerance > 0.0)) return "tolerance must be > 0";
  if (max_iterations < 1) return "max_iterations must be >= 1";
  return {};
}

namespace {

// The pairwise exponent of eqs (160) and (163): S^{−γ} for the sum S that excludes the pair.
// γ = 1 (BP) and γ = 0 (pure entropy, no per-pair power) have their own loops.
enum class Exponent { one, zero, general };

template <Exponent kind>
inline double excluded_power(double excluded, double gamma) {
  if constexpr (kind == Exponent::one) return 1.0 / excluded;
  else if constexpr (kind == Exponent::zero) return 1.0;
  else return std::pow(excluded, -gamma);
}

// e^κ S^{−(1−γ)}: the factor shared by all pairs of one row or column.
inline double shared_factor(double e_kappa, double sum, double gamma) {
  if (gamma == 1.0) return e_kappa;
  if (gamma == 0.0) return e_kappa / sum;
  return e_kappa * std::pow(sum, gamma - 1.0);
}

// x_ij = factor_j · (C_j − w_ij y_ij)^{−γ} for every stored pair (eq 160). The sum excluding a
// pair is formed without cancellation: for the largest term of a column (`top`) it is the sum of
// the other terms, accumulated separately (`rest`); for any other term t ≤ top, C_j − t ≥ C_j / 2,
// so the subtraction loses at most one bit. A plain C_j − w_ij y_ij would return 0 or garbage
// once one term exceeds the rest by ~1e16.
template <Exponent kind>
DABENCH_AVX2_CLONES void pair_messages(int edges, double gamma, const int* __restrict column, const double* __restrict weight,
                   const double* __restrict from, const double* __restrict sum, const double* __restrict factor,
                   const int* __restrict top, const double* __restrict rest, double* __restrict to) {
  for (int e = 0; e < edges; ++e) {
    const int c = column[e];
    const double excluded = top[c] == e ? rest[c] : sum[c] - weight[e] * from[e];
    to[e] = factor[c] * excluded_power<kind>(excluded, gamma);
  }
}

// The convergence measure d = max |log(y_new / y_old)| of one iteration, compared with the
// tolerance. While no ratio has left [e^−tol, e^tol] (widened by 1e-12 against rounding) the
// extreme ratios are tracked exactly; once one has, the iteration cannot have converged and the
// remaining pairs are only compared by multiplication, so early iterations need no division per
// pair, and the stopping decision is exactly that of the plain max-ratio test.
class ChangeTracker {
 public:
  explicit ChangeTracker(double tolerance) : bound_(std::exp(tolerance) * (1.0 + 1e-12)) {}
  void add(double value, double old) {
    if (moved_) return;
    if (value > bound_ * old || old > bound_ * value) {
      moved_ = true;
      return;
    }
    const double ratio = value / old;
    largest_ = std::max(largest_, ratio);
    smallest_ = std::min(smallest_, ratio);
  }
  double change() const {  // d, or +inf once some ratio is certainly beyond the tolerance
    return moved_ ? std::numeric_limits<double>::infinity() : std::log(std::max(largest_, 1.0 / smallest_));
  }

 private:
  double bound_;
  bool moved_ = false;
  double largest_ = 1.0, smallest_ = 1.0;
};

// y_ij of one row (eq 163), with the same leave-one-out rule.
template <Exponent kind>
void row_messages(int begin, int end, double gamma, double factor, double sum, int top, double rest,
                  const double* __restrict weight, const double* __restrict from, double* __restrict to,
                  ChangeTracker& change) {
  for (int e = begin; e < end; ++e) {
    const double excluded = e == top ? rest : sum - weight[e] * from[e];
    const double value = factor * excluded_power<kind>(excluded, gamma);
    change.add(value, to[e]);
    to[e] = value;
  }
}

// Adds `term` (of pair `e`) to a sum kept as its largest term plus the rest (see pair_messages).
// Branch-free: which term is larger is data-dependent and would be mispredicted.
inline void add_term(double term, int e, double& top_value, int& top, double& rest) {
  const bool larger = term > top_value;
  rest += larger ? top_value : term;
  top_value = larger ? term : top_value;
  top = larger ? e : top;
}

Exponent exponent_of(double gamma) {
  if (gamma == 1.0) return Exponent::one;
  if (gamma == 0.0) return Exponent::zero;
  return Exponent::general;
}

// x log(x / w), with 0 log 0 = 0.
double relative_entropy_term(double x, double w) { return x > 0.0 ? x * std::log(x / w) : 0.0; }

}  // namespace

void FractionalBpKernel::build(WeightMatrix w, WeightVector miss_weight, WeightVector clutter_weight) {
  const int n = static_cast<int>(w.rows());
  const int m = static_cast<int>(w.cols());
  if (miss_weight.size() != 0 && miss_weight.size() != n) {
    throw InputError(fmt::format("fbp: miss_weight has {} entries, expected {} (one per target) or none", miss_weight.size(), n));
  }
  if (clutter_weight.size() != 0 && clutter_weight.size() != m) {
    throw InputError(fmt::format("fbp: clutter_weight has {} entries, expected {} (one per measurement) or none",
                                 clutter_weight.size(), m));
  }
  targets_ = n;
  measurements_ = m;
  grow_buffer(row_begin_, static_cast<std::size_t>(n) + 1);
  grow_buffer(edge_column_, static_cast<std::size_t>(n) * m);
  grow_buffer(edge_weight_, static_cast<std::size_t>(n) * m);
  grow_buffer(miss_, n);
  int edges = 0;
  row_begin_[0] = 0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) {
      const double value = w(i, j);
      if (!(value >= 0.0 && std::isfinite(value))) {
        throw InputError(fmt::format("fbp: weight w({}, {}) = {} must be finite and >= 0", i + 1, j + 1, value));
      }
      if (value == 0.0) continue;  // not gated: q_ij = 0 (Appendix D)
      edge_column_[edges] = j;
      edge_weight_[edges++] = value;
    }
    row_begin_[i + 1] = edges;
    const double miss = miss_weight.size() == 0 ? 1.0 : miss_weight[i];
    if (!(miss > 0.0 && std::isfinite(miss))) {
      throw InputError(fmt::format("fbp: miss_weight[{}] = {} must be finite and > 0", i + 1, miss));
    }
    miss_[i] = miss;
  }
  edges_ = edges;
  grow_buffer(clutter_, m);
  for (int j = 0; j < m; ++j) {
    const double clutter = clutter_weight.size() == 0 ? 1.0 : clutter_weight[j];
    if (!(clutter > 0.0 && std::isfinite(clutter))) {
      throw InputError(fmt::format("fbp: clutter_weight[{}] = {} must be finite and > 0", j + 1, clutter));
    }
    clutter_[j] = clutter;
  }
  // y ≡ 1 (Algorithm 1, Initialise).
  grow_buffer(x_, edges);
  grow_buffer(y_, edges);
  std::fill_n(y_.begin(), edges, 1.0);
  grow_buffer(x_miss_, n);
  grow_buffer(y_miss_, n);
  grow_buffer(row_sum_, n);
  std::fill_n(y_miss_.begin(), n, 1.0);
  grow_buffer(x_clutter_, m);
  grow_buffer(y_clutter_, m);
  grow_buffer(column_sum_, m);
  grow_buffer(column_factor_, m);
  grow_buffer(column_top_, m);
  grow_buffer(column_top_value_, m);
  grow_buffer(column_rest_, m);
  grow_buffer(q_clutter_, m);
  std::fill_n(y_clutter_.begin(), m, 1.0);
  grow_buffer(q_, static_cast<std::size_t>(n) * (m + 1));
}

void FractionalBpKernel::column_step(const FractionalBpOptions& options) {
  const int m = measurements_;
  const double gamma = options.gamma;
  for (int j = 0; j < m; ++j) {
    column_top_value_[j] = 0.0;  // the clutter term is never excluded: it starts in the rest
    column_top_[j] = -1;
    column_rest_[j] = clutter_[j] * y_clutter_[j];
  }
  for (int e = 0; e < edges_; ++e) {
    const int j = edge_column_[e];
    add_term(edge_weight_[e] * y_[e], e, column_top_value_[j], column_top_[j], column_rest_[j]);
  }
  for (int j = 0; j < m; ++j) {
    column_sum_[j] = column_rest_[j] + column_top_value_[j];
    const double inverse = 1.0 / column_sum_[j];
    x_clutter_[j] = inverse;                                   // eq (162)
    q_clutter_[j] = clutter_[j] * y_clutter_[j] * inverse;     // q_0j = w_0j y_0j x_0j
    column_factor_[j] = shared_factor(e_kappa_, column_sum_[j], gamma);
  }
  switch (exponent_of(gamma)) {  // eq (160)
    case Exponent::one:
      pair_messages<Exponent::one>(edges_, gamma, edge_column_.data(), edge_weight_.data(), y_.data(),
                                   column_sum_.data(), column_factor_.data(), column_top_.data(), column_rest_.data(), x_.data());
      break;
    case Exponent::zero:
      pair_messages<Exponent::zero>(edges_, gamma, edge_column_.data(), edge_weight_.data(), y_.data(),
                                    column_sum_.data(), column_factor_.data(), column_top_.data(), column_rest_.data(), x_.data());
      break;
    case Exponent::general:
      pair_messages<Exponent::general>(edges_, gamma, edge_column_.data(), edge_weight_.data(), y_.data(),
                                       column_sum_.data(), column_factor_.data(), column_top_.data(), column_rest_.data(), x_.data());
      break;
  }
  if (options.alpha == 1.0) {  // eq (161): x_i0 ≡ 1
    std::fill_n(x_miss_.begin(), targets_, 1.0);
  } else {
    const double power = 1.0 / options.alpha - 1.0;
    for (int i = 0; i < targets_; ++i) x_miss_[i] = std::pow(y_miss_[i], power);
  }
}

double FractionalBpKernel::row_step(const FractionalBpOptions& options) {
  const double gamma = options.gamma;
  const Exponent kind = exponent_of(gamma);
  ChangeTracker change(options.tolerance);
  for (int i = 0; i < targets_; ++i) {
    const int begin = row_begin_[i], end = row_begin_[i + 1];
    double top_value = 0.0, rest = miss_[i] * x_miss_[i];  // the miss term is never excluded
    int top = -1;
    for (int e = begin; e < end; ++e) add_term(edge_weight_[e] * x_[e], e, top_value, top, rest);
    const double sum = rest + top_value;
    row_sum_[i] = sum;
    const double y_miss = 1.0 / sum;  // eq (164)
    change.add(y_miss, y_miss_[i]);
    y_miss_[i] = y_miss;
    const double factor = shared_factor(e_kappa_, sum, gamma);
    switch (kind) {  // eq (163)
      case Exponent::one:
        row_messages<Exponent::one>(begin, end, gamma, factor, sum, top, rest, edge_weight_.data(), x_.data(), y_.data(),
                                    change);
        break;
      case Exponent::zero:
        row_messages<Exponent::zero>(begin, end, gamma, factor, sum, top, rest, edge_weight_.data(), x_.data(), y_.data(),
                                     change);
        break;
      case Exponent::general:
        row_messages<Exponent::general>(begin, end, gamma, factor, sum, top, rest, edge_weight_.data(), x_.data(), y_.data(),
                                        change);
        break;
    }
  }
  if (options.beta != 1.0) {  // eq (165); y_0j ≡ 1 when β = 1
    const double power = 1.0 / options.beta - 1.0;
    for (int j = 0; j < measurements_; ++j) {
      const double value = std::pow(x_clutter_[j], power);
      change.add(value, y_clutter_[j]);
      y_clutter_[j] = value;
    }
  }
  return change.change();
}

void FractionalBpKernel::write_outputs() {
  // Row-normalised read-out of the last iteration: q_ij = w_ij x_ij y_i0, q_i0 = w_i0 x_i0 y_i0,
  // y_i0 = 1/R_i (eqs 153-154 with 158-159); q_0j was set by the last column step.
  const int stride = measurements_ + 1;
  for (int i = 0; i < targets_; ++i) {
    double* row = q_.data() + static_cast<std::size_t>(i) * stride;
    const double inverse = 1.0 / row_sum_[i];
    std::fill_n(row, stride, 0.0);
    row[0] = miss_[i] * x_miss_[i] * inverse;
    for (int e = row_begin_[i]; e < row_begin_[i + 1]; ++e) row[1 + edge_column_[e]] = edge_weight_[e] * x_[e] * inverse;
  }
}

double FractionalBpKernel::objective(const FractionalBpOptions& options) const {
  const int stride = measurements_ + 1;
  double pairs = 0.0, pair_entropy = 0.0, misses = 0.0, clutter = 0.0;
  for (int i = 0; i < targets_; ++i) {
    const double* row = q_.data() + static_cast<std::size_t>(i) * stride;
    misses += relative_entropy_term(row[0], miss_[i]);
    for (int e = row_begin_[i]; e < row_begin_[i + 1]; ++e) {
      const double q = row[1 + edge_column_[e]];
      pairs += relative_entropy_term(q, edge_weight_[e]);
      if (q < 1.0) pair_entropy += (1.0 - q) * std::log1p(-q);
    }
  }
  for (int j = 0; j < measurements_; ++j) clutter += relative_entropy_term(q_clutter_[j], clutter_[j]);
  return pairs + options.alpha * misses + options.beta * clutter - options.gamma * pair_entropy;  // eq (138)
}

FractionalBpOutcome FractionalBpKernel::solve(WeightMatrix w, WeightVector miss_weight, WeightVector clutter_weight,
                                              const FractionalBpOptions& options) {
  if (std::string why = options.validate(); !why.empty()) throw InputError("fbp: " + why);
  build(w, miss_weight, clutter_weight);
  e_kappa_ = std::exp(-1.0 - options.gamma + options.alpha + options.beta);
  FractionalBpOutcome outcome;
  while (!outcome.converged && outcome.iterations < options.max_iterations) {
    column_step(options);
    outcome.converged = row_step(options) < options.tolerance;
    ++outcome.iterations;
  }
  write_outputs();
  outcome.objective = objective(options);
  return outcome;
}

FractionalBp::FractionalBp(const Options& options) : options_(options) {
  if (std::string why = options_.validate(); !why.empty()) throw InputError(std::string(kName) + ": " + why);
}

void FractionalBp::solve(const SingleScanProblem& problem, MarginalTable& marginals, SolveReport& report) {
  report.reset();
  if (!(problem.largest_weight_sum() < SingleScanProblem::kOutOfRangeSum)) {
    report.skipped = "numerical";
    return;
  }
  const FractionalBpOutcome outcome =
      kernel_.solve(problem.psi, problem.miss_weight, problem.clutter_weight, options_);
  report.iterations = outcome.iterations;
  report.converged = outcome.converged;
  report.free_energy = outcome.objective;
  marginals.reshape(problem.targets(), problem.measurements());
  marginals.view() = kernel_.target_marginals();
}

DABENCH_REGISTER_SINGLE_SCAN_ALGORITHM(FractionalBp);

}  // namespace dabench
