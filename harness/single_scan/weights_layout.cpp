#include "harness/single_scan/weights_layout.hpp"

#include <cmath>
#include <limits>
#include <utility>

#include <fmt/format.h>

#include "harness/core/errors.hpp"

namespace dabench {
namespace {

constexpr std::pair<WeightsLayout, const char*> kLayouts[] = {
    {WeightsLayout::psi, "psi"}, {WeightsLayout::stonesoup, "stonesoup"},
    {WeightsLayout::tcl, "tcl"}, {WeightsLayout::matlab, "matlab"}};

// The user's entries, checked as they are read: weights (or log weights) in their own domain.
class Entries {
 public:
  Entries(const Eigen::Ref<const RowMatrix>& matrix, bool log, const std::string& where) : matrix_(matrix), log_(log), where_(where) {}

  // The entry at (row, column), 0-based: finite and >= 0 (log: not NaN, not +inf).
  double weight(Eigen::Index row, Eigen::Index column) const {
    const double value = matrix_(row, column);
    if (std::isnan(value) || (std::isinf(value) && !(log_ && value < 0.0))) {
      throw error(row, column, fmt::format("{} {} is not finite", log_ ? "log weight" : "weight", value));
    }
    if (!log_ && value < 0.0) throw error(row, column, fmt::format("weight {} is negative", value));
    return value;
  }
  // A clutter weight, which must not be 0 (a measurement that must come from a target is not
  // a model dabench's algorithms take).
  double clutter_weight(Eigen::Index row, Eigen::Index column) const {
    const double value = weight(row, column);
    if (is_zero(value)) throw error(row, column, "the clutter weight is 0 (it must be > 0)");
    return value;
  }
  bool is_zero(double value) const { return log_ ? value == -std::numeric_limits<double>::infinity() : value == 0.0; }
  // w / (w_miss · w_clutter), each in the entries' domain, as a weight.
  double relative(double value, double miss, double clutter) const {
    return log_ ? std::exp(value - miss - clutter) : value / miss / clutter;
  }
  InputError error(Eigen::Index row, Eigen::Index column, const std::string& reason) const {
    return InputError(fmt::format("{}:{}: column {}: {}", where_, row + 1, column + 1, reason));
  }

