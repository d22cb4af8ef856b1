#pragma once
// Scenario "grid": the single-scan experiments of Williams & Lau 2014 (bp-marginal-association),
// Section V. Targets sit on a regular rows×cols grid; each track's prior covariance comes from
// simulating `steps` scans of the constant-velocity model; the measurements of one scan are
// gated and turned into the weights ψ_i(j) of eq (11).
//
// Readings of the paper (Sec. V) made here:
//  - Target i = row·cols + col is at (col·spacing, row·spacing); state [x, vx, y, vy].
//  - F = I2 ⊗ [[1, T], [0, 1]], Q = q·I2 ⊗ [[T³/3, T²/2], [T²/2, T]], R = r·I2.
//  - H = I2 ⊗ [1 0] (position only). The paper prints H = I2 ⊗ I2, which is 4×4 and cannot be
//    combined with the 2×2 R = r·I2; we read it as the usual position measurement.
//  - Covariance recursion from P = 0: `steps` times predict P = FPF' + Q, then with probability
//    Pd (drawn per target and step) update P = P − KHP. One more predict gives the prior of the
//    scan being associated (scan steps+1). Each target is simulated independently, so the
//    covariances differ between targets. Every matrix is I2 ⊗ (one axis), so P = I2 ⊗ p,
//    S_i = s_i·I2 and the gates are circles; the code works on p and s_i.
//  - Track estimate = true position + N(0, HPH') ("corrupted with additive Gaussian noise with
//    covariance distributed according to the prior covariance"); only positions matter for ψ.
//  - Detection with probability Pd, z = truth + N(0, R); innovation covariance S = HPH' + R.
//  - Gate: (z − ẑ)'S⁻¹(z − ẑ) ≤ γ with γ = −2 ln(gate_miss), the χ²(2) threshold whose miss
//    probability is gate_miss (paper: 10⁻⁴).
//  - False alarms: Poisson with mean λ_fa·area, uniform over the axis-aligned box covering every
//    gate ellipse (track i spans ẑ_i ± sqrt(γ S_i(d,d)) per axis): "sufficiently large to cover
//    these gates".
//  - Eq (11) with existence r_t = 1 and constant Pd: ψ_i(j) = Pd·N(z_j; ẑ_i, S_i) / (λ_fa(1 − Pd))
//    inside the gate, 0 outside.
//  - weight_floor (default 0): ψ below it is set to 0 before any algorithm sees it, as the
//    paper's experiment 1 thresholds "the weights utilised in all algorithms" at 1e-4.
//  - Measurements gated by no track are dropped (they cannot change any marginal) but counted in
//    ScenarioSample::false_alarms; the rest are shuffled so their order does not reveal origin.
//  - validate() also refuses settings whose expected false-alarm count (with the never-detected
//    prior) exceeds 10⁷ per scan, so a typo such as spacing=1e9 fails at once instead of
//    exhausting memory in the first trial.
//
// Draw order (stable; a change alters every trial's numbers):
//  1. per target i = 0..n−1: `steps` bernoulli(Pd) for the history, then 2 normals (estimate x, y);
//  2. per target i = 0..n−1: bernoulli(Pd), and if detected 2 normals (measurement noise x, y);
//  3. poisson(λ_fa·area), then per false alarm uniform x, uniform y;
//  4. Fisher–Yates shuffle of the M measurements: for k = M−1..1 one uniform.
#include <Eigen/Core>
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "harness/core/params.hpp"
#include "harness/single_scan/scenario.hpp"

namespace dabench {

struct GridOptions {
  int rows = 2;             // grid rows of targets (paper: 2, n ∈ 2..30, or n ∈ 2..10)
  int cols = 3;             // grid columns of targets
  double spacing = 3.0;     // distance between neighbouring targets, ≥ 0 (paper: 0..10)
  double pd = 0.6;          // detection probability Pd, in (0, 1)
  double lambda_fa = 0.01;  // false-alarm density per unit area, > 0
  double r = 1.0;           // measurement noise variance, R = r·I2, > 0
  double q = 0.01;          // process noise intensity, ≥ 0
  double T = 1.0;           // sampling period, > 0
  int steps = 30;           // scans simulated before this one to build each covariance, ≥ 0
  double gate_miss = 1e-4;  // probability that a target's measurement falls outside its gate
  double weight_floor = 0;  // ψ below this is set to 0 for every algorithm (paper's exp. 1: 1e-4)

