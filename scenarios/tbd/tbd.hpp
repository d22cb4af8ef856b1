#pragma once
// Track-before-detect scenario "tbd": image frames for the TBD-BP letter (Liang, Kropfreiter &
// Meyer, "A BP method for track-before-detect", IEEE SPL 2023) and its supplement
// (papers/tbd-bp-supplement.txt). One draw is one Monte Carlo run. The letter's body (its
// Sec. IV) could not be had, so most of this is reconstruction: tags as in
// ../shared/tbd-bp-model.md §0 — [S] the supplement states it, [F] read from the supplement's
// figures, [C] the IEMB authors' code does it, [R] a documented default no source states.
//
// Measurement model (harness/tbd/problem.hpp; tbd-bp-model.md §1):
//  - Frame k holds one z_j ∈ R² per cell, z_j = Σ_n h_{j,n} + σ ε_j, h_{j,n} ~ N(μ_j(x_n), c_j I₂)
//    over the objects n existing at k, ε_j ~ N(0, I₂), all independent ([S] eq (1), §1.1).
//    Drawn as h = μ_j + √c_j · w with w ~ N(0, I₂) (TbdSensor::contribution).
//  - Readings (§1.3, [R]): `signal` = d1 (fluctuating: μ_j = 0, c_j = σ_S² γ/2 g_j), d2
//    (deterministic: μ_j = (γ ψ_j, 0), small c_j) or d3 (mixed: μ_j = (√(ργ) g_j, 0),
//    c_j = (1 − ρ) σ_S² γ/2 g_j; problem.hpp). σ² = 1 [F] (the Rayleigh(1) background of
//    Fig. 2, §1.2), γ = 60 [S] (toy example), σ_S² = 1 [S] (Fig. 2 caption; its meaning is [R]).
//    σ_h² = 0.5 m² for d1 and 1.5 m² for d2 [R] (§1.3: calibrated to the ≈180 excess energy of
//    an isolated object in Fig. 2 [F]; d1 gives E Σ_j ‖h_j‖² = σ_S² γ 2πσ_h²/Δ² = 188.5);
//    d3's ρ = 0.66 and σ_h² = 0.58 m² maximise the likelihood of the readable cells of Fig. 1(a)
//    (Rice densities given the toy's objects) times that of Fig. 2's excess energy [F]
//    (results/tbd/REPORT.md shows the fit and its profile over ρ).
//  - Support: an object's contribution is added to the cells whose centre lies within 8 σ_h of
//    it; beyond, g_j < e^{−32} ≈ 1.3·10⁻¹⁴ (for d1 a standard deviation √(30 g) < 10⁻⁶ against
//    the noise's 1).
//  - Region [0, columns·Δ] × [0, rows·Δ]; default 32 × 32 cells of Δ = 1 m [F] (Fig. 2 axes).
//
// Truth (positions in m, velocities in m/s, speeds in m per step = |v|·T, steps 1-based here;
// 0-based in the arrays):
//  - Motion: nearly constant velocity (TbdMotion), T = 1 s [R]. The truth's acceleration noise
//    `truth_noise_variance` (1e-4 m²/s⁴ [R]) is separate from the filter's σ_a² =
//    `driving_noise_variance` (0.01 [R], the Meyer-group default, §2.3): Fig. 2's tracks are
//    nearly straight lines [F], while σ_a² = 0.01 over 25 steps moves the velocity by
//    √(25·0.01) = ±0.5 m/s (the speeds themselves are 0.1–0.3 m/step) and the position by
//    √(0.01·25³/3) ≈ ±7 m. At 1e-4 the crossing objects' velocities drift by ±0.05 m/s over 25
//    steps; the slow object's by ±0.04 m/s over its 17 steps either side of m₀, comparable to
//    its own speed, so its heading is not kept (in Fig. 2 the slow object moves 0.054, then
//    0.023 m/step between the panels k = 14, 21, 27 [F], so it may wander too).
//  - An object exists from its birth to its death step (inclusive) while inside the region;
//    once it leaves it stops existing and never comes back (§2.3). Absent steps are NaN columns.
//  - layout = crossing (the letter's Sec. IV as reconstructed in §2.2–2.3):
//      object 0, slow: state at step m₀ = ⌈L₀/2⌉ has position ~ N(a₀, 0.5² I), a₀ = (12.7, 7.5)
//        [F], uniform heading, speed 0.05 m/step [F]; present at steps 1..L₀, L₀ = 35 [F].
//      objects 1..objects−1, crossing: state at step m = ⌈K/2⌉ (25 of 50, the centre of the
//        window 20..30 where all of them exist; §2.3 writes k_mid = 24) has position
//        ~ N(a, 0.5² I), a = (22.5, 18.5) [F], uniform heading, speed U[0.1, 0.3] m/step [F];
//        birth step uniform in 1..B, death step uniform in D..K, B = 20 and D = 30 for K = 50
//        [R]. From the middle step the state is propagated forward to the death step and
//        backward (x_{k−1} = A⁻¹(x_k − W a)) to the birth step, as the IEMB generator
//        Trajectory_cross.m does [C].
//      Other K scale the windows: B = max(1, round(0.4 K)), D = max(B, round(0.6 K)),
//      L₀ = round(0.7 K) (halves rounded up), so B ≤ m ≤ D. Another region scales the anchors
//      a and a₀ with its size (they are 22.5/32, 18.5/32 and 12.7/32, 7.5/32 of its width and
//      height); speeds and spreads stay in metres.
//  - layout = persistent (the supplement's runtime study, §3 [S]: objects exist for all 50
//    steps unless they leave): `objects` objects born at step 1, positions uniform over the
//    middle half of the region in each coordinate ([8, 24]² for 32 m), uniform heading, speed
//    U[0.1, 0.3] m/step, propagated to step K. With the defaults 88 % stay inside all 50 steps
//    (0.879 over 40 000 objects; 0.900 with truth_noise_variance = 0; straight-line margins of
//    4 / 10 m instead of 8 would give 0.77 / 0.95) [R].
//  - layout = toy (supplement §1.3 [S]): 10 × 10 cells of 1 m, objects at (4, 4) and (5, 5) (cell
//    corners) with zero velocity, one step. The problem carries the two POs' α as initial
//    objects, N(p; p_n, 0.3 I₂) δ(v), existence 1, and birth_mean = 0 (no new POs). The option
//    machinery cannot tell a key that was set from its default, so `objects`, `steps`,
//    `columns`, `rows` and `cell_size` must each be its default or the toy's value (2, 1, 10,
//    10, 1); anything else is an error. With `frame` = a file (scenarios/tbd/magnitude_frame.hpp;
//    experiments/data/tbd-fig1a-frame.csv is the supplement's Fig. 1(a) digitised), that frame
//    replaces the drawn one (z_j = (|z_j|, 0); its unread cells get `unread_magnitude`, by
//    default the background's median σ√(2 ln 2)) and nothing is drawn; `frame` needs layout = toy.
//
// The problem's filter model (TbdFilterModel, §2.3 [R]): p_s = 0.99, μ_B = 0.01, birth velocity
// s.d. 0.3 m/s — what trackers assume, not what drew the truth.
//
// Draw order (stable; a change alters every run's numbers):
//  1. Truth, per object in index order:
//     crossing, object 0: normal, normal (position at m₀), uniform (heading); then per step
//       forward from m₀ two normals (acceleration x, y), then per step backward two normals;
//     crossing, objects ≥ 1: uniform (birth step), uniform (death step), normal, normal
//       (position at m), uniform (heading), uniform (speed); then forward, then backward;
//     persistent: uniform (x), uniform (y), uniform (heading), uniform (speed); then forward;
//     toy: nothing.
//  (toy with `frame`: no draws at all.)
//     A propagation stops at the first step outside the region (no further draws).
//  2. Frames, per step: per cell j = 0..J−1 two normals (σ ε_j, x then y); then per existing
//     object in index order, per cell of its support in increasing j, two normals (w).
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "harness/core/params.hpp"
#include "harness/tbd/scenario.hpp"

