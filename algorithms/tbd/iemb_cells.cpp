#include "algorithms/tbd/iemb_cells.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "harness/core/log_gamma.hpp"

namespace dabench {

// ---- the cell model ----------------------------------------------------------------------------

PowerMoments power_moments(double noise_variance, double own, double zc, double sc) {
  const double mean = noise_variance + own + zc;
  return {mean, mean * mean + 2.0 * sc};
}

int IembWindow::cell(int c) const {
  return (row_begin + c / columns()) * grid_columns + column_begin + c % columns();
}

IembWindow iemb_window(const TbdSensor& sensor, const Eigen::Vector4d& mean, const Eigen::Matrix4d& covariance,
                       double margin, double position_sigmas, int max_cells) {
  // Cells whose centre origin + (i + ½)Δ lies in [centre − radius, centre + radius].
  const auto range = [&](double centre, double variance, double origin, int limit, int& begin, int& end) {
    const double radius = margin + position_sigmas * std::sqrt(std::max(variance, 0.0));
    const auto index = [&](double v) { return std::clamp(v, -1.0, limit + 1.0); };
    if (!std::isfinite(centre) || !std::isfinite(radius)) {
      begin = end = 0;
      return;
    }
    begin = std::clamp(static_cast<int>(std::ceil(index((centre - radius - origin) / sensor.cell_size - 0.5))), 0, limit);
    end = std::clamp(static_cast<int>(std::floor(index((centre + radius - origin) / sensor.cell_size - 0.5))) + 1, 0, limit);
    end = std::max(begin, end);
    if (end - begin > max_cells) {
      const int own = static_cast<int>(std::floor(index((centre - origin) / sensor.cell_size)));
      begin = std::clamp(own - max_cells / 2, begin, end - max_cells);
      end = begin + max_cells;
    }
  };
  IembWindow w;
  w.grid_columns = sensor.columns;
  range(mean(0), covariance(0, 0), sensor.x_min, sensor.columns, w.column_begin, w.column_end);
  range(mean(1), covariance(1, 1), sensor.y_min, sensor.rows, w.row_begin, w.row_end);
  if (w.columns() == 0 || w.rows() == 0) w.column_end = w.column_begin, w.row_end = w.row_begin;
  return w;
}

IembCellModel::IembCellModel(const TbdSensor& sensor, double amplitude, IembMeasurementKind kind)
    : sensor_(&sensor), kind_(kind) {
  const SpreadCoefficients k = sensor.coefficients(amplitude);  // harness/tbd/problem.hpp: the readings
  mean_per_spread_ = k.mean;
  variance_per_spread_ = k.variance;
  variance_per_spread2_ = k.variance2;
}

void IembCellModel::evaluate(const SigmaPoints& sigma, const IembWindow& window, SigmaMatrix& h,
                             SigmaMatrix& variance) const {
  for (int p = 0; p < SigmaPoints::kCount; ++p) evaluate_at(sigma.points[p], window, h.col(p).data(), variance.col(p).data());
}

void IembCellModel::evaluate_at(const Eigen::Vector4d& state, const IembWindow& window, double* h,
                                double* variance) const {
  const TbdSensor& s = *sensor_;
  const int columns = window.columns();
  const int rows = window.rows();
  const double scale = 1.0 / (2.0 * s.spread_variance);
  std::array<double, kMaxSide> gx, gy;
  for (int a = 0; a < columns; ++a) {
    const double dx = s.centre_x(window.column_begin + a) - state(0);
    gx[a] = std::exp(-dx * dx * scale);
  }
  for (int b = 0; b < rows; ++b) {
    const double dy = s.centre_y(window.row_begin + b) - state(1);
    gy[b] = std::exp(-dy * dy * scale);
  }
  for (int b = 0; b < rows; ++b) {
    for (int a = 0; a < columns; ++a) {
      const int c = b * columns + a;
      const double g = gx[a] * gy[b];
      const double v = (variance_per_spread_ + variance_per_spread2_ * g) * g;
      variance[c] = v;
      if (kind_ == IembMeasurementKind::power) {
        h[c] = v;
      } else {
        h[2 * c] = mean_per_spread_ * g;
        h[2 * c + 1] = 0.0;
      }
    }
  }
}

void IembCellModel::moments(const SigmaPoints& sigma, int cells, const SigmaMatrix& h, const SigmaMatrix& variance,
                            CellMoments& out) const {
  out.mean.resize(cells);
  out.second.resize(cells);
  for (int c = 0; c < cells; ++c) {
    Eigen::Vector2d m = Eigen::Vector2d::Zero();
    Eigen::Matrix2d y = Eigen::Matrix2d::Zero();
    for (int p = 0; p < SigmaPoints::kCount; ++p) {
      const double w = sigma.weights[p];
      if (kind_ == IembMeasurementKind::power) {
        m(0) += w * h(c, p);
        y(0, 0) += w * h(c, p) * h(c, p);
      } else {
        const Eigen::Vector2d v(h(2 * c, p), h(2 * c + 1, p));
        m += w * v;
        y.noalias() += w * (v * v.transpose() + variance(c, p) * Eigen::Matrix2d::Identity());
      }
    }
    out.mean[c] = m;
    out.second[c] = y;
  }
}

void IembField::reset(int cells) {
  mean_.assign(cells, Eigen::Vector2d::Zero());
  covariance_.assign(cells, Eigen::Matrix2d::Zero());
}

void IembField::add(const IembWindow& window, const CellMoments& own, double existence) {
  const double r = existence;
  for (int c = 0; c < window.cells(); ++c) {
    const int j = window.cell(c);
    mean_[j] += r * own.mean[c];
    covariance_[j] += r * own.second[c] - r * r * own.mean[c] * own.mean[c].transpose();
  }
}

void IembField::remove(const IembWindow& window, const CellMoments& own, double existence) {
  const double r = existence;
  for (int c = 0; c < window.cells(); ++c) {
    const int j = window.cell(c);
    mean_[j] -= r * own.mean[c];
    covariance_[j] -= r * own.second[c] - r * r * own.mean[c] * own.mean[c].transpose();
  }
}

void IembField::exchange(const IembWindow& window, const CellMoments& own, double existence,
                         std::vector<Eigen::Vector2d>& zc, std::vector<Eigen::Matrix2d>& sc) const {
  const double r = existence;
  zc.resize(window.cells());
  sc.resize(window.cells());
  for (int c = 0; c < window.cells(); ++c) {
    const int j = window.cell(c);
    zc[c] = mean_[j] - r * own.mean[c];
    sc[c] = covariance_[j] - (r * own.second[c] - r * r * own.mean[c] * own.mean[c].transpose());
  }
}

void IembCellMeasurement::prepare(const IembCellModel& model, double noise_variance, const IembWindow& window,
                                  const Eigen::Matrix2Xd& frame, const std::vector<double>& powers,
                                  const std::vector<Eigen::Vector2d>& zc, const std::vector<Eigen::Matrix2d>& sc) {
  model_ = &model;
  powers_ = &powers;
  window_ = window;
  noise_variance_ = noise_variance;
  zc_ = &zc;
  sc_ = &sc;
  q = model.rows_per_cell();
  cells = window.cells();
  if (residual.size() < q * cells) residual.resize(q * cells);
  if (variance_.rows() < cells) variance_.resize(cells, Eigen::NoChange);
  absent_covariance.resize(cells);
  for (int c = 0; c < cells; ++c) {
    const int j = window.cell(c);
    if (q == 1) {
      const PowerMoments absent = power_moments(noise_variance, 0.0, zc[c](0), sc[c](0, 0));
      residual(c) = powers[j] - absent.mean;
      absent_covariance[c] = Eigen::Matrix2d::Zero();
      absent_covariance[c](0, 0) = absent.variance;
    } else {
      residual.segment<2>(2 * c) = frame.col(j) - zc[c];
      absent_covariance[c] = noise_variance * Eigen::Matrix2d::Identity() + sc[c];
    }
  }
}

double IembCellMeasurement::gamma_log_likelihood(const Eigen::Vector4d* state) {
  if (state != nullptr) {
    if (at_state_.size() < cells) at_state_.resize(cells);
    model_->evaluate_at(*state, window_, at_state_.data(), at_state_.data());  // power: h = c_j
  }
  double total = 0.0;
  for (int c = 0; c < cells; ++c) {
    const double y = std::max((*powers_)[window_.cell(c)], std::numeric_limits<double>::min());
    const PowerMoments m = power_moments(noise_variance_, state != nullptr ? at_state_(c) : 0.0, (*zc_)[c](0),
                                         (*sc_)[c](0, 0));
    const double shape = m.mean * m.mean / m.variance;
    const double scale = m.variance / m.mean;
    total += (shape - 1.0) * std::log(y) - y / scale - shape * std::log(scale) - log_gamma(shape);
  }
  return total;
}

void IembCellMeasurement::evaluate(const SigmaPoints& sigma, SigmaMatrix& h, std::vector<Eigen::Matrix2d>& noise) {
  model_->evaluate(sigma, window_, h, variance_);
  for (int c = 0; c < cells; ++c) {
    const Eigen::Vector2d& zc = (*zc_)[c];
    const Eigen::Matrix2d& sc = (*sc_)[c];
    if (q == 1) {
      double v = 0.0;
      for (int p = 0; p < SigmaPoints::kCount; ++p) {
        v += sigma.weights[p] * power_moments(noise_variance_, variance_(c, p), zc(0), sc(0, 0)).variance;
      }
      noise[c] = Eigen::Matrix2d::Zero();
      noise[c](0, 0) = v;
    } else {
      double v = 0.0;
      for (int p = 0; p < SigmaPoints::kCount; ++p) v += sigma.weights[p] * variance_(c, p);
      noise[c] = (noise_variance_ + v) * Eigen::Matrix2d::Identity() + sc;
    }
  }
}

}  // namespace dabench
