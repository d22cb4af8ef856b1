#include "scenarios/multi_scan/bearings.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <tuple>

#include <fmt/format.h>

#include "harness/multi_scan/registry.hpp"

namespace dabench {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDegree = kPi / 180.0;
constexpr double kWedge = kPi / 2.0;     // bearing range of the region seen from a corner
constexpr double kCutoffSigmas = 37.0;   // beyond this the factor (< 1e-290) is stored as 0
constexpr int kMaxParticles = 10'000'000;
constexpr double kMaxSiteDistance = 1e4;  // |site coordinate| bound: farther, the wedge is a sliver

// Angle difference wrapped to [−π, π).
double wrap(double angle) { return angle - 2.0 * kPi * std::floor((angle + kPi) / (2.0 * kPi)); }

double upper_tail(double z) { return 0.5 * std::erfc(z / std::numbers::sqrt2); }  // P(Z > z)

// N(mean, sd²) truncated to [lo, hi] (multiscan Sec. IV: the initialising bearing restricted
// to the region's wedge by the uniform prior).
class TruncatedNormal {
 public:
  TruncatedNormal(double mean, double sd, double lo, double hi)
      : mean_(mean), sd_(sd), a_((lo - mean) / sd), b_((hi - mean) / sd) {
    if (a_ > 0.0) mass_ = upper_tail(a_) - upper_tail(b_);
    else if (b_ < 0.0) mass_ = upper_tail(-b_) - upper_tail(-a_);
    else mass_ = 1.0 - upper_tail(-a_) - upper_tail(b_);
  }

  double density(double x) const {
    const double z = (x - mean_) / sd_;
    return std::exp(-0.5 * z * z) / (std::sqrt(2.0 * kPi) * sd_ * mass_);
  }

  double sample(RandomStream& rng) const {
    if (a_ > 0.5) return mean_ + sd_ * tail(rng, a_, b_);
    if (b_ < -0.5) return mean_ - sd_ * tail(rng, -b_, -a_);
    while (true) {  // the interval holds at least P(Z > 0.5) ≈ 0.31 of the mass
      const double z = rng.normal();
      if (z >= a_ && z <= b_) return mean_ + sd_ * z;
    }
  }

 private:
  // Standard normal on [a, b], a > 0: Robert (1995), exponential proposal with rate α.
  static double tail(RandomStream& rng, double a, double b) {
    const double alpha = 0.5 * (a + std::sqrt(a * a + 4.0));
    while (true) {
      const double z = a - std::log(1.0 - rng.uniform()) / alpha;
      const double accept = std::exp(-0.5 * (z - alpha) * (z - alpha));
      if (rng.uniform() < accept && z <= b) return z;
    }
  }

  double mean_, sd_, a_, b_, mass_ = 1.0;
};

// Per-thread buffers reused across trials (generate() is const and called concurrently).
struct BearingsScratch {
  std::vector<BearingsDetails::Target> targets;
  std::vector<std::vector<double>> bearings;
  std::vector<std::vector<int>> origin;
  std::vector<double> predicted;  // bearings of one track's hypotheses from one sensor
};

}  // namespace

