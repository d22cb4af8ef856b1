#include "harness/single_scan/marginal_errors.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace dabench {

MarginalErrors marginal_errors(const MarginalTable& estimate, const MarginalTable& reference) {
  assert(estimate.targets() == reference.targets() && estimate.measurements() == reference.measurements());
  assert(estimate.targets() > 0);
  const int n = estimate.targets();
  const int columns = estimate.measurements() + 1;
  double sum_of_row_max = 0.0;
  double sum_abs = 0.0;
  for (int i = 0; i < n; ++i) {
    const double* a = estimate.row(i);
    const double* b = reference.row(i);
    double row_max = 0.0;
    for (int j = 0; j < columns; ++j) {
      const double difference = std::fabs(a[j] - b[j]);
      row_max = std::max(row_max, difference);
      sum_abs += difference;
    }
    sum_of_row_max += row_max;
  }
  return {sum_of_row_max / n, sum_abs / (static_cast<double>(n) * columns)};
}

}  // namespace dabench
