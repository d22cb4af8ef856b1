#pragma once
// Helpers of the TBD-BP cell-message tests (tests/tbd/test_cell_messages_*.cpp): the
// measurement model of harness/tbd/problem.hpp restated per cell, random particle objects and
// frames on small grids, a PO's window as algorithms/tbd/cell_messages.hpp defines it, and
// log-density helpers for the expected values.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <vector>

#include <Eigen/Dense>

#include "algorithms/tbd/cell_messages.hpp"
#include "algorithms/tbd/particle_object.hpp"
#include "harness/core/random_stream.hpp"
#include "harness/tbd/problem.hpp"
#include "tests/support/tbd_frames.hpp"

namespace dabench::test::cell_messages {

inline constexpr std::uint64_t kSeed = 20230711;

// The measurement model per cell (tests/support/tbd_frames.hpp's cell_signal): g_j(p) =
// exp(−‖c_j − p‖²/(2σ_h²)); D1: μ_j = 0, c_j = σ_S² γ/2 g; D2: μ_j = (γ Δ²/(2πσ_h²) g, 0),
// c_j = σ_S² g².
struct Model {
  TbdSensor sensor;
  double gamma = 60.0;

  int cells() const { return sensor.columns * sensor.rows; }
  double cx(int column) const { return sensor.x_min + (column + 0.5) * sensor.cell_size; }
  double cy(int row) const { return sensor.y_min + (row + 0.5) * sensor.cell_size; }
  Eigen::Vector2d mu(int cell, double px, double py) const {
    Eigen::Vector2d mu;
    double c = 0.0;
    cell_signal(sensor, gamma, cell % sensor.columns, cell / sensor.columns, px, py, mu, c);
    return mu;
  }
  double c(int cell, double px, double py) const {
    Eigen::Vector2d mu;
    double c = 0.0;
    cell_signal(sensor, gamma, cell % sensor.columns, cell / sensor.columns, px, py, mu, c);
    return c;
  }
};

// A columns × rows grid of 1 m cells with the readings of tests/support/tbd_frames.hpp's
// grid_problem: γ = 60, σ² = 1, σ_S² = 1, σ_h² = 0.5.
inline Model small_model(TbdSignal signal, int columns = 6, int rows = 6) {
  const TbdProblem grid = grid_problem(columns, signal, kSeed, 0);
  Model m{grid.sensor, grid.amplitude};
  m.sensor.rows = rows;
  return m;
}

// A frame of the model: z_j = ε_j + Σ over `positions` of h_j, h_j ~ N(μ_j, c_j I₂).
inline Eigen::Matrix2Xd draw_frame(const Model& m, const std::vector<Eigen::Vector2d>& positions, RandomStream& rng) {
  return test::draw_frame(m.sensor, m.gamma, positions, rng);
}

inline double log_normal(const Eigen::Vector2d& z, const Eigen::Vector2d& mean, const Eigen::Matrix2d& cov) {
  const Eigen::Vector2d d = z - mean;
  return -std::log(2.0 * std::numbers::pi) - 0.5 * std::log(cov.determinant()) - 0.5 * d.dot(cov.inverse() * d);
}

inline double log_sum_exp(const std::vector<double>& v) {
  double top = -std::numeric_limits<double>::infinity();
  for (double x : v) top = std::max(top, x);
  double s = 0.0;
  for (double x : v) s += std::exp(x - top);
  return top + std::log(s);
}

// `count` particles uniform in the square centre ± half_width, random positive weights
// (normalised), existence r.
inline ParticleObject random_object(RandomStream& rng, double cx, double cy, double half_width, int count, double r,
                                    int label) {
  ParticleObject o;
  o.resize(count);
  o.label = label;
  o.existence = r;
  double sum = 0.0;
  for (int i = 0; i < count; ++i) {
    o.x[i] = rng.uniform(cx - half_width, cx + half_width);
    o.y[i] = rng.uniform(cy - half_width, cy + half_width);
    o.vx[i] = 0.1 * rng.normal();
    o.vy[i] = 0.1 * rng.normal();
    o.weight[i] = rng.uniform(0.2, 1.0);
    sum += o.weight[i];
  }
  for (double& w : o.weight) w /= sum;
  return o;
}

// A PO's window as the header defines it: the cells whose centre lies within `radius` of the
// particles' bounding box (per axis), clipped to the grid.
inline CellWindow expected_window(const Model& m, const ParticleObject& o, double radius) {
  // On one axis of `count` cells with centres centre(k): [begin, end) of those in [low − radius,
  // high + radius] (begin = count, end = 0 if none).
  const auto axis = [radius](int count, auto centre, const std::vector<double>& positions, int& begin, int& end) {
    const auto [low, high] = std::minmax_element(positions.begin(), positions.end());
    begin = count;
    end = 0;
    for (int k = 0; k < count; ++k) {
      if (centre(k) >= *low - radius && centre(k) <= *high + radius) {
        begin = std::min(begin, k);
        end = std::max(end, k + 1);
      }
    }
  };
  CellWindow w;
  axis(m.sensor.columns, [&](int c) { return m.cx(c); }, o.x, w.column_begin, w.column_end);
  axis(m.sensor.rows, [&](int r) { return m.cy(r); }, o.y, w.row_begin, w.row_end);
  return w;
}

inline bool in_window(const Model& m, const CellWindow& w, int cell) {
  const int column = cell % m.sensor.columns, row = cell / m.sensor.columns;
  return column >= w.column_begin && column < w.column_end && row >= w.row_begin && row < w.row_end;
}

// The index within window w of grid cell `cell` (row-major over the window).
inline int window_slot(const Model& m, const CellWindow& w, int cell) {
  return (cell / m.sensor.columns - w.row_begin) * w.columns() + cell % m.sensor.columns - w.column_begin;
}

inline void require_window(const CellWindow& got, const CellWindow& want) {
  REQUIRE(got.column_begin == want.column_begin);
  REQUIRE(got.column_end == want.column_end);
  REQUIRE(got.row_begin == want.row_begin);
  REQUIRE(got.row_end == want.row_end);
}

// The POs as CellMessages::run takes them.
inline std::vector<ParticleObject*> pointers(std::vector<ParticleObject>& objects) {
  std::vector<ParticleObject*> p;
  for (ParticleObject& o : objects) p.push_back(&o);
  return p;
}

inline Approx close(double value, double relative = 1e-12, double absolute = 1e-11) {
  return Approx(value).epsilon(relative).margin(absolute);
}

// A PO's signal moments at one cell: μ_{n,j} and R_{n,j} (its second moment).
struct Moments {
  Eigen::Vector2d mu = Eigen::Vector2d::Zero();  // μ_{n,j}
  Eigen::Matrix2d R = Eigen::Matrix2d::Zero();   // R_{n,j}
};

// Three POs with 5, 4 and 6 particles near each other in the middle of a 6 × 6 grid, and a
// frame drawn with objects at their centres.
struct ThreeObjects {
  Model model;
  std::vector<ParticleObject> objects;
  Eigen::Matrix2Xd frame;
};

inline ThreeObjects three_objects(TbdSignal signal, std::uint32_t trial) {
  ThreeObjects t;
  t.model = small_model(signal);
  RandomStream rng(kSeed, 1, trial);
  t.objects.push_back(random_object(rng, 2.6, 2.5, 0.4, 5, rng.uniform(0.2, 0.9), 0));
  t.objects.push_back(random_object(rng, 3.3, 2.9, 0.4, 4, rng.uniform(0.2, 0.9), 1));
  t.objects.push_back(random_object(rng, 2.8, 3.5, 0.4, 6, rng.uniform(0.2, 0.9), 2));
  t.frame = draw_frame(t.model, {{2.6, 2.5}, {3.3, 2.9}, {2.8, 3.5}}, rng);
  return t;
}

// Runs `messages` for `iterations` iterations on t's POs and frame, every PO's window the whole
// grid (support radius 20 m).
inline void run_whole_grid(CellMessages& messages, ThreeObjects& t, int iterations) {
  CellMessageOptions options;
  options.iterations = iterations;
  options.support_radius = 20.0;
  REQUIRE(messages.run(t.model.sensor, t.model.gamma, t.frame, pointers(t.objects), options));
}

}  // namespace dabench::test::cell_messages
