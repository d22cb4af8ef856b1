#pragma once
// One-sample Kolmogorov–Smirnov statistic against Uniform(0, 1):
//   D = max_k max(k/n − u_(k), u_(k) − (k−1)/n)  over the sorted sample u_(1..n).
// The asymptotic 5 % critical value is 1.358/√n (Kolmogorov's distribution; accurate for
// n ≥ 35); 1 % is 1.628/√n.
#include <algorithm>
#include <cmath>
#include <vector>

namespace dabench::test {

inline double ks_uniform_statistic(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const double n = static_cast<double>(values.size());
  double d = 0.0;
  for (std::size_t k = 0; k < values.size(); ++k) {
    const double u = std::clamp(values[k], 0.0, 1.0);
    d = std::max({d, (static_cast<double>(k) + 1.0) / n - u, u - static_cast<double>(k) / n});
  }
  return d;
}

inline double ks_critical_5_percent(std::size_t n) { return 1.358 / std::sqrt(static_cast<double>(n)); }

}  // namespace dabench::test