namespace dabench {

enum class TbdLayout { crossing, persistent, toy };

// D3's parameters, fitted to the supplement's Fig. 1(a) and Fig. 2 (results/tbd/REPORT.md,
// "Calibration of D3"; reports/studies/tbd_calibration.py checks that they are the fit).
constexpr double kMeanShareD3 = 0.66;
constexpr double kSpreadD3 = 0.58;

struct TbdImageOptions {
  int layout = 0;                       // crossing | persistent | toy (see the header)
  int objects = 5;                      // crossing: objects − 1 crossing + 1 slow; persistent: all
  int steps = 50;                       // K [S]
  int columns = 32;                     // cells along x [F]
  int rows = 32;                        // cells along y [F]
  double cell_size = 1.0;               // Δ, m [S]
  int signal = 0;                       // d1 (fluctuating) | d2 (deterministic) | d3 (mixed) [R]
  double sigma_s2 = 1.0;                // σ_S² [S]
  double mean_share = kMeanShareD3;     // ρ of d3: the share of the power in the mean [F: Fig. 1, 2 fit]
  double noise_variance = 1.0;          // σ², C_ε = σ² I₂ [F]
  double spread_variance = 0.0;         // σ_h², m²; 0: the reading's own (d1 0.5, d2 1.5, d3 0.58) [R]
  double amplitude = 60.0;              // γ [S]
  double driving_noise_variance = 0.01; // filter's σ_a², m²/s⁴ [R]
  double truth_noise_variance = 1e-4;   // truth's σ_a², m²/s⁴ [R]
  double scan_interval = 1.0;           // T, s [R]
  double survival_probability = 0.99;   // filter's p_s [R]
  double birth_mean = 0.01;             // filter's μ_B per step [R]
  double birth_speed_sd = 0.3;          // filter's birth velocity s.d., m/s [R]
  std::string frame;                    // toy: a file of cell magnitudes replacing the drawn frame
  double unread_magnitude = -1.0;       // toy frame file: value of its `nan` cells; < 0: σ√(2 ln 2)

