#pragma once
// Track-before-detect on images (tbd-bp-supplement; the letter's eq (1)), the fourth problem
// kind: K frames of J data cells on a regular grid, no detections. Cell j of frame k holds
// z_j ∈ R² drawn from the superpositional model
//
//   z_j = Σ_n r_n h_{j,n} + ε_j,   h_{j,n} | x_n ~ N(μ_j(x_n), C_j(x_n)),   ε_j ~ N(0, C_ε),
//
// all independent, so p(z_j | y) = N(z_j; Σ_n r_n μ_j(x_n), C_ε + Σ_n r_n C_j(x_n)) and the cells
// are conditionally independent given the objects (supplement eqs (1)-(9) rest on this).
// An object's state is x = [p_x, p_y, v_x, v_y] (m, m/s) with a known amplitude γ
// (docs/models/track-before-detect.md §1.1: the supplement's state also carries γ, held at δ(γ − 60)).
//
//  - TbdSensor: the grid and μ_j, C_j, C_ε (docs/models/track-before-detect.md §1.3, readings D1 and D2).
//  - TbdProblem: what a tracker may read — the frames and the model every tracker assumes
//    (motion, survival, birth), so that trackers compared on a run share one model.
//  - TbdTruth: what only metrics, tests and plots may read.
//  - TbdEstimate: a tracker's output at one step.
#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/Core>

#include "harness/core/random_stream.hpp"

namespace dabench {

// How an object's signal enters a cell (docs/models/track-before-detect.md §1.3; results/tbd/REPORT.md, "The
// readings"). All are isotropic in R²: C_j(x) = c_j(x) I₂, with g_j(p) = exp(−‖c_j − p‖²/(2σ_h²)),
// c_j the cell centre.
//  - fluctuating (D1): μ_j(x) = 0, c_j(x) = σ_S² (γ/2) g_j(p) — a Swerling-type amplitude whose
//    power spreads over the cells by g_j.
//  - deterministic (D2): μ_j(x) = (γ ψ_j(p), 0) with ψ_j(p) = Δ²/(2πσ_h²) g_j(p), and a small
//    c_j(x) = σ_S² g_j(p)² (that is σ_S² ψ_j² / ψ_max²).
//  - mixed (D3): a share ρ of the power in a mean along e₁, the rest fluctuating:
//    μ_j(x) = (√(ργ) g_j(p), 0), c_j(x) = (1 − ρ) σ_S² (γ/2) g_j(p). ρ = 0 is D1; a cell-centred
//    object puts E‖h_j‖² = γ in its cell at σ_S² = 1 for every ρ.
enum class TbdSignal { fluctuating, deterministic, mixed };

// One cell's share of one object: μ_j(x) and c_j(x) of C_j(x) = c_j(x) I₂.
struct CellContribution {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  double variance = 0.0;
};

// The readings as functions of g = g_j(p): μ_j = (mean · g, 0), c_j = variance · g + variance2 · g².
struct SpreadCoefficients {
  double mean = 0.0, variance = 0.0, variance2 = 0.0;
};

struct TbdSensor {
  int columns = 32;            // cells along x
  int rows = 32;               // cells along y
  double cell_size = 1.0;      // Δ, m (cells are Δ × Δ squares)
  double x_min = 0.0;          // lower-left corner of the region, m
  double y_min = 0.0;
  TbdSignal signal = TbdSignal::fluctuating;
  double noise_variance = 1.0;   // σ²: C_ε = σ² I₂
  double signal_scale = 1.0;     // σ_S² (the supplement's Fig. 2 caption: σ_S² = 1)
  double spread_variance = 0.5;  // σ_h², m²: width of g_j
  double mean_share = 0.0;       // ρ of D3 (ignored by D1, D2)

  int cells() const { return columns * rows; }
  // Cell j = row · columns + column; its centre c_j.
  double centre_x(int column) const { return x_min + (column + 0.5) * cell_size; }
  double centre_y(int row) const { return y_min + (row + 0.5) * cell_size; }
  double x_max() const { return x_min + columns * cell_size; }
  double y_max() const { return y_min + rows * cell_size; }
  bool inside(double px, double py) const { return px >= x_min && px < x_max() && py >= y_min && py < y_max(); }