  void bind(ParamList& p) {
    p.add("rows", rows, "grid rows of targets");
    p.add("cols", cols, "grid columns of targets");
    p.add("spacing", spacing, "distance between neighbouring targets (>= 0)");
    p.add("pd", pd, "detection probability, in (0, 1)");
    p.add("lambda_fa", lambda_fa, "false-alarm density per unit area (> 0)");
    p.add("r", r, "measurement noise variance, R = r*I (> 0)");
    p.add("q", q, "process noise intensity of the constant-velocity model (>= 0)");
    p.add("T", T, "sampling period (> 0)");
    p.add("steps", steps, "scans simulated to build each track covariance (>= 0)");
    p.add("gate_miss", gate_miss, "probability a target's measurement falls outside its gate, in (0, 1)");
    p.add("weight_floor", weight_floor, "weights psi below this are zeroed for all algorithms (>= 0)");
  }
  std::string validate() const;  // "" if valid, else which field breaks which rule
  double gate_threshold() const { return -2.0 * std::log(gate_miss); }  // γ, χ²(2) quantile
};

// The constant-velocity model of Sec. V. F, Q, H and R all have the form I2 ⊗ (one axis) and the
// recursion starts at P = 0, so every covariance is I2 ⊗ p, with p the 2×2 (position, velocity)
// covariance of one axis: the recursion runs on p, exactly, with 2×2 products in place of 4×4.
struct ConstantVelocityModel {
  Eigen::Matrix2d f;   // one axis of F: [[1, T], [0, 1]]
  Eigen::Matrix2d q1;  // one axis of Q: q·[[T³/3, T²/2], [T²/2, T]]
  double r;            // R = r·I2

  ConstantVelocityModel(double q, double T, double r);
  Eigen::Matrix2d predict(const Eigen::Matrix2d& p) const;  // f p f' + q1
  Eigen::Matrix2d update(const Eigen::Matrix2d& p) const;   // p − k h p, h = [1 0], k = p h'/(h p h' + r)
};

// I2 ⊗ axis: the 4×4 matrix over the state [x, vx, y, vy].
inline Eigen::Matrix4d lift(const Eigen::Matrix2d& axis) {
  Eigen::Matrix4d full = Eigen::Matrix4d::Zero();
  full.block<2, 2>(0, 0) = full.block<2, 2>(2, 2) = axis;
  return full;
}

// One axis of the prior covariance P_{t|t−1} after `steps` simulated scans from P = 0 (Sec. V):
// detected_at(k) says whether scan k = 0..steps−1 updated the track.
template <class DetectedAt>
Eigen::Matrix2d prior_covariance(const ConstantVelocityModel& model, int steps, DetectedAt&& detected_at) {
  Eigen::Matrix2d p = Eigen::Matrix2d::Zero();
  for (int k = 0; k < steps; ++k) {
    p = model.predict(p);
    if (detected_at(k)) p = model.update(p);
  }
  return model.predict(p);
}

// What a draw contains besides the problem (for tests, diagnostics and pictures like Fig. 5).
struct GridDetails {
  struct Target {
    Eigen::Vector2d truth;       // true position
    Eigen::Vector2d estimate;    // prior track estimate ẑ_i
    Eigen::Matrix4d prior;       // P_{t|t−1} = I2 ⊗ p
    Eigen::Matrix2d innovation;  // S_i = H P H' + R = (p(0,0) + r)·I2
    bool detected = false;
    Eigen::Vector2d measurement = Eigen::Vector2d::Zero();  // its detection (even if gated out)
  };
  std::vector<Target> targets;
  std::vector<Eigen::Vector2d> measurements;  // position of each column of ψ
  Eigen::Vector2d box_lo, box_hi;             // false-alarm region
  double area() const { return (box_hi - box_lo).prod(); }
};

class GridScenario final : public SingleScanScenario {
 public:
  using Options = GridOptions;
  static constexpr std::string_view kName = "grid";
  static constexpr std::string_view kSummary =
      "Sec. V of Williams & Lau 2014: targets on a grid, CV-model track covariances, uniform clutter";

  explicit GridScenario(const Options& options);
  void generate(RandomStream& rng, ScenarioSample& sample) const override;
  // The same draw (same numbers); also fills `details` unless it is null.
  void generate(RandomStream& rng, ScenarioSample& sample, GridDetails* details) const;
  const Options& options() const { return options_; }

 private:
  Options options_;
  ConstantVelocityModel model_;
  double gamma_;      // gate threshold
  double psi_scale_;  // Pd / (λ_fa (1 − Pd) 2π): eq (11) without the 1/sqrt(det S) factor
};

}  // namespace dabench
