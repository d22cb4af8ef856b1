#pragma once
// Scenario "bearings": the bearings-only experiment of Williams & Lau, "Multiple scan data
// association by convex variational inference" (multiscan-convex-variational), Sec. IV.
//
// Model (paper's values are the defaults):
//  - Region [−100, 100]²; four sensors at the corners, indexed counter-clockwise from
//    (−100, −100): (−100,−100), (100,−100), (100,100), (−100,100). Seen from its corner, the
//    region is exactly the 90° wedge of bearings [θ_k, θ_k + 90°] with θ_k = 0°, 90°, 180°, 270°.
//  - Number of targets Poisson(mean_targets), known to the estimator (poisson_targets = 0 uses
//    exactly mean_targets, e.g. one target for exact single-track checks). A draw with no
//    target is a problem with no tracks (the runner records it as skipped:no_targets).
//  - Targets are uniform on the region and static: the paper "refines locations" with every
//    scan and describes no motion model, so positions do not change between scans.
//  - Track initialisation: one sensor measures the target's bearing with N(0, init_noise_deg²)
//    noise; the track's particles represent the posterior π0(x) ∝ 1{x in region}·N(φ(x); φ_m,
//    σ0²) (uniform prior × that bearing). Which sensor is a reading [R] (`init_sensor`): the
//    paper initialises tracks "from one sensor … from a single location"; `corner` (default:
//    one site, the wording's most direct reading) takes init_corner for every target, `random`
//    draws a corner uniformly per target (the uniform is drawn either way, so the
//    two readings share the draws up to the first target whose corner differs; its particles
//    then take other numbers), `site` takes the point
//    (init_site_x, init_site_y) outside the open region for every target: a separate accurate
//    sensor that does not scan (the paper's four corner sensors make "four scans in total"; at a
//    corner, `site` is `corner`, since that corner's sensor scans either way).
//  - Scans: scans_per_sensor scans of each of the four sensors, so 4 or 12 scans, in the order
//    `scan_order` [R]: `round_robin` (default; scan t uses sensor t mod 4) or `grouped` (scan t
//    uses sensor t / scans_per_sensor: all of sensor 0's scans, then sensor 1's, ...). The
//    paper does not give the order; with one scan per sensor the two coincide. In each scan every target is detected with
//    probability pd, with bearing noise N(0, noise_deg²); false alarms are Poisson(clutter_mean)
//    uniform over the sensor's 90° wedge; the measurements of a scan are shuffled.
//  - Factors, eq (33) with constant Pd:  ψ_t(p, 0) = 1 − pd,
//      ψ_t(p, j) = N(wrap(z_j − θ_k(x_p)); 0, σ²)·pd / λ_fa,  λ_fa = clutter_mean / (π/2) per
//    radian, wrap to (−π, π] (the Gaussian on the wrapped difference; the wrapped-normal terms
//    it drops are below e^{−(2π)²/(2σ²)}). No gating, except that a factor whose |difference|
//    exceeds 37σ is stored as 0 instead of its value (< 1e−290, against 1 − pd ≥ 1e−3 for a
//    miss): a negligible threshold that only saves the exp().
//
// Particles (parameter `particles`, N). Proposal g for the relative bearing φ ∈ [0, π/2] and
// range r from the corner: φ ~ N(φ_m, σ0²) truncated to [0, π/2] (rejection near the mode,
// Robert's exponential rejection in a far tail), r = L(φ)·√u with L(φ) = 200 / max(cos φ, sin φ)
// the length of the ray inside the region. In the plane,
//     g(x) = TN(φ; φ_m, σ0, [0, π/2]) · 2 / L(φ)²,
// known exactly, so the importance weights ψ^i(p) = π0(x_p)/g(x_p) ∝ L(φ_p)² make the weighted
// particles an exact (unbiased up to self-normalisation) representation of π0. Since L varies
// little across a 0.1° fan, the weights are nearly equal (this is almost exact sampling).
// From a site, φ is relative to the smallest bearing of the region seen from it, the wedge is
// that of the region's corners (at most π), the ray meets the region on [r_in(φ), r_out(φ)],
// r² is uniform on [r_in², r_out²] and L(φ)² above becomes r_out² − r_in² (r_in = 0 at a corner).
// Each track also gets a truth probe (harness/multi_scan/scenario.hpp): one more hypothesis at
// the true position, last in the track, with prior ε·L(φ*)² (ε = probe_weight), and
// density_scale N·g(x) for particles, N·g(x*)/ε for the probe (harness/multi_scan/particle_metrics.hpp).
//
// Default particle count: 10000. The posterior after the scans covers a small part of the
// initial bearing line, so only that share of the particles carries its weight. Chosen with
// experiments/multiscan-particles.ini (one target per trial, where jpda-bp is exact Bayes, so
// HPD values must be Uniform(0, 1) up to particle error; the KS distance of 300, 1000, 3000 and
// 10000 particles against its 5 % critical value): 10000 is the smallest of these counts that
// passes at 4 and at 12 scans (results/multiscan/REPORT.md, checks E1 and E2, computes this from
// the committed run). What it costs each method:
// bearings_trial in bench/multi_scan/bench_multi_scan.cpp, and the time_us columns of the runs
// in results/multiscan/ (plots/multiscan_cost.py).
//
// Draw order (stable; a change alters every trial's numbers):
//  1. the number of targets: poisson(mean_targets) (nothing if poisson_targets = 0);
//  2. per target: uniform x, uniform y, uniform (initialising sensor; drawn also when
//     init_sensor = corner), normal (its bearing
//     noise), then per particle: the truncated normal's uniforms/normals, one uniform (range);
//  3. per scan: per target bernoulli(pd) and, if detected, one normal; poisson(clutter_mean),
//     one uniform per false alarm; Fisher–Yates shuffle (for k = M−1..1 one uniform).
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
  int particles = 10000;        // N particles per track (see the header)
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