  // g_j(p) of cell (column, row).
  double spread(int column, int row, double px, double py) const {
    const double dx = centre_x(column) - px;
    const double dy = centre_y(row) - py;
    return std::exp(-(dx * dx + dy * dy) / (2.0 * spread_variance));
  }
  SpreadCoefficients coefficients(double amplitude) const {
    switch (signal) {
      case TbdSignal::fluctuating:
        return {0.0, signal_scale * 0.5 * amplitude, 0.0};
      case TbdSignal::deterministic:
        return {amplitude * cell_size * cell_size / (2.0 * std::numbers::pi * spread_variance), 0.0, signal_scale};
      case TbdSignal::mixed:
        return {std::sqrt(mean_share * amplitude), (1.0 - mean_share) * signal_scale * 0.5 * amplitude, 0.0};
    }
    return {};
  }
  // μ_j(x) and c_j(x) for an object at (px, py) with amplitude γ.
  CellContribution contribution(int column, int row, double px, double py, double amplitude) const {
    const double g = spread(column, row, px, py);
    const SpreadCoefficients k = coefficients(amplitude);
    CellContribution c;
    c.mean.x() = k.mean * g;
    c.variance = (k.variance + k.variance2 * g) * g;
    return c;
  }
};

// Nearly-constant-velocity motion in (p, v): x_k = A x_{k−1} + W a_k, A = [I₂ T·I₂; 0 I₂],
// W = [T²/2·I₂; T·I₂], a_k ~ N(0, σ_a² I₂) (docs/models/track-before-detect.md §2.3).
struct TbdMotion {
  double scan_interval = 1.0;            // T, s
  double driving_noise_variance = 0.01;  // σ_a², m²/s⁴
};

// What every tracker assumes beside the sensor and the motion (docs/models/track-before-detect.md §2.3, §3.2).
struct TbdFilterModel {
  double survival_probability = 0.99;  // p_s (0 once an object's mean has left the region)
  double birth_mean = 0.01;            // μ_B, expected new objects per step, uniform over the region
  double birth_speed_sd = 0.3;         // new objects' velocity ~ N(0, σ_v² I₂), m/s
};

// A potential object known before frame 0, as the supplement's toy example gives them (§1.3:
// α_n(x, 1) = N(p; μ_n, 0.3 I₂) δ(v) δ(γ − 60), α_n(x, 0) = 0): Gaussian in x (the covariance
// may be singular, e.g. a known velocity), existence probability r.
struct TbdPrior {
  Eigen::Vector4d mean = Eigen::Vector4d::Zero();
  Eigen::Matrix4d covariance = Eigen::Matrix4d::Zero();
  double existence = 1.0;
};

struct TbdProblem {
  TbdSensor sensor;
  TbdMotion motion;
  TbdFilterModel filter;
  double amplitude = 60.0;               // γ, known and equal for every object
  std::vector<Eigen::Matrix2Xd> frames;  // per step k: 2 × J, column j = z_j
  std::vector<TbdPrior> initial_objects; // predicted objects at step 0 (before frame 0); usually none
  TrialKey trial_key;                    // for trackers that draw random numbers (particles)

  int steps() const { return static_cast<int>(frames.size()); }
};

struct TbdTruth {
  struct Object {
    Eigen::Matrix4Xd states;  // 4 × K; columns of steps where the object does not exist are NaN
    std::vector<bool> alive;  // per step
  };
  std::vector<Object> objects;
};

struct TbdSample {
  TbdProblem problem;
  TbdTruth truth;
};

// One reported object at one step.
struct TbdEstimate {
  Eigen::Vector4d state = Eigen::Vector4d::Zero();  // posterior mean [p, v]
  double existence = 0.0;                           // r̃ (or the filter's existence probability)
  int label = -1;                                   // the potential object it came from
};

}  // namespace dabench
