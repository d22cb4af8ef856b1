#pragma once
// Scenario "bearings": the bearings-only experiment of Williams & Lau, "Multiple scan data
// association by convex variational inference" (multiscan-convex-variational), Sec. IV.
// The paper's values are the defaults; [R] marks our readings, where the paper is silent.
//
// Model:
//  - Region [−100, 100]²; four sensors at the corners, indexed counter-clockwise from
//    (−100, −100). Seen from its corner, the region is the 90° wedge of bearings
//    [θ_k, θ_k + 90°], θ_k = 0°, 90°, 180°, 270°.
//  - Poisson(mean_targets) targets (exactly mean_targets if poisson_targets = 0), known to the
//    estimator, uniform on the region and static [R]. No target: a problem with no tracks.
//  - Track initialisation: one bearing with N(0, init_noise_deg²) noise, from the sensor that
//    `init_sensor` [R] names (corner: init_corner; random: a corner per target; site: a
//    non-scanning sensor at (init_site_x, init_site_y)). The track's particles represent
//    π0(x) ∝ 1{x in region}·N(φ(x); φ_m, σ0²).
//  - Scans: scans_per_sensor scans of each sensor (4 or 12 scans), in the order `scan_order` [R]
//    (round_robin: scan t uses sensor t mod 4; grouped: sensor t / scans_per_sensor). Each
//    target is detected with probability pd, with bearing noise N(0, noise_deg²); false alarms
//    are Poisson(clutter_mean), uniform over the sensor's 90° wedge; a scan's measurements are
//    shuffled.
//  - Factors, eq (33) with constant Pd:  ψ_t(p, 0) = 1 − pd,
//      ψ_t(p, j) = N(wrap(z_j − θ_k(x_p)); 0, σ²)·pd / λ_fa,  λ_fa = clutter_mean / (π/2) per
//    radian, wrap to [−π, π). No gating, but a factor with |difference| > 37σ (< 1e−290) is
//    stored as 0.
//
// Particles (N = `particles`): relative bearing φ ~ N(φ_m, σ0²) truncated to the wedge, range r
// with r² uniform on [r_in(φ)², r_out(φ)²] (from a corner r_in = 0, r_out = L(φ) =
// 200 / max(cos φ, sin φ)), so g(x) = TN(φ; φ_m, σ0, wedge) · 2 / (r_out² − r_in²) and the
// importance weights ψ^i(p) = π0(x_p)/g(x_p) ∝ r_out² − r_in² are exact. Each track ends with a
// truth probe (harness/multi_scan/scenario.hpp): one more hypothesis at the true position, prior
// ε·(r_out² − r_in²) at its bearing (ε = probe_weight); density_scale is N·g(x) for particles,
// N·g(x*)/ε for the probe (harness/multi_scan/particle_metrics.hpp).
//
// Draw order (stable; a change alters every trial's numbers):
//  1. the number of targets: poisson(mean_targets) (nothing if poisson_targets = 0);
//  2. per target: uniform x, uniform y, uniform (initialising corner; drawn whatever
//     init_sensor), normal (its bearing noise), then per particle: the truncated normal's
//     uniforms/normals (again while the ray meets the region in zero area), one uniform (range);
//  3. per scan: per target bernoulli(pd) and, if detected, one normal; poisson(clutter_mean),
//     one uniform per false alarm; Fisher–Yates shuffle (for k = M−1..1 one uniform).
// Background and our readings: docs/algorithms/multi-scan.md#the-bearings-only-scenario
#include <Eigen/Core>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "harness/core/params.hpp"
#include "harness/multi_scan/scenario.hpp"

namespace dabench {

struct BearingsOptions {
  double mean_targets = 8.0;    // Poisson mean of the number of targets (paper: 8)
  bool poisson_targets = true;  // false: exactly mean_targets targets (must then be an integer)
  int particles = 10000;        // N per track (why 10000: docs/algorithms/multi-scan.md#how-many-particles)
  double pd = 0.9;              // detection probability (paper: 0.9)
  double clutter_mean = 1.0;    // false alarms per scan, uniform over the 90° wedge (paper: 1)
  double noise_deg = 1.0;       // bearing noise s.d. of the scans, degrees (paper: 1)
  double init_noise_deg = 0.1;  // s.d. of the initialising bearing, degrees (paper: 0.1)
  int scans_per_sensor = 1;     // rounds of the four sensors: 1 → 4 scans, 3 → 12 (paper: 1, 3)
  int init_sensor = 1;          // corner: all from init_corner; random: each from a corner drawn uniformly [R]
  int init_corner = 0;          // init_sensor = corner: its index, 0..3 (counter-clockwise from (−100, −100))
  double init_site_x = -100.0;  // init_sensor = site: its position, outside the open region (default:
  double init_site_y = -100.0;  //   corner 0, where site draws what corner draws)
  int scan_order = 0;           // round_robin: scan t uses sensor t mod 4; grouped: each sensor's scans together [R]
  double probe_weight = 1e-6;   // ε: truth probe's prior relative to a particle at its place

