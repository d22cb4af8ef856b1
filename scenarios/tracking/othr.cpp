#include "scenarios/tracking/othr.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include <Eigen/Cholesky>
#include <fmt/format.h>

#include "harness/tracking/registry.hpp"

namespace dabench {

namespace {

// Table III: initial state (at the first scan) and lifetime as 1-based scans.
struct TableIIIRow {
  othr::GroundState state;
  int first, last;
};
const TableIIIRow kTableIII[OthrScenario::kTargets] = {
    {{1700.0, 0.10, 0.48, 8.7e-5}, 1, 20},
    {{1750.0, 0.10, 0.48, 8.7e-5}, 1, 20},
    {{1850.0, 0.20, 0.54, 8.7e-5}, 10, 30},
    {{1915.0, -0.20, 0.54, 8.7e-5}, 10, 30},
};

// Surveillance region in measurement space [r, ṙ, ζ] (Sec. IV-A1).
const Eigen::Vector3d kRegionLower{1500.0, -0.524, 0.428};
const Eigen::Vector3d kRegionUpper{2000.0, 0.524, 0.608};

// Per-coordinate NCV blocks for sampling period T: F₁ = [[1, T], [0, 1]] and the Cholesky
// factor of Q₁/q = [[T³/3, T²/2], [T²/2, T]].
Eigen::Matrix2d cv_transition(double T) { return (Eigen::Matrix2d() << 1.0, T, 0.0, 1.0).finished(); }
Eigen::Matrix2d cv_unit_covariance(double T) {
  return (Eigen::Matrix2d() << T * T * T / 3.0, T * T / 2.0, T * T / 2.0, T).finished();
}

bool inside_region(const Eigen::Vector3d& y) {
  return (y.array() >= kRegionLower.array()).all() && (y.array() <= kRegionUpper.array()).all();
}

// Per-thread buffer of one scan's measurements with their origins.
struct ScanBuffer {
  std::vector<std::pair<Eigen::Vector3d, MeasurementOrigin>> items;
};

}  // namespace

std::string OthrOptions::validate() const {
  if (!(pd > 0.0 && pd <= 1.0)) return fmt::format("pd = {} must be in (0, 1]", pd);
  if (!(clutter >= 0.0 && clutter <= 1e5)) return fmt::format("clutter = {} must be in [0, 1e5]", clutter);
  if (scans < 1 || scans > 1000) return fmt::format("scans = {} must be in 1..1000", scans);
  if (!(scan_interval > 0.0 && scan_interval <= 1000.0)) return fmt::format("scan_interval = {} must be in (0, 1000]", scan_interval);
  if (!(process_psd >= 0.0 && process_psd <= 1.0)) return fmt::format("process_psd = {} must be in [0, 1]", process_psd);
  return {};
}

othr::GroundState OthrScenario::initial_state(int target) { return kTableIII[target].state; }
int OthrScenario::first_scan(int target) { return kTableIII[target].first - 1; }
int OthrScenario::last_scan(int target) { return kTableIII[target].last - 1; }

OthrScenario::OthrScenario(const Options& options)
    : options_(options),
      sensor_(std::make_shared<const othr::OthrMeasurementModel>(kSigmaRange, kSigmaRangeRate, kSigmaAzimuth)) {}

void OthrScenario::generate(RandomStream& rng, TrackingScenarioSample& sample) const {
  const Options& o = options_;
  const int K = o.scans;
  const double T = o.scan_interval;
  const double q_g = o.process_psd;
  const double q_b = o.process_psd / (kReferenceGroundRange * kReferenceGroundRange);

  // The model the trackers know.
  TrackingProblem& problem = sample.problem;
  const Eigen::Matrix2d F1 = cv_transition(T);
  const Eigen::Matrix2d Q1 = cv_unit_covariance(T);
  problem.transition = Eigen::Matrix4d::Zero();
  problem.transition.block<2, 2>(0, 0) = F1;
  problem.transition.block<2, 2>(2, 2) = F1;
  problem.process_covariance = Eigen::Matrix4d::Zero();
  problem.process_covariance.block<2, 2>(0, 0) = q_g * Q1;
  problem.process_covariance.block<2, 2>(2, 2) = q_b * Q1;
  problem.scan_interval = T;
  problem.sensor = sensor_;
  problem.detection_probability.assign(othr::kPaths, o.pd);
  problem.clutter_mean = o.clutter;
  problem.region_lower = kRegionLower;
  problem.region_upper = kRegionUpper;

  // 1. Truth trajectories.
  TrackingTruth& truth = sample.truth;
  const Eigen::Matrix2d L1 = Q1.llt().matrixL();
  const double sqrt_q[2] = {std::sqrt(q_g), std::sqrt(q_b)};
  truth.targets.resize(kTargets);
  for (int i = 0; i < kTargets; ++i) {
    TrackingTruth::Target& target = truth.targets[i];
    target.states.setConstant(4, K, std::numeric_limits<double>::quiet_NaN());
    target.alive.assign(K, false);
    const int first = first_scan(i), last = std::min(last_scan(i), K - 1);
    if (first >= K) continue;
    Eigen::Vector4d x = initial_state(i);
    for (int k = first; k <= last; ++k) {
      if (k > first) {
        Eigen::Vector4d next = problem.transition * x;
        for (int c = 0; c < 2; ++c) {
          const Eigen::Vector2d z{rng.normal(), rng.normal()};
          next.segment<2>(2 * c) += sqrt_q[c] * (L1 * z);
        }
        x = next;
      }
      target.states.col(k) = x;
      target.alive[k] = true;
    }
  }

  // 2. Scans.
  thread_local ScanBuffer buffer;
  auto& items = buffer.items;
  const Eigen::Vector3d sigma{kSigmaRange, kSigmaRangeRate, kSigmaAzimuth};
  problem.scans.resize(K);
  truth.origin.resize(K);
  truth.detections = truth.dropped_detections = truth.clutter = 0;
  for (int k = 0; k < K; ++k) {
    items.clear();
    for (int i = 0; i < kTargets; ++i) {
      if (!truth.targets[i].alive[k]) continue;
      const othr::GroundState x = truth.targets[i].states.col(k);
      for (int tau = 0; tau < othr::kPaths; ++tau) {
        if (!rng.bernoulli(o.pd)) continue;
        Eigen::Vector3d y = othr::slant_measurement(x, othr::kPathTable[tau]);
        for (int c = 0; c < 3; ++c) y[c] += sigma[c] * rng.normal();
        ++truth.detections;
        if (inside_region(y)) items.push_back({y, {i, tau}});
        else ++truth.dropped_detections;
      }
    }
    const auto clutter = static_cast<int>(rng.poisson(o.clutter));
    truth.clutter += clutter;
    for (int j = 0; j < clutter; ++j) {
      Eigen::Vector3d y;
      for (int c = 0; c < 3; ++c) y[c] = rng.uniform(kRegionLower[c], kRegionUpper[c]);
      items.push_back({y, {}});
    }
    const int M = static_cast<int>(items.size());
    for (int j = M - 1; j > 0; --j) {
      const int pick = std::min(static_cast<int>(rng.uniform() * (j + 1)), j);
      std::swap(items[j], items[pick]);
    }
    problem.scans[k].resize(3, M);
    truth.origin[k].resize(M);
    for (int j = 0; j < M; ++j) {
      problem.scans[k].col(j) = items[j].first;
      truth.origin[k][j] = items[j].second;
    }
  }
}

DABENCH_REGISTER_TRACKING_SCENARIO(OthrScenario);

}  // namespace dabench
