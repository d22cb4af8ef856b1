#pragma once
// Helpers of the scenario tests (test_othr_scenario, test_tbd_scenario): a scenario built from
// `key = value` settings as the registry builds it, and running moments of its draws.
#include <cmath>
#include <vector>

#include "harness/core/params.hpp"

namespace dabench::test {

// `Scenario` with its options read from `settings` (errors name the scenario).
template <class Scenario>
Scenario scenario_from(const std::vector<KeyValue>& settings) {
  return Scenario(make_options<typename Scenario::Options>(settings, Scenario::kName));
}

// Count, mean, and unbiased variance and standard deviation of the values added.
struct RunningMoments {
  double n = 0.0, sum = 0.0, squares = 0.0;
  void add(double v) {
    n += 1.0;
    sum += v;
    squares += v * v;
  }
  double mean() const { return sum / n; }
  double variance() const { return (squares - sum * sum / n) / (n - 1.0); }
  double sd() const { return std::sqrt(variance()); }
};

}  // namespace dabench::test