std::string BearingsOptions::validate() const {
  if (!(mean_targets >= 0.0 && mean_targets <= 1000.0)) return fmt::format("mean_targets = {} must be in [0, 1000]", mean_targets);
  if (!poisson_targets && mean_targets != std::floor(mean_targets)) {
    return fmt::format("mean_targets = {} must be an integer when poisson_targets = 0", mean_targets);
  }
  if (particles < 1 || particles > kMaxParticles) return fmt::format("particles = {} must be in 1..{}", particles, kMaxParticles);
  if (!(pd > 0.0 && pd < 1.0)) return fmt::format("pd = {} must be in (0, 1)", pd);
  if (!(clutter_mean > 0.0 && clutter_mean <= 1e6)) {
    return fmt::format("clutter_mean = {} must be in (0, 1e6] (eq (33) divides by the clutter density)", clutter_mean);
  }
  if (!(noise_deg > 0.0 && noise_deg <= 90.0)) return fmt::format("noise_deg = {} must be in (0, 90]", noise_deg);
  if (!(init_noise_deg > 0.0 && init_noise_deg <= 90.0)) return fmt::format("init_noise_deg = {} must be in (0, 90]", init_noise_deg);
  if (scans_per_sensor < 1 || scans_per_sensor > 1000) return fmt::format("scans_per_sensor = {} must be in 1..1000", scans_per_sensor);
  if (!(probe_weight > 0.0 && probe_weight <= 1e-3)) return fmt::format("probe_weight = {} must be in (0, 1e-3]", probe_weight);
  if (init_corner < 0 || init_corner > 3) return fmt::format("init_corner = {} must be in 0..3", init_corner);
  if (init_sensor == BearingsScenario::kInitSite) {
    const double reach = std::max(std::fabs(init_site_x), std::fabs(init_site_y));
    if (!(reach >= BearingsScenario::kHalfWidth && reach <= kMaxSiteDistance)) {
      return fmt::format("init_site = ({}, {}) must lie outside the open region (-100, 100)^2 and within {} of the origin",
                         init_site_x, init_site_y, kMaxSiteDistance);
    }
  }
  return {};
}

Eigen::Vector2d BearingsScenario::sensor_position(int sensor) {
  static const Eigen::Vector2d corners[4] = {
      {-kHalfWidth, -kHalfWidth}, {kHalfWidth, -kHalfWidth}, {kHalfWidth, kHalfWidth}, {-kHalfWidth, kHalfWidth}};
  return corners[sensor];
}

double BearingsScenario::wedge_start(int sensor) { return sensor * kWedge; }

double BearingsScenario::ray_length(double relative_bearing) {
  return 2.0 * kHalfWidth / std::max(std::cos(relative_bearing), std::sin(relative_bearing));
}

BearingsScenario::InitView BearingsScenario::corner_view(int corner) {
  return {sensor_position(corner), wedge_start(corner), kWedge, true};
}

BearingsScenario::InitView BearingsScenario::site_view(const Eigen::Vector2d& site) {
  for (int corner = 0; corner < 4; ++corner) {
    if (site == sensor_position(corner)) return corner_view(corner);
  }
  // The region's bearings from outside it span its corners' (less than π, or π on an edge),
  // measured from the direction of its centre so that no wrap falls inside the wedge.
  const double reference = std::atan2(-site.y(), -site.x());
  double lo = kPi, hi = -kPi;
  for (int corner = 0; corner < 4; ++corner) {
    const Eigen::Vector2d d = sensor_position(corner) - site;
    const double angle = wrap(std::atan2(d.y(), d.x()) - reference);
    lo = std::min(lo, angle);
    hi = std::max(hi, angle);
  }
  return {site, reference + lo, hi - lo, false};
}

std::pair<double, double> BearingsScenario::ray_segment(const InitView& view, double relative_bearing) {
  if (view.corner) return {0.0, ray_length(relative_bearing)};
  const double angle = view.start + relative_bearing;
  const double direction[2] = {std::cos(angle), std::sin(angle)};
  const double origin[2] = {view.origin.x(), view.origin.y()};
  double enter = 0.0, exit = std::numeric_limits<double>::infinity();
  for (int axis = 0; axis < 2; ++axis) {  // slab test against [−W, W] on each axis
    if (direction[axis] == 0.0) {
      if (std::fabs(origin[axis]) > kHalfWidth) return {0.0, 0.0};
      continue;
    }
    const double a = (-kHalfWidth - origin[axis]) / direction[axis];
    const double b = (kHalfWidth - origin[axis]) / direction[axis];
    enter = std::max(enter, std::min(a, b));
    exit = std::min(exit, std::max(a, b));
  }
  return {enter, std::max(enter, exit)};
}

