#pragma once
// A synthetic multiple-scan problem for timing (not the paper's `bearings` scenario): n targets
// uniform on [−100, 100]², each track a cloud of equally weighted particles drawn from
// N(truth, 20² I); four bearing sensors at the corners, scan t' from sensor t' mod 4; each
// target detected with Pd 0.9, bearing noise 1°, Poisson(1) false alarms uniform over the 90°
// the sensor sees. Factors by eq (33): 1 − Pd for a miss, f(z | x) Pd / λ_fa for a measurement,
// with λ_fa = 1 / (π/2) per radian.
#include <cmath>
#include <numbers>

#include "harness/multi_scan_problem.hpp"
#include "harness/random_stream.hpp"

namespace dabench::bench {

inline MultiScanProblem synthetic_bearings_problem(int targets, int scans, int particles, std::uint64_t seed) {
  constexpr double kPd = 0.9;
  constexpr double kSigma = std::numbers::pi / 180.0;  // 1°
  constexpr double kClutterDensity = 1.0 / (std::numbers::pi / 2.0);
  const double corner[4][2] = {{-100, -100}, {100, -100}, {100, 100}, {-100, 100}};
  RandomStream random(seed, 0, 0);
  std::vector<double> truth_x(targets), truth_y(targets);
  MultiScanProblem problem;
  std::vector<std::vector<double>> px(targets), py(targets);
  for (int i = 0; i < targets; ++i) {
    truth_x[i] = random.uniform(-100, 100);
    truth_y[i] = random.uniform(-100, 100);
    for (int p = 0; p < particles; ++p) {
      px[i].push_back(truth_x[i] + 20.0 * random.normal());
      py[i].push_back(truth_y[i] + 20.0 * random.normal());
    }
    problem.prior.push_back(Vector::Ones(particles));
  }
  auto wrap = [](double angle) { return std::remainder(angle, 2.0 * std::numbers::pi); };
  for (int t = 0; t < scans; ++t) {
    const double* sensor = corner[t % 4];
    const double facing = std::atan2(-sensor[1], -sensor[0]);  // towards the centre; sees ±45°
    std::vector<double> bearing;
    for (int i = 0; i < targets; ++i) {
      if (random.uniform() < kPd) {
        bearing.push_back(std::atan2(truth_y[i] - sensor[1], truth_x[i] - sensor[0]) + kSigma * random.normal());
      }
    }
    const std::int64_t clutter = random.poisson(1.0);
    for (std::int64_t k = 0; k < clutter; ++k) bearing.push_back(facing + random.uniform(-0.25, 0.25) * std::numbers::pi);
    ScanFactors scan;
    scan.measurements = static_cast<int>(bearing.size());
    for (int i = 0; i < targets; ++i) {
      RowMatrix factor(particles, scan.measurements + 1);
      for (int p = 0; p < particles; ++p) {
        const double predicted = std::atan2(py[i][p] - sensor[1], px[i][p] - sensor[0]);
        factor(p, 0) = 1.0 - kPd;
        for (int j = 0; j < scan.measurements; ++j) {
          const double residual = wrap(bearing[j] - predicted) / kSigma;
          factor(p, j + 1) = std::exp(-0.5 * residual * residual) / (std::sqrt(2.0 * std::numbers::pi) * kSigma) * kPd /
                             kClutterDensity;
        }
      }
      scan.factor.push_back(factor);
    }
    problem.scans.push_back(scan);
  }
  return problem;
}

}  // namespace dabench::bench
