#pragma once
// The separable TBD likelihood of TBD-MB (docs/models/track-before-detect.md §4.1 [R]) on an object's support:
// an object at position p contributes to the cells S(p) whose centre lies within `radius` of
// p, and alone there (other objects' supports are disjoint from its own: cell_exclusion.hpp).
// Against the noise-only image its likelihood ratio is
//   ℓ(z | p) = Π_{j∈S(p)} N(z_j; μ_j(p), (σ² + c_j(p)) I₂) / N(z_j; 0, σ² I₂),
// with μ_j and c_j of the sensor reading (problem.hpp: D1 or D2). The cells outside S(p) are
// explained by noise; the default radius 2σ_h holds about 96 % of a cell-centred object's
// energy Σ_j g_j (D1: 77 % at a cell corner).
#include <algorithm>
#include <cmath>

#include <Eigen/Core>

#include "harness/tbd/problem.hpp"

namespace dabench {

// Calls visit(column, row) for every cell whose centre lies within `radius` of (px, py), among
// columns [column_begin, column_end) and rows [row_begin, row_end).
template <class Visit>
void visit_support(const TbdSensor& s, double radius, double px, double py, int column_begin, int column_end,
                   int row_begin, int row_end, Visit&& visit) {
  const int c0 = std::max(column_begin, static_cast<int>(std::ceil((px - radius - s.x_min) / s.cell_size - 0.5)));
  const int c1 = std::min(column_end - 1, static_cast<int>(std::floor((px + radius - s.x_min) / s.cell_size - 0.5)));
  const int r0 = std::max(row_begin, static_cast<int>(std::ceil((py - radius - s.y_min) / s.cell_size - 0.5)));
  const int r1 = std::min(row_end - 1, static_cast<int>(std::floor((py + radius - s.y_min) / s.cell_size - 0.5)));
  const double limit = radius * radius;
  for (int row = r0; row <= r1; ++row) {
    const double dy = s.centre_y(row) - py;
    for (int column = c0; column <= c1; ++column) {
      const double dx = s.centre_x(column) - px;
      if (dx * dx + dy * dy <= limit) visit(column, row);
    }
  }
}

class SupportLikelihood {
 public:
  SupportLikelihood() = default;
  SupportLikelihood(const TbdSensor& sensor, double amplitude, double radius)
      : sensor_(&sensor), amplitude_(amplitude), radius_(radius) {}
  double radius() const { return radius_; }
  // log ℓ(z | p) for the frame (2 × J).
  double log_ratio(const Eigen::Matrix2Xd& frame, double px, double py) const;

 private:
  const TbdSensor* sensor_ = nullptr;
  double amplitude_ = 0.0;
  double radius_ = 0.0;
};

}  // namespace dabench
