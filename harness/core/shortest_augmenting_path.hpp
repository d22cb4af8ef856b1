#pragma once
// The shortest-augmenting-path step that dabench's two linear assignment solvers share: the
// dense rectangular LinearAssignment (harness/core/linear_assignment.hpp: GOSPA, Murty's k-best
// for MD-HMHT and k-best JPDA) and the sparse per-cluster search for the MAP association event
// (algorithms/single_scan/map_association.hpp: `map` and MCMCDA's initial state).
//
// Method: the augmentation phase of Jonker & Volgenant (Computing 38, 1987) in the rectangular
// form of Crouse ("On implementing 2D rectangular assignment algorithms", IEEE TAES 52(4), 2016:
// its shortest augmenting path algorithm and dual update). Rows are matched one at a time; each
// by one Dijkstra search over the reduced costs c(r, j) − u_r − v_j ≥ 0 from the new row to the
// nearest free column, settling one column at a time; then the dual update, which keeps every
// reduced cost ≥ 0 and those of matched pairs = 0, and the augmentation along the predecessor
// rows. The caller makes the starting potentials dual feasible (every reduced cost ≥ 0).
//
// Ties, deterministic for a given problem: among the columns at the least tentative distance a
// free one is preferred, then the lowest column index (TieOrder::lowest_column: the dense
// solver, so a constant square matrix gives the identity) or the column reached first
// (TieOrder::first_reached: the sparse MAP search).
//
// Cost: per search, O(arcs of the visited rows + reached columns × settled columns). The
// workspace only grows, so once it has reached the largest problem seen a search allocates
// nothing.
#include <algorithm>
#include <cstddef>
#include <vector>

#include "harness/core/grow_buffer.hpp"
#include "harness/core/special_values.hpp"

namespace dabench {

enum class TieOrder { lowest_column, first_reached };

template <TieOrder kTies>
class ShortestAugmentingPath {
 public:
  // Sizes the state for `rows` × `columns`: potentials 0, nothing matched, no column reached.
  void reset(int rows, int columns) {
    grow_buffer(row_dual_, rows);
    grow_buffer(column_of_row_, rows);
    grow_buffer(column_dual_, columns);
    grow_buffer(row_of_column_, columns);
    grow_buffer(path_row_, columns);
    grow_buffer(distance_, columns);
    grow_buffer(settled_, columns);
    std::fill_n(row_dual_.begin(), rows, 0.0);
    std::fill_n(column_of_row_.begin(), rows, -1);
    std::fill_n(column_dual_.begin(), columns, 0.0);
    std::fill_n(row_of_column_.begin(), columns, -1);
    std::fill_n(distance_.begin(), columns, kInfinity);
    std::fill_n(settled_.begin(), columns, 0);
    reached_.reserve(columns);
    visited_rows_.reserve(rows);
    settled_columns_.reserve(columns);
  }

  void set_row_dual(int row, double value) { row_dual_[row] = value; }
  [[nodiscard]] int column_of_row(int row) const { return column_of_row_[row]; }

  // Matches the free row `start`, keeping every matched row matched. `for_each_arc(row, relax)`
  // calls relax(column, cost) for each arc of `row` (cost +∞: a forbidden pair, never used).
  // Returns false when no free column is reachable through finite arcs: then no matching of the
  // rows matched so far and `start` avoids the forbidden pairs (Berge), and the state is as before.
  template <class ForEachArc>
  [[nodiscard]] bool augment(int start, ForEachArc&& for_each_arc) {
    visited_rows_.clear();
    settled_columns_.clear();
    double reached = 0.0;  // distance of the last settled column
    int row = start;
    int sink = -1;
    while (sink < 0) {
      visited_rows_.push_back(row);
      const double base = reached - row_dual_[row];
      for_each_arc(row, [&](int column, double cost) {
        if (settled_[column]) return;
        const double candidate = base + cost - column_dual_[column];
        if (candidate < distance_[column]) {
          if (distance_[column] == kInfinity) reached_.push_back(column);
          distance_[column] = candidate;
          path_row_[column] = row;
        }
      });
      if (reached_.empty()) break;
      const std::size_t best = closest_reached();
      const int column = reached_[best];
      reached_.erase(reached_.begin() + static_cast<std::ptrdiff_t>(best));
      reached = distance_[column];
      settled_[column] = 1;
      settled_columns_.push_back(column);
      if (row_of_column_[column] < 0) {
        sink = column;
      } else {
        row = row_of_column_[column];
      }
    }
    if (sink >= 0) {
      row_dual_[start] += reached;
      for (const int r : visited_rows_) {
        if (r != start) row_dual_[r] += reached - distance_[column_of_row_[r]];
      }
      for (const int column : settled_columns_) column_dual_[column] -= reached - distance_[column];
      for (int column = sink;;) {
        const int r = path_row_[column];
        row_of_column_[column] = r;
        std::swap(column_of_row_[r], column);
        if (r == start) break;
      }
    }
    // Clear the search's marks on every column it touched, settled or only reached.
    for (const int column : settled_columns_) {
      settled_[column] = 0;
      distance_[column] = kInfinity;
    }
    for (const int column : reached_) distance_[column] = kInfinity;
    reached_.clear();
    return sink >= 0;
  }

 private:
  // The position in reached_ of the closest column: least distance, then free, then TieOrder.
  [[nodiscard]] std::size_t closest_reached() const {
    std::size_t best = 0;
    for (std::size_t f = 1; f < reached_.size(); ++f) {
      const int candidate = reached_[f];
      const int incumbent = reached_[best];
      const double d = distance_[candidate];
      const double b = distance_[incumbent];
      if (d != b) {
        if (d < b) best = f;
        continue;
      }
      const bool candidate_free = row_of_column_[candidate] < 0;
      const bool incumbent_free = row_of_column_[incumbent] < 0;
      if (candidate_free != incumbent_free) {
        if (candidate_free) best = f;
      } else if (kTies == TieOrder::lowest_column && candidate < incumbent) {
        best = f;
      }
    }
    return best;
  }

  std::vector<double> row_dual_;     // u
  std::vector<double> column_dual_;  // v
  std::vector<int> column_of_row_;   // −1: unmatched
  std::vector<int> row_of_column_;   // −1: free
  std::vector<int> path_row_;        // predecessor row of each reached column
  std::vector<double> distance_;     // tentative shortest-path cost per column (+∞ = unreached)
  std::vector<char> settled_;
  std::vector<int> reached_;         // reached, unsettled columns, in the order reached
  std::vector<int> visited_rows_;
  std::vector<int> settled_columns_;
};

}  // namespace dabench
