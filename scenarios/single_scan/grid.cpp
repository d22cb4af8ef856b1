#include "scenarios/single_scan/grid.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "harness/single_scan/registry.hpp"

namespace dabench {

namespace {

constexpr std::int64_t kMaxTargets = 100000;
constexpr double kMaxExpectedFalseAlarms = 1e7;

Eigen::Vector2d normal2(RandomStream& rng) {
  const double x = rng.normal();
  const double y = rng.normal();
  return {x, y};
}

struct PredictedTrack {
  Eigen::Vector2d estimate;  // ẑ_i
  double inverse_s;          // S_i = s_i·I2, so (z − ẑ)'S⁻¹(z − ẑ) = |z − ẑ|²/s_i
  double scale;              // Pd / (λ_fa (1 − Pd) 2π sqrt(det S_i)), det S_i = s_i²
};

// Per-thread buffers reused across trials (generate() is const and called concurrently).
struct GridScratch {
  std::vector<PredictedTrack> tracks;
  std::vector<Eigen::Vector2d> points;  // measurements: detections, then false alarms; shuffled
  std::vector<int> origin;              // per point: target index, or −1 for a false alarm
  std::vector<int> column;              // per point: 1-based column of the final ψ, 0 if dropped
  RowMatrix psi;                        // n × M, before dropping ungated columns
};

}  // namespace

std::string GridOptions::validate() const {
  if (rows < 1) return fmt::format("rows = {} must be >= 1", rows);
  if (cols < 1) return fmt::format("cols = {} must be >= 1", cols);
  if (static_cast<std::int64_t>(rows) * cols > kMaxTargets) {
    return fmt::format("rows*cols = {} must be <= {} (every target is gated against every measurement)",
                       static_cast<std::int64_t>(rows) * cols, kMaxTargets);
  }
  if (!(spacing >= 0.0)) return fmt::format("spacing = {} must be >= 0", spacing);
  if (!(pd > 0.0 && pd < 1.0)) return fmt::format("pd = {} must be in (0, 1) (eq (11) divides by 1 - pd)", pd);
  if (!(lambda_fa > 0.0)) return fmt::format("lambda_fa = {} must be > 0 (eq (11) divides by it)", lambda_fa);
  if (!(r > 0.0)) return fmt::format("r = {} must be > 0 (R = r*I must be invertible)", r);
  if (!(q >= 0.0)) return fmt::format("q = {} must be >= 0", q);
  if (!(T > 0.0)) return fmt::format("T = {} must be > 0", T);
  if (steps < 0) return fmt::format("steps = {} must be >= 0", steps);
  if (!(gate_miss > 0.0 && gate_miss < 1.0)) return fmt::format("gate_miss = {} must be in (0, 1)", gate_miss);
  if (!(weight_floor >= 0.0)) return fmt::format("weight_floor = {} must be >= 0", weight_floor);
  // Refuse clutter that would not fit in memory. Bound the gates by the largest prior (a track
  // never detected) and ignore the estimate noise: this is the typical scale, not a hard cap.
  const ConstantVelocityModel model(q, T, r);
  const Eigen::Matrix2d widest = prior_covariance(model, steps, [](int) { return false; });
  const double half_width = std::sqrt(gate_threshold() * (widest(0, 0) + r));
  const double expected = lambda_fa * (spacing * (cols - 1) + 2.0 * half_width) *
                          (spacing * (rows - 1) + 2.0 * half_width);
  if (!(expected <= kMaxExpectedFalseAlarms)) {
    return fmt::format("lambda_fa * area = {:.3g} expected false alarms per scan must be <= {:g} "
                       "(lower lambda_fa, spacing, q, steps or r)", expected, kMaxExpectedFalseAlarms);
  }
  return {};
}

ConstantVelocityModel::ConstantVelocityModel(double q, double T, double r_) : r(r_) {
  f << 1.0, T, 0.0, 1.0;
  q1 << T * T * T / 3.0, T * T / 2.0, T * T / 2.0, T;
  q1 *= q;
}

Eigen::Matrix2d ConstantVelocityModel::predict(const Eigen::Matrix2d& p) const {
  return f * p * f.transpose() + q1;
}

Eigen::Matrix2d ConstantVelocityModel::update(const Eigen::Matrix2d& p) const {
  const Eigen::Vector2d ph = p.col(0);             // p h'
  return p - (ph * ph.transpose()) / (ph(0) + r);  // p − p h' (h p h' + r)⁻¹ h p
}

GridScenario::GridScenario(const Options& options)
    : options_(options),
      model_(options.q, options.T, options.r),
      gamma_(options.gate_threshold()),
      psi_scale_(options.pd / (options.lambda_fa * (1.0 - options.pd) * 2.0 * std::numbers::pi)) {}

void GridScenario::generate(RandomStream& rng, ScenarioSample& sample) const {
  generate(rng, sample, nullptr);
}

void GridScenario::generate(RandomStream& rng, ScenarioSample& sample, GridDetails* details) const {
  const Options& o = options_;
  const int n = o.rows * o.cols;
  auto truth = [&](int i) { return Eigen::Vector2d((i % o.cols) * o.spacing, (i / o.cols) * o.spacing); };
  thread_local GridScratch scratch;
  auto& [tracks, points, origin, column, psi] = scratch;
  if (details != nullptr) details->targets.resize(n);

  // 1. Tracks: covariance history, estimate, innovation covariance; the box covering the gates.
  tracks.resize(n);
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (int i = 0; i < n; ++i) {
    const Eigen::Matrix2d p = prior_covariance(model_, o.steps, [&](int) { return rng.bernoulli(o.pd); });
    const double position_variance = std::max(p(0, 0), 0.0);  // H P H' = p(0,0)·I2
    const Eigen::Vector2d estimate = truth(i) + std::sqrt(position_variance) * normal2(rng);
    const double s = position_variance + o.r;  // S = H P H' + R = s·I2
    tracks[i] = {estimate, 1.0 / s, psi_scale_ / s};
    const Eigen::Vector2d half = Eigen::Vector2d::Constant(std::sqrt(gamma_ * s));
    lo = lo.cwiseMin(estimate - half);
    hi = hi.cwiseMax(estimate + half);
    if (details != nullptr) {
      details->targets[i] = {truth(i), estimate, lift(p), s * Eigen::Matrix2d::Identity(), false, Eigen::Vector2d::Zero()};
    }
  }

  // 2. Detections.
  points.clear();
  origin.clear();
  const double noise = std::sqrt(o.r);
  for (int i = 0; i < n; ++i) {
    if (!rng.bernoulli(o.pd)) continue;
    points.push_back(truth(i) + noise * normal2(rng));
    origin.push_back(i);
    if (details != nullptr) {
      details->targets[i].detected = true;
      details->targets[i].measurement = points.back();
    }
  }
  const int detections = static_cast<int>(points.size());

  // 3. False alarms, uniform over the box.
  const Eigen::Vector2d extent = hi - lo;
  const auto false_alarms = static_cast<int>(rng.poisson(o.lambda_fa * extent.prod()));
  for (int k = 0; k < false_alarms; ++k) {
    const double x = lo.x() + extent.x() * rng.uniform();
    const double y = lo.y() + extent.y() * rng.uniform();
    points.emplace_back(x, y);
    origin.push_back(-1);
  }

  // 4. Fisher–Yates shuffle, so column order does not reveal which measurement is whose.
  const int m_all = static_cast<int>(points.size());
  for (int k = m_all - 1; k > 0; --k) {
    const int j = std::min(static_cast<int>(rng.uniform() * (k + 1)), k);
    std::swap(points[k], points[j]);
    std::swap(origin[k], origin[j]);
  }

  // Gating and eq (11); then keep only columns with some ψ > 0.
  psi.resize(n, m_all);
  column.assign(m_all, 0);
  int kept = 0;
  for (int j = 0; j < m_all; ++j) {
    bool any = false;
    for (int i = 0; i < n; ++i) {
      const double nis = (points[j] - tracks[i].estimate).squaredNorm() * tracks[i].inverse_s;
      const double weight = nis > gamma_ ? 0.0 : tracks[i].scale * std::exp(-0.5 * nis);
      psi(i, j) = weight < o.weight_floor ? 0.0 : weight;
      any = any || psi(i, j) > 0.0;
    }
    if (any) column[j] = ++kept;
  }

  sample.problem.psi.resize(n, kept);
  for (int j = 0; j < m_all; ++j) {
    if (column[j] > 0) sample.problem.psi.col(column[j] - 1) = psi.col(j);
  }
  sample.problem.miss_weight.resize(0);
  sample.problem.clutter_weight.resize(0);
  sample.problem.context.pd = o.pd;
  sample.problem.context.lambda_fa = o.lambda_fa;

  sample.true_measurement.assign(n, 0);
  sample.detections = detections;
  sample.gated_out_detections = 0;
  sample.false_alarms = false_alarms;
  for (int j = 0; j < m_all; ++j) {
    const int i = origin[j];
    if (i < 0) continue;
    if ((points[j] - tracks[i].estimate).squaredNorm() * tracks[i].inverse_s > gamma_) {
      ++sample.gated_out_detections;
    } else if (column[j] > 0 && sample.problem.psi(i, column[j] - 1) > 0.0) {
      sample.true_measurement[i] = column[j];  // (0 if weight_floor removed it)
    }
  }

  if (details != nullptr) {
    details->measurements.clear();
    for (int j = 0; j < m_all; ++j) {
      if (column[j] > 0) details->measurements.push_back(points[j]);
    }
    details->box_lo = lo;
    details->box_hi = hi;
  }
}

DABENCH_REGISTER_SINGLE_SCAN_SCENARIO(GridScenario);

}  // namespace dabench