  void bind(ParamList& p) {
    p.add("mean_targets", mean_targets, "mean number of targets (Poisson), >= 0");
    p.add("poisson_targets", poisson_targets, "1: Poisson number of targets; 0: exactly mean_targets");
    p.add("particles", particles, "particles per track, >= 1");
    p.add("pd", pd, "detection probability, in (0, 1)");
    p.add("clutter_mean", clutter_mean, "false alarms per scan (Poisson mean), > 0");
    p.add("noise_deg", noise_deg, "bearing noise s.d. of the scans, degrees, > 0");
    p.add("init_noise_deg", init_noise_deg, "s.d. of the initialising bearing, degrees, > 0");
    p.add("scans_per_sensor", scans_per_sensor, "scans of each of the 4 sensors (round robin), >= 1");
    p.add("probe_weight", probe_weight, "truth probe prior relative to a particle there, in (0, 1e-3]");
    p.add_choice("init_sensor", init_sensor, {"random", "corner", "site"},
                 "which sensor initialises a track: a uniformly drawn corner per target, init_corner for all, or a "
                 "non-scanning sensor at (init_site_x, init_site_y) for all");
    p.add("init_corner", init_corner, "init_sensor = corner: the corner, 0..3 counter-clockwise from (-100, -100)");
    p.add("init_site_x", init_site_x, "init_sensor = site: x of the site, outside the open region (-100, 100)^2");
    p.add("init_site_y", init_site_y, "init_sensor = site: y of the site");
    p.add_choice("scan_order", scan_order, {"round_robin", "grouped"},
                 "round_robin: scan t uses sensor t mod 4; grouped: scans_per_sensor scans of sensor 0, then 1, ...");
  }
  std::string validate() const;  // "" if valid, else which field breaks which rule
};

// What a draw contains besides the problem, for tests and pictures.
struct BearingsDetails {
  struct Target {
    Eigen::Vector2d truth;
    int init_sensor = 0;          // corner of the initialising bearing, −1 for a site
    double init_bearing = 0.0;    // its measured bearing relative to the start of the wedge, rad
    Eigen::MatrixX2d particles;   // N + 1 rows: the particles, then the truth probe (= truth)
    Vector proposal_density;      // g(x) at every row of `particles`
  };
  std::vector<Target> targets;
  std::vector<int> scan_sensor;                  // per scan
  std::vector<std::vector<double>> bearings;     // per scan: absolute bearing of column j+1, rad
  std::vector<std::vector<int>> origin;          // per scan, per measurement: target or −1
};

class BearingsScenario final : public MultiScanScenario {
 public:
  using Options = BearingsOptions;
  static constexpr std::string_view kName = "bearings";
  static constexpr std::string_view kSummary =
      "Sec. IV of Williams & Lau (multi-scan): 4 corner bearing sensors, particle tracks, Poisson(8) static targets";

  static constexpr double kHalfWidth = 100.0;  // region [−100, 100]²
  static Eigen::Vector2d sensor_position(int sensor);
  static double wedge_start(int sensor);       // θ_k, rad
  static double ray_length(double relative_bearing);  // L(φ)
  static constexpr int kInitRandom = 0, kInitCorner = 1, kInitSite = 2;  // BearingsOptions::init_sensor
  // Where a track's initialising bearing is measured from, and the region seen from there.
  struct InitView {
    Eigen::Vector2d origin;
    double start = 0.0;         // absolute bearing of the wedge's first edge, rad
    double span = 0.0;          // the wedge's width, rad (π/2 at a corner)
    bool corner = true;         // r_in = 0 and r_out = ray_length(φ)
  };
  static InitView corner_view(int corner);
  static InitView site_view(const Eigen::Vector2d& site);
  // The ray at relative bearing φ meets the region on [r_in, r_out] (r_in = 0 from a corner).
  static std::pair<double, double> ray_segment(const InitView& view, double relative_bearing);
  static constexpr int kRoundRobin = 0, kGrouped = 1;     // BearingsOptions::scan_order
  int scan_sensor(int scan) const;                        // the sensor of scan t (scan_order)

  explicit BearingsScenario(const Options& options);
  void generate(RandomStream& rng, MultiScanSample& sample) const override;
  // The same draw (same numbers); also fills `details` unless it is null.
  void generate(RandomStream& rng, MultiScanSample& sample, BearingsDetails* details) const;
  const Options& options() const { return options_; }

 private:
  Options options_;
  InitView site_;  // init_sensor = site: the view from (init_site_x, init_site_y)
};

}  // namespace dabench
