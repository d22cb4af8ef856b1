#include "scenarios/tbd/tbd.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <type_traits>

#include <fmt/format.h>

#include "harness/tbd/registry.hpp"
#include "scenarios/tbd/magnitude_frame.hpp"

namespace dabench {

namespace {

// Anchors of the crossing layout as fractions of the region, read from Fig. 2 [F] on [0, 32]²
// (docs/models/track-before-detect.md §2.2).
constexpr double kCrossingAnchor[2] = {22.5 / 32.0, 18.5 / 32.0};
constexpr double kSlowAnchor[2] = {12.7 / 32.0, 7.5 / 32.0};

// The toy example's fixed settings (supplement §1.3).
constexpr double kToyPositionVariance = 0.3;  // m², of the two POs' α (0.3 I₂)
constexpr int kToyObjects = 2;
constexpr int kToySteps = 1;
constexpr int kToyCells = 10;

// Spreads σ_h² of D1 and D2 (docs/models/track-before-detect.md §1.3); D3's is kSpreadD3 (tbd.hpp).
constexpr double kSpreadD1 = 0.5;
constexpr double kSpreadD2 = 1.5;

int uniform_int(RandomStream& rng, int lo, int hi) {
  return lo + std::min(static_cast<int>(rng.uniform() * (hi - lo + 1)), hi - lo);
}

// State [p, v] from a position, a heading (rad) and a speed in m/step.
Eigen::Vector4d moving_state(double px, double py, double heading, double speed_per_step, double T) {
  const double v = speed_per_step / T;
  return {px, py, v * std::cos(heading), v * std::sin(heading)};
}

// One NCV step forward (direction +1: x ← A x + W a) or backward (−1: x ← A⁻¹(x − W a), the
// sign of a being immaterial), a ~ N(0, sd² I₂) from two normals.
void ncv_step(Eigen::Vector4d& x, double T, double sd, double direction, RandomStream& rng) {
  const double ax = sd * rng.normal();
  const double ay = sd * rng.normal();
  const Eigen::Vector2d a{ax, ay};
  x.head<2>() += direction * T * x.tail<2>() + 0.5 * T * T * a;
  x.tail<2>() += direction * T * a;
}

// Writes `object`'s states: `start` at step `middle`, then forward to `last` and backward to
// `first` (0-based, inclusive), each direction stopping at its first step outside the region.
void trace(const Eigen::Vector4d& start, int middle, int first, int last, const TbdSensor& sensor, double T,
           double sd, RandomStream& rng, TbdTruth::Object& object) {
  if (!sensor.inside(start[0], start[1])) return;
  object.states.col(middle) = start;
  object.alive[middle] = true;
  Eigen::Vector4d x = start;
  for (int k = middle + 1; k <= last; ++k) {
    ncv_step(x, T, sd, 1.0, rng);
    if (!sensor.inside(x[0], x[1])) break;
    object.states.col(k) = x;
    object.alive[k] = true;
  }
  x = start;
  for (int k = middle - 1; k >= first; --k) {
    ncv_step(x, T, sd, -1.0, rng);
    if (!sensor.inside(x[0], x[1])) break;
    object.states.col(k) = x;
    object.alive[k] = true;
  }
}

// Cells [lo, hi] (clamped to 0..count−1) whose centre origin + (i + 0.5)Δ is within r of p.
void cell_range(double p, double r, double origin, double size, int count, int& lo, int& hi) {
  const double last = static_cast<double>(count - 1);
  lo = static_cast<int>(std::clamp(std::ceil((p - r - origin) / size - 0.5), 0.0, last + 1.0));
  hi = static_cast<int>(std::clamp(std::floor((p + r - origin) / size - 0.5), -1.0, last));
}

}  // namespace

std::string TbdImageOptions::validate() const {
  // "" if value lies in [lo, hi] (in (lo, hi] when open_low), else the rule it breaks.
  const auto range = [](std::string_view key, auto value, double lo, double hi, bool open_low = false) {
    if ((open_low ? value > lo : value >= lo) && value <= hi) return std::string();
    if constexpr (std::is_integral_v<decltype(value)>) return fmt::format("{} = {} must be in {}..{}", key, value, lo, hi);
    return fmt::format("{} = {} must be in {}{}, {}]", key, value, open_low ? "(" : "[", lo, hi);
  };
  for (const std::string& why : {range("objects", objects, layout_kind() == TbdLayout::persistent ? 0 : 1, 1000), range("steps", steps, 1, 10000),
                                 range("columns", columns, 1, 1024), range("rows", rows, 1, 1024),
                                 range("cell_size", cell_size, 0, 1000, true), range("sigma_s2", sigma_s2, 0, 1e6),
                                 range("mean_share", mean_share, 0, 1),
                                 range("noise_variance", noise_variance, 0, 1e6, true),
                                 range("spread_variance", spread_variance, 0, 1e6), range("amplitude", amplitude, 0, 1e6),
                                 range("driving_noise_variance", driving_noise_variance, 0, 100),
                                 range("truth_noise_variance", truth_noise_variance, 0, 100),
                                 range("scan_interval", scan_interval, 0, 1000, true),
                                 range("survival_probability", survival_probability, 0, 1),
                                 range("birth_mean", birth_mean, 0, 1000), range("birth_speed_sd", birth_speed_sd, 0, 1000)}) {
    if (!why.empty()) return why;
  }
  if (!frame.empty() && layout_kind() != TbdLayout::toy) return "frame (a file of cell magnitudes) needs layout = toy";
  if (unread_magnitude > 1e6) return "unread_magnitude must be at most 1e6";
  if (layout_kind() == TbdLayout::toy) {
    // Each must be left at its default or set to the toy's value (see the header).
    const TbdImageOptions defaults;
    const auto conflict = [](std::string_view key, auto value, auto fallback, auto toy) {
      if (value == fallback || value == toy) return std::string();
      return fmt::format("{} = {} conflicts with layout = toy, which fixes it to {}", key, value, toy);
    };
    for (const std::string& why : {conflict("objects", objects, defaults.objects, kToyObjects),
                                   conflict("steps", steps, defaults.steps, kToySteps),
                                   conflict("columns", columns, defaults.columns, kToyCells),
                                   conflict("rows", rows, defaults.rows, kToyCells),
                                   conflict("cell_size", cell_size, defaults.cell_size, 1.0)}) {
      if (!why.empty()) return why;
    }
  }
  return {};
}

double TbdImageOptions::effective_spread_variance() const {
  if (spread_variance > 0.0) return spread_variance;
  switch (signal_kind()) {
    case TbdSignal::fluctuating:
      return kSpreadD1;
    case TbdSignal::deterministic:
      return kSpreadD2;
    case TbdSignal::mixed:
      return kSpreadD3;
  }
  return kSpreadD1;
}

void add_tbd_objects(const TbdSensor& sensor, double amplitude, const std::vector<Eigen::Vector2d>& positions,
                     RandomStream& rng, Eigen::Matrix2Xd& frame) {
  const double r = TbdImageScenario::kSupportRadius * std::sqrt(sensor.spread_variance);
  for (const Eigen::Vector2d& p : positions) {
    int c_lo = 0, c_hi = 0, r_lo = 0, r_hi = 0;
    cell_range(p.x(), r, sensor.x_min, sensor.cell_size, sensor.columns, c_lo, c_hi);
    cell_range(p.y(), r, sensor.y_min, sensor.cell_size, sensor.rows, r_lo, r_hi);
    for (int row = r_lo; row <= r_hi; ++row) {
      const double dy = sensor.centre_y(row) - p.y();
      for (int column = c_lo; column <= c_hi; ++column) {
        const double dx = sensor.centre_x(column) - p.x();
        if (dx * dx + dy * dy > r * r) continue;
        const CellContribution h = sensor.contribution(column, row, p.x(), p.y(), amplitude);
        const double w0 = rng.normal();
        const double w1 = rng.normal();
        const double sd = std::sqrt(h.variance);
        frame.col(row * sensor.columns + column) += h.mean + sd * Eigen::Vector2d{w0, w1};
      }
    }
  }
}

void draw_tbd_frame(const TbdSensor& sensor, double amplitude, const std::vector<Eigen::Vector2d>& positions,
                    RandomStream& rng, Eigen::Matrix2Xd& frame) {
  const double sigma = std::sqrt(sensor.noise_variance);
  frame.resize(2, sensor.cells());
  for (int j = 0; j < sensor.cells(); ++j) {
    const double e0 = rng.normal();
    const double e1 = rng.normal();
    frame(0, j) = sigma * e0;
    frame(1, j) = sigma * e1;
  }
  add_tbd_objects(sensor, amplitude, positions, rng, frame);
}

TbdImageScenario::Windows TbdImageScenario::crossing_windows(int steps) {
  Windows w{};
  w.birth_last = std::max(1, (4 * steps + 5) / 10);
  w.death_first = std::max(w.birth_last, (6 * steps + 5) / 10);
  w.middle = (steps + 1) / 2;
  w.slow_last = std::max(1, (7 * steps + 5) / 10);
  return w;
}

TbdImageScenario::TbdImageScenario(const Options& options) : options_(options) {
  if (options_.layout_kind() == TbdLayout::toy) {
    options_.objects = kToyObjects;
    options_.steps = kToySteps;
    options_.columns = options_.rows = kToyCells;
    options_.cell_size = 1.0;
  }
  sensor_.columns = options_.columns;
  sensor_.rows = options_.rows;
  sensor_.cell_size = options_.cell_size;
  sensor_.signal = options_.signal_kind();
  sensor_.noise_variance = options_.noise_variance;
  sensor_.signal_scale = options_.sigma_s2;
  sensor_.spread_variance = options_.effective_spread_variance();
  sensor_.mean_share = options_.mean_share;
  if (!options_.frame.empty()) {
    const double unread = options_.unread_magnitude >= 0.0 ? options_.unread_magnitude
                                                           : std::sqrt(2.0 * std::numbers::ln2 * options_.noise_variance);
    file_frame_ = read_magnitude_frame(options_.frame, sensor_.columns, sensor_.rows, unread).z;
  }
}

void TbdImageScenario::generate(RandomStream& rng, TbdSample& sample) const {
  const Options& o = options_;
  const int K = o.steps;
  const double T = o.scan_interval;
  const double sd = std::sqrt(o.truth_noise_variance);
  const double width = sensor_.x_max() - sensor_.x_min;
  const double height = sensor_.y_max() - sensor_.y_min;

  TbdProblem& problem = sample.problem;
  problem.sensor = sensor_;
  problem.motion = TbdMotion{T, o.driving_noise_variance};
  problem.filter = TbdFilterModel{o.survival_probability, o.birth_mean, o.birth_speed_sd};
  problem.amplitude = o.amplitude;
  problem.initial_objects.clear();

  // 1. Truth.
  TbdTruth& truth = sample.truth;
  truth.objects.resize(o.objects);
  for (TbdTruth::Object& object : truth.objects) {
    object.states.setConstant(4, K, std::numeric_limits<double>::quiet_NaN());
    object.alive.assign(K, false);
  }
  switch (o.layout_kind()) {
    case TbdLayout::crossing: {
      const Windows w = crossing_windows(K);
      for (int n = 0; n < o.objects; ++n) {
        if (n == 0) {
          const int middle = (w.slow_last + 1) / 2;
          const double px = sensor_.x_min + kSlowAnchor[0] * width + kPositionSd * rng.normal();
          const double py = sensor_.y_min + kSlowAnchor[1] * height + kPositionSd * rng.normal();
          const double heading = rng.uniform(0.0, 2.0 * std::numbers::pi);
          trace(moving_state(px, py, heading, kSlowSpeed, T), middle - 1, 0, w.slow_last - 1, sensor_, T, sd, rng,
                truth.objects[n]);
        } else {
          const int birth = uniform_int(rng, 1, w.birth_last);
          const int death = uniform_int(rng, w.death_first, K);
          const double px = sensor_.x_min + kCrossingAnchor[0] * width + kPositionSd * rng.normal();
          const double py = sensor_.y_min + kCrossingAnchor[1] * height + kPositionSd * rng.normal();
          const double heading = rng.uniform(0.0, 2.0 * std::numbers::pi);
          const double speed = rng.uniform(kSpeedMin, kSpeedMax);
          trace(moving_state(px, py, heading, speed, T), w.middle - 1, birth - 1, death - 1, sensor_, T, sd, rng,
                truth.objects[n]);
        }
      }
      break;
    }
    case TbdLayout::persistent:
      for (TbdTruth::Object& object : truth.objects) {
        const double px = rng.uniform(sensor_.x_min + kPersistentMargin * width, sensor_.x_max() - kPersistentMargin * width);
        const double py = rng.uniform(sensor_.y_min + kPersistentMargin * height, sensor_.y_max() - kPersistentMargin * height);
        const double heading = rng.uniform(0.0, 2.0 * std::numbers::pi);
        const double speed = rng.uniform(kSpeedMin, kSpeedMax);
        trace(moving_state(px, py, heading, speed, T), 0, 0, K - 1, sensor_, T, sd, rng, object);
      }
      break;
    case TbdLayout::toy:
      truth.objects[0].states.col(0) = Eigen::Vector4d{4.0, 4.0, 0.0, 0.0};
      truth.objects[1].states.col(0) = Eigen::Vector4d{5.0, 5.0, 0.0, 0.0};
      truth.objects[0].alive[0] = truth.objects[1].alive[0] = true;
      // The two POs' α (supplement §1.3): N(p; p_n, 0.3 I₂) δ(v) δ(γ − 60), α(x, 0) = 0; no new POs.
      for (const TbdTruth::Object& object : truth.objects) {
        TbdPrior prior;
        prior.mean = object.states.col(0);
        prior.covariance.diagonal() << kToyPositionVariance, kToyPositionVariance, 0.0, 0.0;
        prior.existence = 1.0;
        problem.initial_objects.push_back(prior);
      }
      problem.filter.birth_mean = 0.0;
      break;
  }

  // 2. Frames.
  problem.frames.resize(K);
  std::vector<Eigen::Vector2d> positions;
  for (int k = 0; k < K; ++k) {
    positions.clear();
    for (const TbdTruth::Object& object : truth.objects) {
      if (object.alive[k]) positions.push_back(object.states.col(k).head<2>());
    }
    if (file_frame_.size() > 0) {
      problem.frames[k] = file_frame_;
    } else {
      draw_tbd_frame(sensor_, o.amplitude, positions, rng, problem.frames[k]);
    }
  }
}

DABENCH_REGISTER_TBD_SCENARIO(TbdImageScenario);

}  // namespace dabench
