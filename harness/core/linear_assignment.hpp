#pragma once
// Exact dense rectangular linear assignment: given an R×C cost matrix c (row-major), find
//
//   R ≤ C:  min over injections π: rows → columns of Σ_r c(r, π(r))
//           (every row gets a distinct column)
//   R > C:  min over injections σ: columns → rows of Σ_j c(σ(j), j)
//           (every column gets a distinct row; the R − C rows left over get column −1)
//
// — the same problem on min(R, C) pairs, solved on the transpose when R > C. An entry +∞ is a
// forbidden pair, never assigned: if no assignment avoids every forbidden pair, solve() returns
// false (never a wrong answer). Negative finite costs are allowed; NaN and −∞ entries are not.
//
// Algorithm: shortest augmenting paths with dual potentials (harness/core/
// shortest_augmenting_path.hpp, shared with the sparse MAP search of
// algorithms/single_scan/map_association.hpp): rows are added one at a time, each matched by one
// Dijkstra search over the reduced costs. The row potentials start at the row minima (u_r =
// min_j c(r, j), v = 0): this shifts each row by a constant, leaves the optimum unchanged and
// makes every reduced cost non-negative from the start, so negative costs need no copy.
// Infeasibility is exact: when the search from row r reaches no free column through finite
// entries, no matching avoiding the forbidden pairs covers rows 0..r. Chosen over an ε-scaling
// auction because it is exact for real costs and needs no tuning.
//
// Cost: O(min(R,C)² · max(R,C)) time (one search per row of the smaller side, each settling at
// most one column more than there are matched rows, at O(max(R,C)) per settled column);
// O(R + C) workspace, plus R·C for the transpose when R > C. The workspace only grows, so once
// it has reached the largest problem seen a solve allocates nothing (nor does `column_of_row`
// once its capacity suffices). Finite costs must be small enough that sums of a few of them do
// not overflow (|c| ≤ 1e300, say): an overflow to +∞ reads as a forbidden pair.
//
// Ties: deterministic for a given matrix — rows are added in index order; a search settles the
// column of least tentative distance, among equals a free column, then the lowest index
// (TieOrder::lowest_column: a constant square matrix gives the identity). Any optimum may be returned when several exist;
// the total is optimal up to floating-point rounding of the reduced costs.
//
// Used by the GOSPA metric (harness/tbd/gospa.hpp) and as the inner solver of Murty's k-best
// assignment (algorithms/assignment/murty.hpp) for MD-HMHT and k-best JPDA.
#include <vector>

#include "harness/core/shortest_augmenting_path.hpp"

namespace dabench {

class LinearAssignment {
 public:
  // `cost`: rows × cols entries, row-major (may be null when rows · cols = 0).
  // On success returns true, sets column_of_row (size rows: the column of each row, −1 for a row
  // left over when rows > cols) and total_cost (Σ of the assigned entries, in row order; 0 for
  // an empty problem). Returns false if every assignment uses a +∞ entry; column_of_row and
  // total_cost are then unspecified.
  // Throws std::invalid_argument if rows or cols is negative or an entry is NaN or −∞.
  [[nodiscard]] bool solve(const double* cost, int rows, int cols, std::vector<int>& column_of_row, double& total_cost);

 private:
  // The R ≤ C problem on `cost` (rows × cols, row-major); the matching in search_.
  [[nodiscard]] bool solve_wide(const double* cost, int rows, int cols);

  std::vector<double> transposed_;  // cols × rows copy when rows > cols
  ShortestAugmentingPath<TieOrder::lowest_column> search_;
};

}  // namespace dabench
