// Tests of the TBD-BP message passing between potential objects and data cells
// (algorithms/tbd/cell_messages.hpp; tbd-bp-supplement eqs (5), (9); docs/models/track-before-detect.md §3.3):
// the per-cell totals of the Gaussian κ̃ at iteration 1, against the model of
// harness/tbd/problem.hpp restated independently (tests/support/cell_messages.hpp):
//  - The per-cell totals e, V equal the direct sums over the other POs' particles.
//  - A PO's window is the cells whose centre lies within the support radius of its particles'
//    box, and cells outside it contribute nothing.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <Eigen/Dense>

#include "algorithms/tbd/cell_messages.hpp"
#include "algorithms/tbd/particle_object.hpp"
#include "harness/core/random_stream.hpp"
#include "harness/tbd/problem.hpp"
#include "tests/support/cell_messages.hpp"

namespace DABENCH_TEST_FILE {

namespace {

using namespace dabench;
using namespace dabench::test::cell_messages;
using dabench::test::signal_name;

// PO o's α-weighted signal moments at cell j, from its particles: μ_{n,j} = r Σ_i w_i μ_j(x_i),
// R_{n,j} = r Σ_i w_i (c_j(x_i) I + μ_j μ_jᵀ).
Moments alpha_moments(const Model& m, const ParticleObject& o, int j) {
  Moments mo;
  for (int i = 0; i < o.size(); ++i) {
    const Eigen::Vector2d mu = m.mu(j, o.x[i], o.y[i]);
    mo.mu += o.existence * o.weight[i] * mu;
    mo.R += o.existence * o.weight[i] * (m.c(j, o.x[i], o.y[i]) * Eigen::Matrix2d::Identity() + mu * mu.transpose());
  }
  return mo;
}

// A PO's totals at a cell with measurement z are e = z − Σ μ and V = σ² I + Σ (R − μμᵀ), the
// sums over `others`, the moments there of the other POs that reach the cell.
void check_totals(const CellMessages::CellTerms& terms, const Model& m, const Eigen::Vector2d& z,
                  const std::vector<Moments>& others) {
  Eigen::Vector2d e = z;
  Eigen::Matrix2d v = m.sensor.noise_variance * Eigen::Matrix2d::Identity();
  for (const Moments& other : others) {
    e -= other.mu;
    v += other.R - other.mu * other.mu.transpose();
  }
  CHECK(terms.e_x == close(e.x()));
  CHECK(terms.e_y == close(e.y()));
  CHECK(terms.v_xx == close(v(0, 0)));
  CHECK(terms.v_xy == close(v(0, 1)));
  CHECK(terms.v_yy == close(v(1, 1)));
}

}  // namespace

TEST_CASE("tbd cell messages: per-cell totals e and V are the direct sums over the other POs at iteration 1",
          "[tbd][cell_messages][totals]") {
  for (const TbdSignal signal : {TbdSignal::fluctuating, TbdSignal::deterministic}) {
    INFO(signal_name(signal));
    ThreeObjects t = three_objects(signal, 5);
    const Model& m = t.model;
    CellMessages messages;
    run_whole_grid(messages, t, 1);
    const int count = static_cast<int>(t.objects.size());
    std::vector<std::vector<Moments>> direct(count, std::vector<Moments>(m.cells()));
    for (int n = 0; n < count; ++n) {
      for (int j = 0; j < m.cells(); ++j) direct[n][j] = alpha_moments(m, t.objects[n], j);
    }
    for (int n = 0; n < count; ++n) {
      for (int j = 0; j < m.cells(); ++j) {
        INFO("PO " << n << ", cell " << j);
        const auto& terms = messages.cell_terms(n, j);
        CHECK(terms.mean_x == close(direct[n][j].mu.x()));
        CHECK(terms.mean_y == close(direct[n][j].mu.y()));
        CHECK(terms.r_xx == close(direct[n][j].R(0, 0)));
        CHECK(terms.r_xy == close(direct[n][j].R(0, 1)));
        CHECK(terms.r_yy == close(direct[n][j].R(1, 1)));
        std::vector<Moments> others;
        for (int o = 0; o < count; ++o) {
          if (o != n) others.push_back(direct[o][j]);
        }
        check_totals(terms, m, t.frame.col(j), others);
      }
    }
  }
}

TEST_CASE("tbd cell messages: windows are the cells within the support radius and cells outside contribute nothing",
          "[tbd][cell_messages][window]") {
  // Three POs on an 8 × 7 grid with a 1.7 m radius, so the windows differ and overlap in part.
  // Particles lie within 0.1 m of integer coordinates, so every window edge lies 0.2..0.4 m past
  // an integer and no cell centre is within 0.05 m of it (checked): the expected window is
  // unambiguous.
  for (const TbdSignal signal : {TbdSignal::fluctuating, TbdSignal::deterministic}) {
    INFO(signal_name(signal));
    Model m = small_model(signal, 8, 7);
    RandomStream rng(kSeed, 2, 0);
    std::vector<ParticleObject> objects;
    objects.push_back(random_object(rng, 2.0, 2.0, 0.1, 5, 0.6, 0));
    objects.push_back(random_object(rng, 4.0, 3.0, 0.1, 5, 0.4, 1));
    objects.push_back(random_object(rng, 6.0, 5.0, 0.1, 5, 0.7, 2));
    const double radius = 1.7;
    for (const ParticleObject& o : objects) {
      const auto [x_low, x_high] = std::minmax_element(o.x.begin(), o.x.end());
      const auto [y_low, y_high] = std::minmax_element(o.y.begin(), o.y.end());
      for (int c = 0; c < m.sensor.columns; ++c) {
        REQUIRE(std::abs(m.cx(c) - (*x_low - radius)) > 0.05);
        REQUIRE(std::abs(m.cx(c) - (*x_high + radius)) > 0.05);
      }
      for (int r = 0; r < m.sensor.rows; ++r) {
        REQUIRE(std::abs(m.cy(r) - (*y_low - radius)) > 0.05);
        REQUIRE(std::abs(m.cy(r) - (*y_high + radius)) > 0.05);
      }
    }
    const Eigen::Matrix2Xd frame = draw_frame(m, {{2.0, 2.0}, {4.0, 3.0}}, rng);
    CellMessages messages;
    CellMessageOptions options;
    options.iterations = 1;
    options.support_radius = radius;
    REQUIRE(messages.run(m.sensor, m.gamma, frame, pointers(objects), options));
    std::vector<CellWindow> windows;
    for (int n = 0; n < 3; ++n) {
      windows.push_back(expected_window(m, objects[n], radius));
      require_window(messages.window(n), windows.back());
    }
    // By hand: columns 0..3 × rows 0..3, 2..5 × 1..4, 4..7 × 3..6.
    require_window(windows[0], CellWindow{0, 4, 0, 4});
    require_window(windows[1], CellWindow{2, 6, 1, 5});
    require_window(windows[2], CellWindow{4, 8, 3, 7});
    // The windows are not trivial: PO 0 and 1 overlap in part, and none covers the grid.
    int shared01 = 0;
    for (int j = 0; j < m.cells(); ++j) shared01 += in_window(m, windows[0], j) && in_window(m, windows[1], j);
    REQUIRE(shared01 > 0);
    REQUIRE(windows[0].cells() < m.cells());

    for (int n = 0; n < 3; ++n) {
      for (int j = 0; j < m.cells(); ++j) {
        if (!in_window(m, windows[n], j)) continue;
        INFO("PO " << n << ", cell " << j);
        const auto& terms = messages.cell_terms(n, window_slot(m, windows[n], j));
        std::vector<Moments> others;  // the POs whose windows hold cell j
        for (int o = 0; o < 3; ++o) {
          if (o != n && in_window(m, windows[o], j)) others.push_back(alpha_moments(m, objects[o], j));
        }
        check_totals(terms, m, frame.col(j), others);
      }
    }
  }
}

}  // namespace DABENCH_TEST_FILE
