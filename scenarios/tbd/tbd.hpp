#pragma once
// Track-before-detect scenario "tbd": image frames for the TBD-BP letter (Liang, Kropfreiter &
// Meyer, "A BP method for track-before-detect", IEEE SPL 2023) and tbd-bp-supplement. One draw
// is one Monte Carlo run: the truth (TbdTruth) and K frames of J cells (TbdProblem).
//
// Frames (model of harness/tbd/problem.hpp, supplement eq (1)): frame k holds per cell
//   z_j = Σ_n h_{j,n} + σ ε_j,  h_{j,n} ~ N(μ_j(x_n), c_j(x_n) I₂),  ε_j ~ N(0, I₂),
// over the objects existing at k, all independent; h = μ_j + √c_j · w (TbdSensor::contribution)
// in the cells whose centre lies within kSupportRadius = 8 σ_h of the object (beyond, g_j <
// e^{−32}). `signal` picks the reading of μ_j, c_j: d1, d2 or d3 (problem.hpp); `spread_variance`
// = 0 takes the reading's own (0.5, 1.5, 0.58 m²). Region [0, columns·Δ] × [0, rows·Δ].
//
// Truth: NCV motion with the truth's own `truth_noise_variance` (the filters get
// `driving_noise_variance` through TbdMotion). An object exists from its birth to its death step
// (inclusive) while inside the region; once outside it never returns. Absent steps are NaN.
//  - crossing: object 0 slow (kSlowSpeed), drawn at step m₀ = ⌈L₀/2⌉ near kSlowAnchor (tbd.cpp),
//    present at steps 1..L₀; objects 1.. cross: drawn at step ⌈K/2⌉ near kCrossingAnchor, speed
//    U[kSpeedMin, kSpeedMax], birth U{1..B}, death U{D..K}; uniform headings, positions N(anchor,
//    kPositionSd² I). Each is propagated forward to its death and backward (x_{k−1} =
//    A⁻¹(x_k − W a)) to its birth. B, D, L₀: crossing_windows() (20, 30, 35 for K = 50).
//    Anchors scale with the region; speeds and spreads stay in metres.
//  - persistent: every object born at step 1, uniform in the middle half of the region
//    (kPersistentMargin), propagated to step K.
//  - toy: 10 × 10 cells, one step, objects at (4, 4) and (5, 5) at rest; the problem carries
//    their α as initial objects, N(p; p_n, 0.3 I₂) δ(v), existence 1, and birth_mean = 0. Since
//    the options cannot tell a set key from its default, `objects`, `steps`, `columns`, `rows`
//    and `cell_size` must each be its default or the toy's value (2, 1, 10, 10, 1). `frame` (toy
//    only; scenarios/tbd/magnitude_frame.hpp) replaces the drawn frame by a file's magnitudes.
//
// Draw order (stable; a change alters every run's numbers):
//  1. Truth, per object in index order. crossing, object 0: normal, normal (position),
//     uniform (heading), then per step forward two normals (acceleration x, y), then backward;
//     objects ≥ 1: uniform (birth), uniform (death), normal, normal, uniform (heading), uniform
//     (speed), then forward, then backward. persistent: uniform (x), uniform (y), uniform
//     (heading), uniform (speed), then forward. toy: nothing (with `frame`: no draws at all).
//     A propagation stops at its first step outside the region (no further draws).
//  2. Frames, per step: per cell j = 0..J−1 two normals (σ ε_j, x then y); then per existing
//     object in index order, per cell of its support in increasing j, two normals (w).
//
// Background and our readings: docs/models/track-before-detect.md (§0 the tags [S], [F], [C],
// [R] used below; §1 the readings D1–D3 and their calibration; §2 the layouts; §6 our readings).
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "harness/core/params.hpp"
#include "harness/tbd/scenario.hpp"

namespace dabench {

enum class TbdLayout { crossing, persistent, toy };

// D3's parameters, fitted to the supplement's Fig. 1(a) and Fig. 2 (results/tbd/REPORT.md,
// "Calibration of D3"; experiments/tbd/calibration.py checks that they are the fit).
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