 private:
  const Eigen::Ref<const RowMatrix>& matrix_;
  bool log_;
  const std::string& where_;
};

}  // namespace

const char* weights_layout_shape(WeightsLayout layout) {
  switch (layout) {
    case WeightsLayout::psi: return "targets x measurements";
    case WeightsLayout::stonesoup: return "targets x (1 + measurements)";
    case WeightsLayout::tcl: return "targets x (measurements + targets)";
    case WeightsLayout::matlab: return "(1 + measurements) x (1 + targets)";
  }
  return "?";
}

WeightsLayout parse_weights_layout(std::string_view name) {
  for (const auto& [layout, layout_name] : kLayouts) {
    if (name == layout_name) return layout;
  }
  throw InputError(fmt::format("unknown weights layout '{}' (psi, stonesoup, tcl or matlab)", name));
}

const char* weights_layout_name(WeightsLayout layout) {
  for (const auto& [known, name] : kLayouts) {
    if (known == layout) return name;
  }
  return "?";
}

SingleScanProblem problem_from_weights(const Eigen::Ref<const RowMatrix>& matrix, const WeightsFormat& format,
                                       const std::string& where) {
  const Entries entries(matrix, format.log, where);
  const Eigen::Index rows = matrix.rows(), columns = matrix.cols();
  const char* name = weights_layout_name(format.layout);
  // n, m and where w_ij, w_i0 and w_0j sit in the user's matrix.
  Eigen::Index n = rows, m = columns;
  switch (format.layout) {
    case WeightsLayout::psi: break;
    case WeightsLayout::stonesoup:
      if (columns < 1) throw InputError(fmt::format("{}: the {} layout needs a missed-detection column", where, name));
      m = columns - 1;
      break;
    case WeightsLayout::tcl:
      if (columns < rows) {
        throw InputError(fmt::format("{}: the {} layout needs measurements + targets columns: {} columns for {} targets",
                                     where, name, columns, rows));
      }
      m = columns - rows;
      break;
    case WeightsLayout::matlab:
      if (rows < 1 || columns < 1) throw InputError(fmt::format("{}: the {} layout needs a row and a column of side weights", where, name));
      n = columns - 1;
      m = rows - 1;
      break;
  }
  if (n < 1) throw InputError(fmt::format("{}: the {} layout holds no target", where, name));
  // Side weights in the entries' domain; the identity (1, or 0 in log form) where a layout has none
  // (ψ has neither: no vectors then).
  const double none = format.log ? 0.0 : 1.0;
  const bool has_miss = format.layout != WeightsLayout::psi, has_clutter = format.layout == WeightsLayout::matlab;
  Vector miss = Vector::Constant(has_miss ? n : 0, none), clutter = Vector::Constant(has_clutter ? m : 0, none);
  for (Eigen::Index i = 0; i < n; ++i) {
    if (format.layout == WeightsLayout::stonesoup) miss[i] = entries.weight(i, 0);
    if (format.layout == WeightsLayout::matlab) miss[i] = entries.weight(0, i + 1);
    if (format.layout == WeightsLayout::tcl) {
      for (Eigen::Index k = 0; k < n; ++k) {
        if (k == i) {
          miss[i] = entries.weight(i, m + k);
        } else if (!entries.is_zero(entries.weight(i, m + k))) {
          throw entries.error(i, m + k, "an off-diagonal entry of the missed-detection block must be 0");
        }
      }
    }
  }
  if (format.layout == WeightsLayout::matlab) {
    for (Eigen::Index j = 0; j < m; ++j) clutter[j] = entries.clutter_weight(j + 1, 0);
  }
  // What each row is divided by: its missed-detection weight, or for a target that must be
  // detected (w_i0 = 0) its largest weight, which keeps the row in range and leaves the
  // posterior unchanged (every event takes exactly one of the row's entries).
  // Where w_ij sits in the user's matrix.
  const auto position = [&format](Eigen::Index i, Eigen::Index j) {
    if (format.layout == WeightsLayout::matlab) return std::pair<Eigen::Index, Eigen::Index>{j + 1, i + 1};
    return std::pair<Eigen::Index, Eigen::Index>{i, format.layout == WeightsLayout::stonesoup ? j + 1 : j};
  };
  Vector row_divisor = miss;
  for (Eigen::Index i = 0; i < miss.size(); ++i) {
    if (!entries.is_zero(miss[i])) continue;
    for (Eigen::Index j = 0; j < m; ++j) {
      const auto [row, column] = position(i, j);
      const double w = entries.weight(row, column);
      if (j == 0 || w > row_divisor[i]) row_divisor[i] = w;
    }
    if (m == 0 || entries.is_zero(row_divisor[i])) row_divisor[i] = none;
  }
  SingleScanProblem problem;
  problem.psi.resize(n, m);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < m; ++j) {
      const auto [row, column] = position(i, j);
      const double psi = entries.relative(entries.weight(row, column), has_miss ? row_divisor[i] : none, has_clutter ? clutter[j] : none);
      if (!std::isfinite(psi)) throw entries.error(row, column, "the weight relative to its missed detection and clutter overflows");
      problem.psi(i, j) = psi;
    }
  }
  // Targets with a zero missed-detection weight keep it (w_i0 = 0 beside the others' 1): the
  // problem says they must be detected (SingleScanProblem::must_detect).
  bool must_detect = false;
  for (Eigen::Index i = 0; i < miss.size(); ++i) must_detect = must_detect || entries.is_zero(miss[i]);
  if (must_detect) {
    problem.miss_weight = Vector::Ones(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      if (entries.is_zero(miss[i])) problem.miss_weight[i] = 0.0;
    }
  }
  return problem;
}

}  // namespace dabench
