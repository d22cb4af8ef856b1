#include "algorithms/tbd/support_likelihood.hpp"

#include <cmath>

namespace dabench {

double SupportLikelihood::log_ratio(const Eigen::Matrix2Xd& frame, double px, double py) const {
  const TbdSensor& s = *sensor_;
  const double noise = s.noise_variance;
  double sum = 0.0;
  visit_support(s, radius_, px, py, 0, s.columns, 0, s.rows, [&](int column, int row) {
    const CellContribution h = s.contribution(column, row, px, py, amplitude_);
    const Eigen::Vector2d z = frame.col(row * s.columns + column);
    const double variance = noise + h.variance;
    // 2-D: log N(z; μ, v I₂) = −log(2π v) − ‖z − μ‖²/(2v).
    sum += -std::log(variance / noise) - (z - h.mean).squaredNorm() / (2.0 * variance) + z.squaredNorm() / (2.0 * noise);
  });
  return sum;
}

}  // namespace dabench
