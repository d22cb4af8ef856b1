#include "algorithms/assignment/murty.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "harness/core/errors.hpp"
#include "harness/core/grow_buffer.hpp"
#include "harness/core/special_values.hpp"

namespace dabench {

namespace {

constexpr int kFree = -2;  // forced_column_ of a row with no forced pair

void check_entry(double value, const char* what, int row, int column) {
  if (std::isnan(value) || value == -kInfinity) {
    std::string where = std::string(what) + "(" + std::to_string(row);
    if (column >= 0) where += ", " + std::to_string(column);
    throw InputError("murty: " + where + ") is " + (std::isnan(value) ? "NaN" : "-inf") +
                     " (costs must be finite or +inf)");
  }
}

void check_k(int k, const char* who) {
  if (k < 1) throw InputError(std::string(who) + ": k must be at least 1 (got " + std::to_string(k) + ")");
}

}  // namespace

void RankedAssignments::clear(int rows) {
  rows_ = rows;
  costs_.clear();
  columns_.clear();
}

void RankedAssignments::push(double cost, std::span<const int> columns) {
  costs_.push_back(cost);
  columns_.insert(columns_.end(), columns.begin(), columns.end());
}

void MurtyRanking::solve(const double* cost, const double* miss_cost, int rows, int cols, int k,
                         RankedAssignments& out) {
  check_k(k, "murty");
  if (rows < 0 || cols < 0) {
    throw InputError("murty: negative problem size (" + std::to_string(rows) + " x " + std::to_string(cols) + ")");
  }
  for (int r = 0; r < rows; ++r) {
    check_entry(miss_cost[r], "miss_cost", r, -1);
    for (int j = 0; j < cols; ++j) check_entry(cost[static_cast<std::size_t>(r) * cols + j], "cost", r, j);
  }
  cost_ = cost;
  miss_cost_ = miss_cost;
  rows_ = rows;
  cols_ = cols;
  out.clear(rows);
  nodes_.clear();
  heap_.clear();
  constraints_.clear();
  solutions_.clear();
  grow_buffer(forced_column_, rows);
  grow_buffer(row_index_, rows);
  grow_buffer(column_index_, cols);
  grow_buffer(event_, rows);

  // The heap's "less": a is worse than b (higher cost; among equal costs, created later).
  const auto worse = [this](int a, int b) {
    const double ca = nodes_[a].cost;
    const double cb = nodes_[b].cost;
    return ca > cb || (ca == cb && a > b);
  };
  if (solve_subproblem(0, 0, 0)) heap_.push_back(0);

  while (!heap_.empty()) {
    std::pop_heap(heap_.begin(), heap_.end(), worse);
    const Node node = nodes_[heap_.back()];
    heap_.pop_back();
    out.push(node.cost, {solutions_.data() + node.solution, static_cast<std::size_t>(rows)});
    if (out.size() == k) break;

    // Partition over the node's free rows r_1 < ... < r_m: child t forces r_u -> s(r_u) for
    // u < t and forbids r_t -> s(r_t), keeping the node's forbidden pairs on rows r_t..r_m.
    std::fill_n(forced_column_.begin(), rows, kFree);
    for (int f = 0; f < node.forced; ++f) forced_column_[constraints_[node.constraints + f].row] = 0;
    partition_rows_.clear();
    for (int row = 0; row < rows; ++row) {
      if (forced_column_[row] == kFree) partition_rows_.push_back(row);
    }
    for (std::size_t t = 0; t < partition_rows_.size(); ++t) {
      const int row = partition_rows_[t];
      const std::size_t offset = constraints_.size();
      for (int f = 0; f < node.forced; ++f) {
        const Pair pair = constraints_[node.constraints + f];
        constraints_.push_back(pair);
      }
      for (std::size_t u = 0; u < t; ++u) {
        const int earlier = partition_rows_[u];
        constraints_.push_back({earlier, solutions_[node.solution + earlier]});
      }
      int forbidden = 0;
      for (int f = 0; f < node.forbidden; ++f) {
        const Pair pair = constraints_[node.constraints + node.forced + f];
        if (pair.row < row) continue;
        constraints_.push_back(pair);
        ++forbidden;
      }
      constraints_.push_back({row, solutions_[node.solution + row]});
      ++forbidden;
      if (solve_subproblem(offset, node.forced + static_cast<int>(t), forbidden)) {
        heap_.push_back(static_cast<int>(nodes_.size()) - 1);
        std::push_heap(heap_.begin(), heap_.end(), worse);
      } else {
        constraints_.resize(offset);
      }
    }
  }
}

bool MurtyRanking::solve_subproblem(std::size_t constraints, int forced, int forbidden) {
  std::fill_n(forced_column_.begin(), rows_, kFree);
  std::fill_n(column_index_.begin(), cols_, 0);
  for (int f = 0; f < forced; ++f) {
    const Pair pair = constraints_[constraints + f];
    forced_column_[pair.row] = pair.column;
    if (pair.column >= 0) column_index_[pair.column] = -1;
  }
  free_rows_.clear();
  for (int r = 0; r < rows_; ++r) {
    row_index_[r] = -1;
    if (forced_column_[r] != kFree) continue;
    row_index_[r] = static_cast<int>(free_rows_.size());
    free_rows_.push_back(r);
  }
  free_columns_.clear();
  for (int j = 0; j < cols_; ++j) {
    if (column_index_[j] < 0) continue;
    column_index_[j] = static_cast<int>(free_columns_.size());
    free_columns_.push_back(j);
  }

  // Free rows × (free columns, then one private miss column per free row).
  const int n = static_cast<int>(free_rows_.size());
  const int c = static_cast<int>(free_columns_.size());
  const int width = c + n;
  grow_buffer(matrix_, static_cast<std::size_t>(n) * static_cast<std::size_t>(width));
  for (int i = 0; i < n; ++i) {
    const double* source = cost_ + static_cast<std::size_t>(free_rows_[i]) * cols_;
    double* target = matrix_.data() + static_cast<std::size_t>(i) * width;
    for (int j = 0; j < c; ++j) target[j] = source[free_columns_[j]];
    std::fill_n(target + c, n, kInfinity);
    target[c + i] = miss_cost_[free_rows_[i]];
  }
  for (int f = 0; f < forbidden; ++f) {
    const Pair pair = constraints_[constraints + forced + f];
    const int i = row_index_[pair.row];
    const int j = pair.column < 0 ? c + i : column_index_[pair.column];
    if (i >= 0 && j >= 0) matrix_[static_cast<std::size_t>(i) * width + j] = kInfinity;
  }
  double total = 0.0;
  if (!solver_.solve(matrix_.data(), n, width, column_of_row_, total)) return false;

  for (int r = 0; r < rows_; ++r) {
    const int i = row_index_[r];
    event_[r] = i < 0 ? forced_column_[r] : (column_of_row_[i] < c ? free_columns_[column_of_row_[i]] : -1);
  }
  const std::size_t solution = solutions_.size();
  solutions_.insert(solutions_.end(), event_.begin(), event_.begin() + rows_);
  nodes_.push_back({event_cost(event_.data()), solution, constraints, forced, forbidden});
  return true;
}

double MurtyRanking::event_cost(const int* columns) const {
  double total = 0.0;
  for (int r = 0; r < rows_; ++r) {
    total += columns[r] >= 0 ? cost_[static_cast<std::size_t>(r) * cols_ + columns[r]] : miss_cost_[r];
  }
  return total;
}

void RankedListMerge::merge(std::span<const std::span<const double>> lists, int k, std::vector<double>& total,
                            std::vector<int>& choices) {
  check_k(k, "ranked list merge");
  total.clear();
  choices.clear();
  const std::size_t count = lists.size();
  for (const auto& list : lists) {
    if (list.empty()) return;
  }
  entries_.clear();
  heap_.clear();
  choices_.clear();

  const auto sum = [&](std::size_t offset) {
    double value = 0.0;
    for (std::size_t l = 0; l < count; ++l) value += lists[l][static_cast<std::size_t>(choices_[offset + l])];
    return value;
  };
  const auto worse = [this](int a, int b) {
    const double ta = entries_[a].total;
    const double tb = entries_[b].total;
    return ta > tb || (ta == tb && a > b);
  };
  choices_.assign(count, 0);
  entries_.push_back({sum(0), 0, 0});
  heap_.push_back(0);

  while (!heap_.empty()) {
    std::pop_heap(heap_.begin(), heap_.end(), worse);
    const Entry entry = entries_[heap_.back()];
    heap_.pop_back();
    total.push_back(entry.total);
    choices.insert(choices.end(), choices_.begin() + static_cast<std::ptrdiff_t>(entry.choice),
                   choices_.begin() + static_cast<std::ptrdiff_t>(entry.choice + count));
    if (static_cast<int>(total.size()) == k) break;
    for (std::size_t p = static_cast<std::size_t>(entry.last); p < count; ++p) {
      if (static_cast<std::size_t>(choices_[entry.choice + p]) + 1 >= lists[p].size()) continue;
      const std::size_t offset = choices_.size();
      for (std::size_t l = 0; l < count; ++l) {
        const int index = choices_[entry.choice + l];
        choices_.push_back(index);
      }
      ++choices_[offset + p];
      entries_.push_back({sum(offset), offset, static_cast<int>(p)});
      heap_.push_back(static_cast<int>(entries_.size()) - 1);
      std::push_heap(heap_.begin(), heap_.end(), worse);
    }
  }
}

}  // namespace dabench