  void bind(ParamList& p) {
    p.add_choice("layout", layout, {"crossing", "persistent", "toy"},
                 "truth: crossing (letter Sec. IV), persistent (runtime study), toy (supplement 1.3)");
    p.add("objects", objects, "number of objects (crossing: includes the slow one), in 1..1000 (persistent: 0..1000)");
    p.add("steps", steps, "number of frames K, in 1..10000");
    p.add("columns", columns, "cells along x, in 1..1024");
    p.add("rows", rows, "cells along y, in 1..1024");
    p.add("cell_size", cell_size, "cell side, m, in (0, 1000]");
    p.add_choice("signal", signal, {"d1", "d2", "d3"},
                 "d1: fluctuating (mu = 0); d2: deterministic mean; d3: mean share + fluctuation");
    p.add("sigma_s2", sigma_s2, "signal scale sigma_S^2, in [0, 1e6]");
    p.add("mean_share", mean_share, "d3: share rho of the signal power in the mean, in [0, 1]");
    p.add("noise_variance", noise_variance, "noise variance sigma^2 per component, in (0, 1e6]");
    p.add("spread_variance", spread_variance, "spread sigma_h^2, m^2, in [0, 1e6]; 0: d1 0.5, d2 1.5, d3 0.58");
    p.add("amplitude", amplitude, "object amplitude gamma, in [0, 1e6]");
    p.add("driving_noise_variance", driving_noise_variance, "filter's acceleration variance, m^2/s^4, in [0, 100]");
    p.add("truth_noise_variance", truth_noise_variance, "truth's acceleration variance, m^2/s^4, in [0, 100]");
    p.add("scan_interval", scan_interval, "seconds between frames T, in (0, 1000]");
    p.add("survival_probability", survival_probability, "filter's survival probability, in [0, 1]");
    p.add("birth_mean", birth_mean, "filter's expected new objects per step, in [0, 1000]");
    p.add("birth_speed_sd", birth_speed_sd, "filter's birth velocity s.d., m/s, in [0, 1000]");
    p.add("frame", frame, "toy: file of cell magnitudes (rows bottom first; nan = unread) replacing the drawn frame");
    p.add("unread_magnitude", unread_magnitude, "toy frame file: magnitude given to nan cells; < 0: the background median");
  }
  std::string validate() const;  // "" if valid, else which field breaks which rule

  TbdLayout layout_kind() const { return static_cast<TbdLayout>(layout); }
  TbdSignal signal_kind() const { return static_cast<TbdSignal>(signal); }
  double effective_spread_variance() const;  // σ_h² with 0 resolved by the reading
};

// Adds one step's objects to `frame` (2 × J, already holding the noise): for each position in
// order and each cell of its support (centre within 8 σ_h) in increasing j, μ_j + √c_j · w with
// two normals w. Public so that tests and trackers' tests can draw frames for chosen positions.
void add_tbd_objects(const TbdSensor& sensor, double amplitude, const std::vector<Eigen::Vector2d>& positions,
                     RandomStream& rng, Eigen::Matrix2Xd& frame);
// One whole frame: σ ε_j for every cell (two normals per cell, in j order), then add_tbd_objects.
void draw_tbd_frame(const TbdSensor& sensor, double amplitude, const std::vector<Eigen::Vector2d>& positions,
                    RandomStream& rng, Eigen::Matrix2Xd& frame);

class TbdImageScenario final : public TbdScenario {
 public:
  using Options = TbdImageOptions;
  static constexpr std::string_view kName = "tbd";
  static constexpr std::string_view kSummary =
      "TBD-BP letter Sec. IV (reconstructed): 32x32 image frames, 4 crossing + 1 slow object, Rayleigh background";

  static constexpr double kSupportRadius = 8.0;       // support of an object, in σ_h
  static constexpr double kPositionSd = 0.5;          // s.d. of the anchored positions, m [R]
  static constexpr double kSpeedMin = 0.1;            // m/step [F]
  static constexpr double kSpeedMax = 0.3;            // m/step [F]
  static constexpr double kSlowSpeed = 0.05;          // m/step [F]
  static constexpr double kPersistentMargin = 0.25;   // of the region's width/height, each side [R]

  // Crossing layout's windows for K steps, 1-based: birth in 1..birth_last, death in
  // death_first..K, middle step of the crossing objects, last step of the slow object.
  struct Windows {
    int birth_last, death_first, middle, slow_last;
  };
  static Windows crossing_windows(int steps);

  explicit TbdImageScenario(const Options& options);
  void generate(RandomStream& rng, TbdSample& sample) const override;
  const Options& options() const { return options_; }  // as used: the toy layout's values forced
  const TbdSensor& sensor() const { return sensor_; }  // the grid and reading generate() uses

 private:
  Options options_;
  TbdSensor sensor_;
  Eigen::Matrix2Xd file_frame_;  // toy: the frame of options_.frame, if set
};

}  // namespace dabench
