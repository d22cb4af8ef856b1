#pragma once
// Frames for the track-before-detect tests, drawn from the superpositional model of
// harness/tbd/problem.hpp with the tests' own code (not the scenario's), on small grids; the
// problems the trackers' tests build from them (grid, known prior, one moving object).
#include <cmath>
#include <cstdint>
#include <numbers>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "harness/core/random_stream.hpp"
#include "harness/tbd/problem.hpp"

namespace dabench::test {

// One cell's μ_j and c_j (problem.hpp restated): g = exp(−‖c_j − p‖²/(2σ_h²)); D1: μ = 0,
// c = σ_S² γ/2 g; D2: μ = (γ Δ²/(2πσ_h²) g, 0), c = σ_S² g²; D3: μ = (√(ργ) g, 0),
// c = (1 − ρ) σ_S² γ/2 g.
inline void cell_signal(const TbdSensor& s, double gamma, int column, int row, double px, double py,
                        Eigen::Vector2d& mu, double& c) {
  const double dx = s.x_min + (column + 0.5) * s.cell_size - px;
  const double dy = s.y_min + (row + 0.5) * s.cell_size - py;
  const double g = std::exp(-(dx * dx + dy * dy) / (2.0 * s.spread_variance));
  if (s.signal == TbdSignal::fluctuating) {
    mu.setZero();
    c = s.signal_scale * 0.5 * gamma * g;
  } else if (s.signal == TbdSignal::deterministic) {
    mu = Eigen::Vector2d(gamma * s.cell_size * s.cell_size / (2.0 * std::numbers::pi * s.spread_variance) * g, 0.0);
    c = s.signal_scale * g * g;
  } else {
    mu = Eigen::Vector2d(std::sqrt(s.mean_share * gamma) * g, 0.0);
    c = (1.0 - s.mean_share) * s.signal_scale * 0.5 * gamma * g;
  }
}

// z_j = ε_j + Σ_objects h_j, h_j ~ N(μ_j, c_j I₂), ε_j ~ N(0, σ² I₂).
inline Eigen::Matrix2Xd draw_frame(const TbdSensor& s, double gamma, const std::vector<Eigen::Vector2d>& positions,
                                   RandomStream& rng) {
  Eigen::Matrix2Xd z(2, s.cells());
  const double sd = std::sqrt(s.noise_variance);
  for (int row = 0; row < s.rows; ++row) {
    for (int column = 0; column < s.columns; ++column) {
      Eigen::Vector2d v(sd * rng.normal(), sd * rng.normal());
      for (const Eigen::Vector2d& p : positions) {
        Eigen::Vector2d mu;
        double c = 0.0;
        cell_signal(s, gamma, column, row, p.x(), p.y(), mu, c);
        v += mu + std::sqrt(c) * Eigen::Vector2d(rng.normal(), rng.normal());
      }
      z.col(row * s.columns + column) = v;
    }
  }
  return z;
}

// A size × size grid of 1 m cells, γ = 60, σ² = 1, σ_S² = 1, σ_h² = 0.5; no frames yet.
inline TbdProblem grid_problem(int size, TbdSignal signal, std::uint64_t seed, std::uint32_t trial) {
  TbdProblem p;
  p.sensor.columns = p.sensor.rows = size;
  p.sensor.cell_size = 1.0;
  p.sensor.signal = signal;
  p.sensor.noise_variance = 1.0;
  p.sensor.signal_scale = 1.0;
  p.sensor.spread_variance = 0.5;
  p.amplitude = 60.0;
  p.trial_key = {seed, 0, trial};
  return p;
}

// draw_frame with the problem's sensor and amplitude.
inline Eigen::Matrix2Xd problem_frame(const TbdProblem& p, const std::vector<Eigen::Vector2d>& positions,
                                      RandomStream& rng) {
  return draw_frame(p.sensor, p.amplitude, positions, rng);
}

// A prior at rest at (x, y): position variance `variance` per axis, velocity variance 1e-4.
inline TbdPrior prior_at(double x, double y, double variance, double existence) {
  TbdPrior prior;
  prior.mean = Eigen::Vector4d(x, y, 0.0, 0.0);
  prior.covariance = Eigen::Vector4d(variance, variance, 1e-4, 1e-4).asDiagonal();
  prior.existence = existence;
  return prior;
}

// A problem holding one object whose prior is known, and the object's true state per step.
struct KnownObject {
  TbdProblem problem;
  std::vector<Eigen::Vector4d> truth;
};

// `steps` frames of one object starting at (5.5, 6.5) (cell (5, 6)'s centre on a grid of 1 m
// cells) with velocity (0.1, −0.05) and moving by the problem's NCV model; its prior is that
// initial state (r = 1, position variance 0.01, velocity variance 1e-4). Each step after the
// first draws the acceleration (two normals from `rng`), then every step draws its frame with
// frame(problem, positions, rng): the test's own frame code and stream.
template <class DrawFrame>
KnownObject known_object(TbdProblem problem, int steps, RandomStream& rng, DrawFrame&& frame) {
  KnownObject o;
  o.problem = std::move(problem);
  TbdProblem& p = o.problem;
  Eigen::Vector4d x(5.5, 6.5, 0.1, -0.05);
  TbdPrior prior;
  prior.mean = x;
  prior.covariance = Eigen::Vector4d(0.01, 0.01, 1e-4, 1e-4).asDiagonal();
  prior.existence = 1.0;
  p.initial_objects.push_back(prior);
  const double t = p.motion.scan_interval;
  const double sd = std::sqrt(p.motion.driving_noise_variance);
  for (int k = 0; k < steps; ++k) {
    if (k > 0) {
      const double ax = sd * rng.normal(), ay = sd * rng.normal();
      x = Eigen::Vector4d(x(0) + t * x(2) + 0.5 * t * t * ax, x(1) + t * x(3) + 0.5 * t * t * ay, x(2) + t * ax,
                          x(3) + t * ay);
    }
    o.truth.push_back(x);
    p.frames.push_back(frame(p, {x.head<2>()}, rng));
  }
  return o;
}

// For INFO lines of tests run under both signal models.
inline const char* signal_name(TbdSignal s) {
  return s == TbdSignal::fluctuating ? "D1 fluctuating" : "D2 deterministic";
}

}  // namespace dabench::test
