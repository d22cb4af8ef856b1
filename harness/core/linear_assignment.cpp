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
    column_of_row.assign(column_of_row_.begin(), column_of_row_.begin() + rows);
  } else {
    grow_buffer(transposed_, entries);
    for (int r = 0; r < rows; ++r) {
      const double* row_cost = cost + static_cast<std::size_t>(r) * cols;
      for (int c = 0; c < cols; ++c) transposed_[static_cast<std::size_t>(c) * rows + r] = row_cost[c];
    }
    if (!solve_wide(transposed_.data(), cols, rows)) return false;
    column_of_row.assign(rows, -1);
    for (int c = 0; c < cols; ++c) column_of_row[column_of_row_[c]] = c;
  }

  total_cost = 0.0;
  for (int r = 0; r < rows; ++r) {
    if (column_of_row[r] >= 0) total_cost += cost[static_cast<std::size_t>(r) * cols + column_of_row[r]];
  }
  return true;
}

bool LinearAssignment::solve_wide(const double* cost, int rows, int cols) {
  grow_buffer(row_dual_, rows);
  grow_buffer(column_of_row_, rows);
  grow_buffer(column_dual_, cols);
  grow_buffer(row_of_column_, cols);
  grow_buffer(path_row_, cols);
  grow_buffer(distance_, cols);
  grow_buffer(settled_, cols);
  visited_rows_.reserve(rows);
  settled_columns_.reserve(cols);

  // u_r = min_j c(r, j), v = 0: dual feasible (every reduced cost ≥ 0). A row of +∞ has no
  // allowed column at all.
  for (int r = 0; r < rows; ++r) {
    const double* row_cost = cost + static_cast<std::size_t>(r) * cols;
    row_dual_[r] = *std::min_element(row_cost, row_cost + cols);
    if (row_dual_[r] == kInfinity) return false;
    column_of_row_[r] = -1;
  }
  std::fill_n(column_dual_.begin(), cols, 0.0);
  std::fill_n(row_of_column_.begin(), cols, -1);
  for (int r = 0; r < rows; ++r) {
    if (!augment(cost, cols, r)) return false;
  }
  return true;
}

// Dijkstra from the free row `start` over reduced costs, settling one column at a time until a
// free column is settled (the sink); then Crouse's dual update, which keeps every reduced cost
// ≥ 0 and those of matched pairs = 0, and the augmentation along the predecessor rows.
bool LinearAssignment::augment(const double* cost, int cols, int start) {
  std::fill_n(distance_.begin(), cols, kInfinity);
  std::fill_n(settled_.begin(), cols, 0);
  visited_rows_.clear();
  settled_columns_.clear();
  double reached = 0.0;  // distance of the last settled column
  int row = start;
  int sink = -1;
  while (sink < 0) {
    visited_rows_.push_back(row);
    const double* row_cost = cost + static_cast<std::size_t>(row) * cols;
    const double base = reached - row_dual_[row];
    int best = -1;  // the closest unsettled column; among equals a free one, then the lowest index
    double lowest = kInfinity;
    for (int j = 0; j < cols; ++j) {
      if (settled_[j]) continue;
      const double candidate = base + row_cost[j] - column_dual_[j];  // +∞ for a forbidden pair
      if (candidate < distance_[j]) {
        distance_[j] = candidate;
        path_row_[j] = row;
      }
      if (distance_[j] < lowest ||
          (distance_[j] == lowest && best >= 0 && row_of_column_[j] < 0 && row_of_column_[best] >= 0)) {
        lowest = distance_[j];
        best = j;
      }
    }
    // Every unsettled column unreachable through finite arcs: no augmenting path exists, so
    // rows 0..start cannot all be matched. (An unsettled column always remains: each settled
    // column but the sink is matched, and fewer than cols columns are matched.)
    if (best < 0) return false;
    reached = lowest;
    settled_[best] = 1;
    settled_columns_.push_back(best);
    if (row_of_column_[best] < 0) {
      sink = best;
    } else {
      row = row_of_column_[best];
    }
  }

  row_dual_[start] += reached;
  for (const int r : visited_rows_) {
    if (r != start) row_dual_[r] += reached - distance_[column_of_row_[r]];
  }
  for (const int j : settled_columns_) column_dual_[j] -= reached - distance_[j];

  for (int column = sink;;) {
    const int r = path_row_[column];
    row_of_column_[column] = r;
    std::swap(column_of_row_[r], column);
    if (r == start) break;
  }
  return true;
}

}  // namespace dabench
