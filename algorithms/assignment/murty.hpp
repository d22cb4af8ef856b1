#pragma once
// Murty's ranked assignment: the k best association events of a 2-D assignment problem with
// misses, in ascending cost, for a hypothesis-oriented MHT (Cox & Hingorani, PAMI 18(2) 1996)
// such as MD-HMHT, and for k-best JPDA (algorithms/single_scan/kbest_jpda.hpp). The problem:
// R rows (targets, or (target, path) pseudo-targets), C columns (measurements), cost(r, j) of
// row r taking column j and miss_cost(r) of row r taking none; an event gives each row one
// column or a miss, every column to at most one row (a column no row takes is clutter, cost 0:
// costs are relative to "all clutter"). +∞ forbids a pair, or a
// row's miss. Cost of an event = Σ over rows, in row order, of its entries — computed the same
// way for every event, so equal events have bitwise equal costs.
//
// Method: Murty (Oper. Res. 16, 1968) as in Miller, Stone & Cox (1997): a subproblem is a set of
// forced pairs and a set of forbidden pairs; its best event is found by the exact solver
// LinearAssignment (harness/core/linear_assignment.hpp) on the free rows × (free columns + one
// private miss column per free row, +∞ off the diagonal): the miss columns make "unassigned"
// an ordinary choice that can itself be forbidden. The best event of the subproblem popped from
// a best-first heap is output, and its subproblem partitioned by its free rows r_1 < ... < r_m
// into m children: child t forces r_u → s(r_u) for u < t and forbids r_t → s(r_t). The children
// partition the parent's events minus s, so every event is output once and in cost order.
// Not implemented: Miller-Stone-Cox's dual reuse and lower-bound pruning (clusters of MD-HMHT
// are tiny; see docs/models/md-hmht.md, "Cost").
//
// Cost: at most k · R subproblems, each O(R (C + R)) to build and O(R² (C + R)) to solve.
// Ties: deterministic for a given input — the heap pops the least cost, among equal costs the
// subproblem created first. Memory: node constraints and solutions live in flat arenas that only
// grow, so a MurtyRanking reused on problems no larger than before allocates nothing.
//
// Independent clusters: the events of a problem whose rows and columns split into clusters with
// no finite pair across them are the products of per-cluster events, with costs adding. Rank
// each cluster with MurtyRanking and combine the lists with RankedListMerge (below): this equals
// one Murty on the whole problem (tests/assignment/test_murty.cpp), at far less cost.
#include <cstddef>
#include <span>
#include <vector>

#include "harness/core/linear_assignment.hpp"

namespace dabench {

// A ranked list of events of one problem: event i has cost(i) and columns(i), rows() entries,
// the column of each row or −1 for a miss. Storage is flat and reused by clear().
class RankedAssignments {
 public:
  int rows() const { return rows_; }
  int size() const { return static_cast<int>(costs_.size()); }
  double cost(int i) const { return costs_[static_cast<std::size_t>(i)]; }
  std::span<const double> costs() const { return costs_; }
  std::span<const int> columns(int i) const {
    return {columns_.data() + static_cast<std::size_t>(i) * static_cast<std::size_t>(rows_),
            static_cast<std::size_t>(rows_)};
  }

  void clear(int rows);
  void push(double cost, std::span<const int> columns);

 private:
  int rows_ = 0;
  std::vector<double> costs_;
  std::vector<int> columns_;
};

class MurtyRanking {
 public:
  // `cost`: rows × cols, row-major (may be null when rows · cols = 0); `miss_cost`: rows entries
  // (may be null when rows = 0). Replaces `out` with the min(k, number of feasible events) best
  // events in ascending cost (none if every event uses a +∞ entry). An empty problem (rows = 0)
  // has one event, of cost 0.
  // Throws InputError (one line) if k < 1, rows or cols is negative, or an entry is NaN or −∞.
  void solve(const double* cost, const double* miss_cost, int rows, int cols, int k, RankedAssignments& out);

 private:
  struct Pair {
    int row;
    int column;  // −1 = the row's miss
  };
  struct Node {
    double cost;
    std::size_t solution;     // offset of its rows entries in solutions_
    std::size_t constraints;  // offset in constraints_: `forced` pairs, then `forbidden` pairs
    int forced;
    int forbidden;
  };

  // Best event of the subproblem whose constraints are constraints_[offset ...]; on success
  // appends a node (solution, cost) and returns true.
  [[nodiscard]] bool solve_subproblem(std::size_t constraints, int forced, int forbidden);
  double event_cost(const int* columns) const;

  const double* cost_ = nullptr;
  const double* miss_cost_ = nullptr;
  int rows_ = 0;
  int cols_ = 0;

  LinearAssignment solver_;
  std::vector<Node> nodes_;
  std::vector<int> heap_;           // node indices, best on top
  std::vector<Pair> constraints_;   // arena of every node's constraints
  std::vector<int> solutions_;      // arena of every node's event (rows entries each)
  std::vector<double> matrix_;      // the subproblem's reduced cost matrix
  std::vector<int> forced_column_;  // per row: its forced column, −1 miss, kFree if free
  std::vector<int> partition_rows_;  // the popped node's free rows
  std::vector<int> free_rows_;
  std::vector<int> free_columns_;
  std::vector<int> row_index_;      // row → index among free rows (−1 if forced)
  std::vector<int> column_index_;   // column → index among free columns (−1 if taken)
  std::vector<int> column_of_row_;
  std::vector<int> event_;
};

// The k best combinations of one entry from each of L ranked lists (each ascending), by the sum
// of the chosen entries — e.g. the k best events of a problem split into independent clusters,
// from each cluster's MurtyRanking list. Best-first search: combination c's successors raise one
// index at a position p ≥ the last position where c is nonzero, so each combination has one
// predecessor and is generated once. Sums are taken in list order; ties pop in order of
// creation. Cost O(k L log(k L)). An empty list (an infeasible cluster) gives no combination;
// no lists give one empty combination of cost 0.
class RankedListMerge {
 public:
  // Replaces `total` (ascending) and `choices` (size() × L, the index chosen in each list).
  // Throws InputError if k < 1.
  void merge(std::span<const std::span<const double>> lists, int k, std::vector<double>& total,
             std::vector<int>& choices);

 private:
  struct Entry {
    double total;
    std::size_t choice;  // offset of its L indices in choices_
    int last;            // last position with a nonzero index (0 for the first combination)
  };
  std::vector<Entry> entries_;
  std::vector<int> heap_;
  std::vector<int> choices_;
};

}  // namespace dabench
