#include "harness/core/linear_assignment.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>

#include "harness/core/grow_buffer.hpp"
#include "harness/core/special_values.hpp"

namespace dabench {

bool LinearAssignment::solve(const double* cost, int rows, int cols, std::vector<int>& column_of_row,
                             double& total_cost) {
  if (rows < 0 || cols < 0) throw std::invalid_argument("linear assignment: negative matrix size");
  const std::size_t entries = static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols);
  for (std::size_t k = 0; k < entries; ++k) {
    if (std::isnan(cost[k]) || cost[k] == -kInfinity) {
      throw std::invalid_argument("linear assignment: cost(" + std::to_string(k / cols) + ", " +
                                  std::to_string(k % cols) + ") is " + (std::isnan(cost[k]) ? "NaN" : "-inf"));
    }
  }

  if (rows <= cols) {
    if (!solve_wide(cost, rows, cols)) return false;
    column_of_row.resize(rows);
    for (int r = 0; r < rows; ++r) column_of_row[r] = search_.column_of_row(r);
  } else {
    grow_buffer(transposed_, entries);
    for (int r = 0; r < rows; ++r) {
      const double* row_cost = cost + static_cast<std::size_t>(r) * cols;
      for (int c = 0; c < cols; ++c) transposed_[static_cast<std::size_t>(c) * rows + r] = row_cost[c];
    }
    if (!solve_wide(transposed_.data(), cols, rows)) return false;
    column_of_row.assign(rows, -1);
    for (int c = 0; c < cols; ++c) column_of_row[search_.column_of_row(c)] = c;
  }

  total_cost = 0.0;
  for (int r = 0; r < rows; ++r) {
    if (column_of_row[r] >= 0) total_cost += cost[static_cast<std::size_t>(r) * cols + column_of_row[r]];
  }
  return true;
}

bool LinearAssignment::solve_wide(const double* cost, int rows, int cols) {
  search_.reset(rows, cols);
  // u_r = min_j c(r, j), v = 0: dual feasible (every reduced cost ≥ 0). A row of +∞ has no
  // allowed column at all.
  for (int r = 0; r < rows; ++r) {
    const double* row_cost = cost + static_cast<std::size_t>(r) * cols;
    const double lowest = *std::min_element(row_cost, row_cost + cols);
    if (lowest == kInfinity) return false;
    search_.set_row_dual(r, lowest);
  }
  const auto dense_row = [cost, cols](int row, auto&& relax) {
    const double* row_cost = cost + static_cast<std::size_t>(row) * cols;
    for (int j = 0; j < cols; ++j) relax(j, row_cost[j]);
  };
  for (int r = 0; r < rows; ++r) {
    if (!search_.augment(r, dense_row)) return false;
  }
  return true;
}

}  // namespace dabench