BearingsScenario::BearingsScenario(const Options& options) : options_(options) {
  if (options_.init_sensor == kInitSite) site_ = site_view({options_.init_site_x, options_.init_site_y});
}

int BearingsScenario::scan_sensor(int scan) const {
  return options_.scan_order == kRoundRobin ? scan % 4 : scan / options_.scans_per_sensor;
}

void BearingsScenario::generate(RandomStream& rng, MultiScanSample& sample) const { generate(rng, sample, nullptr); }

void BearingsScenario::generate(RandomStream& rng, MultiScanSample& sample, BearingsDetails* details) const {
  const Options& o = options_;
  thread_local BearingsScratch scratch;
  auto& targets = details != nullptr ? details->targets : scratch.targets;
  auto& bearings = details != nullptr ? details->bearings : scratch.bearings;
  auto& origin = details != nullptr ? details->origin : scratch.origin;
  const int particles = o.particles;
  const int hypotheses = particles + 1;  // + the truth probe
  const double init_sd = o.init_noise_deg * kDegree;

  // 1. Number of targets.
  const int n = o.poisson_targets ? static_cast<int>(rng.poisson(o.mean_targets)) : static_cast<int>(o.mean_targets);

  // 2. Targets and their particle tracks.
  targets.resize(n);
  sample.problem.prior.resize(n);
  sample.truth_probe.assign(n, particles);
  sample.density_scale.resize(n);
  const auto relative_bearing = [](const Eigen::Vector2d& x, const InitView& view) {
    const Eigen::Vector2d d = x - view.origin;
    return wrap(std::atan2(d.y(), d.x()) - view.start);
  };
  for (int i = 0; i < n; ++i) {
    BearingsDetails::Target& target = targets[i];
    const double x = rng.uniform(-kHalfWidth, kHalfWidth);
    const double y = rng.uniform(-kHalfWidth, kHalfWidth);
    target.truth = {x, y};
    const int drawn = std::min(static_cast<int>(rng.uniform() * 4.0), 3);
    target.init_sensor = o.init_sensor == kInitRandom ? drawn : o.init_sensor == kInitCorner ? o.init_corner : -1;
    const InitView view = o.init_sensor == kInitSite ? site_ : corner_view(target.init_sensor);
    target.init_bearing = relative_bearing(target.truth, view) + init_sd * rng.normal();
    const TruncatedNormal proposal(target.init_bearing, init_sd, 0.0, view.span);
    target.particles.resize(hypotheses, 2);
    target.proposal_density.resize(hypotheses);
    Vector& prior = sample.problem.prior[i];
    Vector& scale = sample.density_scale[i];
    prior.resize(hypotheses);
    scale.resize(hypotheses);
    const double reference_area = 4.0 * kHalfWidth * kHalfWidth;  // keeps weights near 1
    for (int p = 0; p < particles; ++p) {
      double phi = 0.0, near = 0.0, far = 0.0, area = 0.0;  // area: r_out² − r_in² (L(φ)² from a corner)
      do {  // from a site a bearing on the wedge's edge grazes a corner (area 0): drawn again
        phi = proposal.sample(rng);
        std::tie(near, far) = ray_segment(view, phi);
        area = far * far - near * near;
      } while (!(area > 0.0));
      const double u = rng.uniform();
      const double range = near == 0.0 ? far * std::sqrt(u) : std::sqrt(near * near + u * area);
      const double angle = view.start + phi;
      target.particles.row(p) = (view.origin + range * Eigen::Vector2d(std::cos(angle), std::sin(angle))).transpose();
      target.proposal_density[p] = proposal.density(phi) * 2.0 / area;
      prior[p] = area / reference_area;  // ∝ π0/g
      scale[p] = particles * target.proposal_density[p];
    }
    const double phi_truth = relative_bearing(target.truth, view);
    const auto [near_truth, far_truth] = ray_segment(view, phi_truth);
    const double area_truth = far_truth * far_truth - near_truth * near_truth;
    target.particles.row(particles) = target.truth.transpose();
    target.proposal_density[particles] = proposal.density(phi_truth) * 2.0 / area_truth;
    // ε·(r_out² − r_in²), written so that from a corner (r_in = 0) it rounds as ε·L·L did.
    prior[particles] = (o.probe_weight * far_truth * far_truth - o.probe_weight * near_truth * near_truth) / reference_area;
    scale[particles] = particles * target.proposal_density[particles] / o.probe_weight;
  }

  // 3. Scans, in the order of scan_order.
  const int scan_count = 4 * o.scans_per_sensor;
  const double sd = o.noise_deg * kDegree;
  bearings.resize(scan_count);
  origin.resize(scan_count);
  if (details != nullptr) details->scan_sensor.resize(scan_count);
  sample.detections = sample.false_alarms = 0;
  for (int t = 0; t < scan_count; ++t) {
    const int sensor = scan_sensor(t);
    if (details != nullptr) details->scan_sensor[t] = sensor;
    std::vector<double>& z = bearings[t];
    std::vector<int>& from = origin[t];
    z.clear();
    from.clear();
    const Eigen::Vector2d corner = sensor_position(sensor);
    for (int i = 0; i < n; ++i) {
      if (!rng.bernoulli(o.pd)) continue;
      const Eigen::Vector2d d = targets[i].truth - corner;
      z.push_back(wrap(std::atan2(d.y(), d.x()) + sd * rng.normal()));
      from.push_back(i);
    }
    sample.detections += static_cast<int>(z.size());
    const auto clutter = static_cast<int>(rng.poisson(o.clutter_mean));
    for (int k = 0; k < clutter; ++k) {
      z.push_back(wrap(wedge_start(sensor) + kWedge * rng.uniform()));
      from.push_back(-1);
    }
    sample.false_alarms += clutter;
    for (int k = static_cast<int>(z.size()) - 1; k > 0; --k) {
      const int j = std::min(static_cast<int>(rng.uniform() * (k + 1)), k);
      std::swap(z[k], z[j]);
      std::swap(from[k], from[j]);
    }
  }

  // 4. Factors, eq (33).
  const double clutter_density = o.clutter_mean / kWedge;  // λ_fa per radian
  const double detection_scale = o.pd / (clutter_density * std::sqrt(2.0 * kPi) * sd);
  const double cutoff = kCutoffSigmas * sd;
  sample.problem.scans.resize(scan_count);
  std::vector<double>& predicted = scratch.predicted;
  predicted.resize(hypotheses);
  for (int t = 0; t < scan_count; ++t) {
    ScanFactors& scan = sample.problem.scans[t];
    const std::vector<double>& z = bearings[t];
    const int m = static_cast<int>(z.size());
    scan.measurements = m;
    scan.factor.resize(n);
    const Eigen::Vector2d corner = sensor_position(scan_sensor(t));
    for (int i = 0; i < n; ++i) {
      const Eigen::MatrixX2d& positions = targets[i].particles;
      for (int h = 0; h < hypotheses; ++h) {
        predicted[h] = std::atan2(positions(h, 1) - corner.y(), positions(h, 0) - corner.x());
      }
      RowMatrix& factor = scan.factor[i];
      factor.resize(hypotheses, m + 1);
      for (int h = 0; h < hypotheses; ++h) {
        factor(h, 0) = 1.0 - o.pd;
        for (int j = 0; j < m; ++j) {
          const double difference = wrap(z[j] - predicted[h]);
          factor(h, j + 1) = std::fabs(difference) > cutoff
                                 ? 0.0
                                 : detection_scale * std::exp(-0.5 * (difference / sd) * (difference / sd));
        }
      }
    }
  }
}

DABENCH_REGISTER_MULTI_SCAN_SCENARIO(BearingsScenario);

}  // namespace dabench
