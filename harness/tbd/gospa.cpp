#include "harness/tbd/gospa.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "harness/core/errors.hpp"
#include "harness/core/grow_buffer.hpp"

namespace dabench {

namespace {

void check_finite(const std::vector<Eigen::Vector2d>& points, const char* set) {
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (!points[k].allFinite()) throw std::invalid_argument(fmt::format("gospa: {} point {} is not finite", set, k));
  }
}

}  // namespace

void GospaOptions::validate() const {
  if (!(cutoff > 0.0 && std::isfinite(cutoff)))
    throw InputError(fmt::format("gospa: cutoff must be > 0 and finite (got {})", cutoff));
  if (!(order >= 1.0 && std::isfinite(order)))
    throw InputError(fmt::format("gospa: order must be ≥ 1 and finite (got {})", order));
  if (!(alpha > 0.0 && alpha <= 2.0)) throw InputError(fmt::format("gospa: alpha must be in (0, 2] (got {})", alpha));
}

GospaResult Gospa::compute(const std::vector<Eigen::Vector2d>& truth, const std::vector<Eigen::Vector2d>& estimates,
                           const GospaOptions& options) {
  options.validate();
  check_finite(truth, "truth");
  check_finite(estimates, "estimate");
  const int rows = static_cast<int>(truth.size());
  const int cols = static_cast<int>(estimates.size());
  const double c = options.cutoff;
  const double p = options.order;
  const double cutoff_power = std::pow(c, p);

  // d^(c)(x_i, y_j)^p; LinearAssignment transposes internally when |X| > |Y|, which is the
  // symmetric case of Definition 1.
  grow_buffer(cost_, static_cast<std::size_t>(rows) * cols);
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) {
      cost_[static_cast<std::size_t>(i) * cols + j] = std::pow(std::min((truth[i] - estimates[j]).norm(), c), p);
    }
  }
  double assigned_cost = 0.0;
  [[maybe_unused]] const bool solved = assignment_.solve(cost_.data(), rows, cols, column_of_row_, assigned_cost);
  assert(solved);  // every entry is finite

  GospaResult result;
  const double unmatched = std::abs(cols - rows);
  result.distance = std::pow(assigned_cost + cutoff_power / options.alpha * unmatched, 1.0 / p);
  if (options.alpha != 2.0) {
    result.localisation = result.missed = result.false_targets = std::numeric_limits<double>::quiet_NaN();
    result.missed_count = result.false_count = -1;
    return result;
  }
  // Proposition 1: γ = the optimal pairs closer than c.
  int pairs = 0;
  for (int i = 0; i < rows; ++i) {
    const int j = column_of_row_[i];
    if (j >= 0 && (truth[i] - estimates[j]).norm() < c) {
      ++pairs;
      result.localisation += cost_[static_cast<std::size_t>(i) * cols + j];
    }
  }
  result.missed_count = rows - pairs;
  result.false_count = cols - pairs;
  result.missed = cutoff_power / 2.0 * result.missed_count;
  result.false_targets = cutoff_power / 2.0 * result.false_count;
  return result;
}

}  // namespace dabench
