#pragma once
// The cost matrices of the assignment tests (test_linear_assignment, test_murty): rows × cols
// costs, row-major, where +∞ forbids a pair.
#include <cstddef>
#include <limits>
#include <vector>

namespace dabench::test {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

struct CostMatrix {
  int rows = 0;
  int cols = 0;
  std::vector<double> cost;  // rows × cols, row-major
  double at(int r, int c) const { return cost[static_cast<std::size_t>(r) * cols + c]; }
};

}  // namespace dabench::test
