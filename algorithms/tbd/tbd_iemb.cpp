#include "algorithms/tbd/tbd_iemb.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <fmt/format.h>

#include "harness/core/log_gamma.hpp"
#include "harness/tbd/registry.hpp"

namespace dabench {

namespace {

constexpr int kStateSize = 4;
constexpr int kUColumns = SigmaPoints::kCount + kStateSize;  // U = [√w_s e_s, A L_P]
constexpr int kColumnA = SigmaPoints::kCount;                 // the whitened M = [√w_s e_s, A, z − ẑ]
constexpr int kColumnInnovation = kColumnA + kStateSize;
const double kLog2Pi = std::log(2.0 * std::numbers::pi);

// The inverse of the top-left q × q block of `b` (q = 1 or 2) into `inverse`; returns its log
// determinant (NaN if the block is not positive definite).
double block_inverse(const Eigen::Matrix2d& b, int q, Eigen::Matrix2d& inverse) {
  if (q == 1) {
    inverse(0, 0) = 1.0 / b(0, 0);
    return b(0, 0) > 0.0 ? std::log(b(0, 0)) : std::numeric_limits<double>::quiet_NaN();
  }
  const double det = b(0, 0) * b(1, 1) - b(0, 1) * b(1, 0);
  inverse << b(1, 1) / det, -b(0, 1) / det, -b(1, 0) / det, b(0, 0) / det;
  return det > 0.0 && b(0, 0) > 0.0 ? std::log(det) : std::numeric_limits<double>::quiet_NaN();
}

// Eigenvalues below `floor` raised to it (symmetrised first).
Eigen::Matrix4d positive_definite(const Eigen::Matrix4d& p, double floor) {
  const Eigen::Matrix4d s = 0.5 * (p + p.transpose());
  if (Eigen::LLT<Eigen::Matrix4d>(s).info() == Eigen::Success) return s;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eigen(s);
  const Eigen::Vector4d values = eigen.eigenvalues().cwiseMax(floor);
  return eigen.eigenvectors() * values.asDiagonal() * eigen.eigenvectors().transpose();
}

// r' = r L₁ / ((1 − r) L₀ + r L₁), from log L₁, log L₀ (scaled by the larger, as [C]).
double updated_existence(double r, const IplfResult& result) {
  const double top = std::max(result.log_present, result.log_absent);
  const double present = r * std::exp(result.log_present - top);
  return present / ((1.0 - r) * std::exp(result.log_absent - top) + present);
}

}  // namespace

// ---- sigma points ------------------------------------------------------------------------------

bool make_sigma_points(const Eigen::Vector4d& mean, const Eigen::Matrix4d& covariance, SigmaPoints& out) {
  const double w0 = SigmaPoints::kCentreWeight;
  const Eigen::LLT<Eigen::Matrix4d> llt(kStateSize / (1.0 - w0) * covariance);
  if (llt.info() != Eigen::Success) return false;
  const Eigen::Matrix4d root = llt.matrixL();
  out.points[0] = mean;
  out.weights[0] = w0;
  for (int i = 0; i < kStateSize; ++i) {
    out.points[1 + i] = mean + root.col(i);
    out.points[1 + kStateSize + i] = mean - root.col(i);
    out.weights[1 + i] = out.weights[1 + kStateSize + i] = (1.0 - w0) / (2 * kStateSize);
  }
  return true;
}

double kl_divergence(const Eigen::Vector4d& m0, const Eigen::Matrix4d& p0, const Eigen::Vector4d& m1,
                     const Eigen::Matrix4d& p1) {
  const Eigen::LLT<Eigen::Matrix4d> l0(p0), l1(p1);
  if (l0.info() != Eigen::Success || l1.info() != Eigen::Success) return std::numeric_limits<double>::infinity();
  const Eigen::Vector4d diff = m1 - m0;
  const double log_det0 = 2.0 * l0.matrixL().toDenseMatrix().diagonal().array().log().sum();
  const double log_det1 = 2.0 * l1.matrixL().toDenseMatrix().diagonal().array().log().sum();
  return 0.5 * (log_det1 - log_det0 + l1.solve(p0).trace() + diff.dot(l1.solve(diff)) - kStateSize);
}

// ---- IPLF --------------------------------------------------------------------------------------

void IplfUpdate::reserve(int rows, int blocks) {
  if (h_.rows() < rows) {
    h_.resize(rows, Eigen::NoChange);
    m_.resize(rows, Eigen::NoChange);
    ybar_.resize(rows);
  }
  if (static_cast<int>(noise_.size()) < blocks) {
    noise_.resize(blocks, Eigen::Matrix2d::Zero());
    l00_.resize(blocks);
    l10_.resize(blocks);
    l11_.resize(blocks);
  }
}

// Block c of D = noise_[c] (q × q) = L Lᵀ; every column of `m` ← L⁻¹ (its rows of block c).
// Returns log det D (NaN if a block is not positive definite).
template <class Block>
double IplfUpdate::whiten(int q, int blocks, Block& m) {
  double log_det = 0.0;
  auto inverse00 = l00_.head(blocks);
  if (q == 1) {
    for (int c = 0; c < blocks; ++c) inverse00(c) = 1.0 / std::sqrt(noise_[c](0, 0));
    log_det = -2.0 * inverse00.array().log().sum();
    for (int k = 0; k < m.cols(); ++k) m.col(k).array() *= inverse00.array();
    return log_det;
  }
  auto lower10 = l10_.head(blocks);
  auto inverse11 = l11_.head(blocks);
  for (int c = 0; c < blocks; ++c) {
    const double l00 = std::sqrt(noise_[c](0, 0));
    const double l10 = noise_[c](1, 0) / l00;
    const double l11 = std::sqrt(noise_[c](1, 1) - l10 * l10);
    inverse00(c) = 1.0 / l00;
    lower10(c) = l10;
    inverse11(c) = 1.0 / l11;
  }
  log_det = -2.0 * (inverse00.array().log().sum() + inverse11.array().log().sum());
  using Strided = Eigen::Map<Eigen::VectorXd, 0, Eigen::InnerStride<2>>;
  for (int k = 0; k < m.cols(); ++k) {
    Strided first(m.col(k).data(), blocks), second(m.col(k).data() + 1, blocks);
    first.array() *= inverse00.array();
    second.array() = (second.array() - lower10.array() * first.array()) * inverse11.array();
  }
  return log_det;
}

IplfResult IplfUpdate::run(const Eigen::Vector4d& mean, const Eigen::Matrix4d& covariance,
                           IplfMeasurement& measurement, int max_iterations, double kl_threshold) {
  IplfResult result;
  result.mean = mean;
  result.covariance = covariance;
  const int q = measurement.q;
  const int blocks = measurement.cells;
  const int d = q * blocks;
  reserve(d, blocks);

  // L₀ = N(z; E[z | absent], Cov[z | absent]), block by block.
  for (int c = 0; c < blocks; ++c) {
    Eigen::Matrix2d inverse;
    const double log_det = block_inverse(measurement.absent_covariance[c], q, inverse);
    const auto r = measurement.residual.segment(q * c, q);
    result.log_absent -= 0.5 * (q * kLog2Pi + log_det + r.dot(inverse.topLeftCorner(q, q) * r));
  }
  result.log_present = result.log_absent;
  if (d == 0) return result;

  const Eigen::Matrix4d prior_root = Eigen::LLT<Eigen::Matrix4d>(covariance).matrixL();
  Eigen::Matrix<double, SigmaPoints::kCount, 1> weights;
  Eigen::Vector4d iterate_mean = mean;
  Eigen::Matrix4d iterate_covariance = covariance;
  SigmaPoints sigma;
  result.converged = false;
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    if (!make_sigma_points(iterate_mean, iterate_covariance, sigma)) break;
    for (int s = 0; s < SigmaPoints::kCount; ++s) weights(s) = sigma.weights[s];
    measurement.evaluate(sigma, h_, noise_);
    const auto h = h_.topRows(d);
    auto ybar = ybar_.head(d);
    auto m = m_.topRows(d);
    auto a = m.middleCols<kStateSize>(kColumnA);

    // SLR about the iterate: ȳ = Σ w_s h_s, Ψᵀ = Σ w_s (h_s − ȳ)(χ_s − u)ᵀ = Σ w_s h_s (χ_s − u)ᵀ
    // (the offsets' weighted sum is 0), A = Ψᵀ W⁻¹.
    ybar.noalias() = h * weights;
    Eigen::Matrix<double, SigmaPoints::kCount, kStateSize> offsets;
    for (int s = 0; s < SigmaPoints::kCount; ++s) {
      offsets.row(s) = sigma.weights[s] * (sigma.points[s] - iterate_mean).transpose();
    }
    const Eigen::Matrix4d iterate_inverse =
        Eigen::LLT<Eigen::Matrix4d>(iterate_covariance).solve(Eigen::Matrix4d::Identity());
    a.noalias() = h * (offsets * iterate_inverse);
    // Φ − A W Aᵀ = Σ w_s e_s e_sᵀ with the residuals e_s = h_s − ȳ − A (χ_s − u), so
    // S = A P Aᵀ + Ω + S_corr = D + U Uᵀ with U = [√w_s e_s, A L_P] (rank 13) and
    // D = Σ_s w_s Cov[z | χ_s] block diagonal (S_corr in it).
    for (int s = 0; s < SigmaPoints::kCount; ++s) {
      m.col(s).noalias() = std::sqrt(sigma.weights[s]) * (h.col(s) - ybar - a * (sigma.points[s] - iterate_mean));
    }
    // Innovation: z − ẑ, ẑ = E[z | absent] + A m + b, b = ȳ − A u.
    m.col(kColumnInnovation).noalias() = measurement.residual.head(d) - ybar - a * (mean - iterate_mean);

    // Whiten M = [√w e, A, z − ẑ] by D's block Cholesky factors (D = L Lᵀ, M ← L⁻¹M); then
    // Mᵀ M holds every product of S⁻¹ through Woodbury: S⁻¹ = D⁻¹ − D⁻¹U C⁻¹ UᵀD⁻¹ with
    // C = I + UᵀD⁻¹U, and det S = det D · det C.
    const double log_det_d = whiten(q, blocks, m);
    Eigen::Matrix<double, kWhitened, kWhitened> gram;
    gram.noalias() = m.transpose() * m;
    const auto ee = gram.topLeftCorner<SigmaPoints::kCount, SigmaPoints::kCount>();
    const auto ea = gram.block<SigmaPoints::kCount, kStateSize>(0, kColumnA);
    const Eigen::Matrix4d aa = gram.block<kStateSize, kStateSize>(kColumnA, kColumnA);
    const Eigen::Vector4d ar = gram.block<kStateSize, 1>(kColumnA, kColumnInnovation);
    Eigen::Matrix<double, kUColumns, kUColumns> capacitance = Eigen::Matrix<double, kUColumns, kUColumns>::Identity();
    capacitance.topLeftCorner<SigmaPoints::kCount, SigmaPoints::kCount>() += ee;
    capacitance.topRightCorner<SigmaPoints::kCount, kStateSize>() = ea * prior_root;
    capacitance.bottomLeftCorner<kStateSize, SigmaPoints::kCount>() = prior_root.transpose() * ea.transpose();
    capacitance.bottomRightCorner<kStateSize, kStateSize>() += prior_root.transpose() * aa * prior_root;
    Eigen::Matrix<double, kUColumns, kStateSize> ua;  // UᵀD⁻¹A
    ua << ea, prior_root.transpose() * aa;
    Eigen::Matrix<double, kUColumns, 1> ur;  // UᵀD⁻¹(z − ẑ)
    ur << gram.block<SigmaPoints::kCount, 1>(0, kColumnInnovation), prior_root.transpose() * ar;
    const Eigen::LLT<Eigen::Matrix<double, kUColumns, kUColumns>> cap(capacitance);
    const double log_det = log_det_d + 2.0 * cap.matrixL().toDenseMatrix().diagonal().array().log().sum();
    const Eigen::Matrix<double, kUColumns, kStateSize> cua = cap.solve(ua);
    const Eigen::Matrix4d at_s_a = aa - ua.transpose() * cua;   // Aᵀ S⁻¹ A
    const Eigen::Vector4d at_s_r = ar - cua.transpose() * ur;   // Aᵀ S⁻¹ (z − ẑ)
    const double r_s_r = gram(kColumnInnovation, kColumnInnovation) - ur.dot(cap.solve(ur));
    const double log_present = -0.5 * (d * kLog2Pi + log_det + r_s_r);

    // Kalman update of the prior: K = P Aᵀ S⁻¹.
    const Eigen::Vector4d next_mean = mean + covariance * at_s_r;
    Eigen::Matrix4d next_covariance = covariance - covariance * at_s_a * covariance;
    next_covariance = 0.5 * (next_covariance + next_covariance.transpose()).eval();
    if (!std::isfinite(log_present) || Eigen::LLT<Eigen::Matrix4d>(next_covariance).info() != Eigen::Success) break;
    const double kl = kl_divergence(iterate_mean, iterate_covariance, next_mean, next_covariance);
    iterate_mean = next_mean;
    iterate_covariance = next_covariance;
    result.log_present = log_present;
    ++result.iterations;
    if (kl < kl_threshold) {
      result.converged = true;
      break;
    }
  }
  result.mean = iterate_mean;
  result.covariance = iterate_covariance;
  return result;
}

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

// ---- the tracker -------------------------------------------------------------------------------

std::string TbdIembOptions::validate() const {
  if (iterations < 1 || iterations > 100) return "iterations must be in 1..100";
  if (!(kl_threshold > 0.0) || !std::isfinite(kl_threshold)) return "kl_threshold must be positive and finite";
  if (!(support_sigmas >= 1.0 && support_sigmas <= 10.0)) return "support_sigmas must be in [1, 10]";
  if (!(position_sigmas >= 0.0 && position_sigmas <= 10.0)) return "position_sigmas must be in [0, 10]";
  if (max_window < 3 || max_window > IembCellModel::kMaxSide) return "max_window must be in 3..64";
  if (!(detection_threshold > 0.0 && detection_threshold < 1.0)) return "detection_threshold must be in (0, 1)";
  if (!(pruning_threshold >= 0.0 && pruning_threshold < detection_threshold)) {
    return "pruning_threshold must be in [0, detection_threshold)";
  }
  if (!(merge_distance >= 0.0 && merge_distance <= 1000.0)) return "merge_distance must be in [0, 1000]";
  return {};
}

void TbdIemb::start(const TbdProblem& problem) {
  problem_ = &problem;
  const TbdSensor& sensor = problem.sensor;
  const bool zero_mean = sensor.coefficients(problem.amplitude).mean == 0.0;  // D1 (or D3 with ρ = 0)
  IembMeasurementKind kind = zero_mean ? IembMeasurementKind::power : IembMeasurementKind::complex;
  if (options_.measurement == 1) kind = IembMeasurementKind::complex;
  if (options_.measurement == 2) kind = IembMeasurementKind::power;
  skip_ = kind == IembMeasurementKind::power && !zero_mean;
  skip_reason_ = skip_ ? "measurement=power needs a zero-mean reading (D1); this problem's signal has a mean (D2, D3)" : "";
  model_ = IembCellModel(sensor, problem.amplitude, kind);
  margin_ = options_.support_sigmas * std::sqrt(sensor.spread_variance);
  next_label_ = 0;
  legacy_.clear();
  const int most_cells = options_.max_window * options_.max_window;
  h_.resize(2 * most_cells, Eigen::NoChange);
  variance_.resize(most_cells, Eigen::NoChange);
  powers_.assign(sensor.cells(), 0.0);

  // New Bernoullis: one per cell, r = (μ_B/J)/(1 + μ_B/J); their predicted terms are the same
  // every step, so their part of the field is formed once.
  const double birth = problem.filter.birth_mean / sensor.cells();
  birth_prior_.existence = birth / (1.0 + birth);
  const double position_variance = sensor.cell_size * sensor.cell_size / 12.0;
  const double speed_variance = problem.filter.birth_speed_sd * problem.filter.birth_speed_sd;
  birth_prior_.covariance = positive_definite(
      Eigen::Matrix4d(Eigen::Vector4d(position_variance, position_variance, speed_variance, speed_variance).asDiagonal()),
      kCovarianceJitter);
  birth_field_.reset(sensor.cells());
  if (birth_prior_.existence > 0.0) {
    for (int row = 0; row < sensor.rows; ++row) {
      for (int column = 0; column < sensor.columns; ++column) {
        birth_prior_.mean = Eigen::Vector4d(sensor.centre_x(column), sensor.centre_y(row), 0.0, 0.0);
        if (!predicted_moments(birth_prior_, scratch_work_)) {
          skip_ = true;
          skip_reason_ = "failed:the new Bernoullis' prior covariance is not positive definite";
          return;
        }
        birth_field_.add(scratch_work_.window, scratch_work_.own, birth_prior_.existence);
      }
    }
  }
  cell_head_.assign(sensor.cells(), -1);
}

// The state after a failed step is no filter's state: this step and every later one are skipped.
void TbdIemb::covariance_failure(SolveReport& report, int k) {
  skip_ = true;
  skip_reason_ = fmt::format("failed:step {}: a Bernoulli's covariance is not positive definite", k + 1);
  report.skipped = skip_reason_;
}

bool TbdIemb::predicted_moments(const GaussianBernoulli& b, Work& work) {
  work.window = iemb_window(problem_->sensor, b.mean, b.covariance, margin_, options_.position_sigmas,
                            options_.max_window);
  if (!make_sigma_points(b.mean, b.covariance, sigma_)) return false;
  model_.evaluate(sigma_, work.window, h_, variance_);
  model_.moments(sigma_, work.window.cells(), h_, variance_, work.own);
  return true;
}

IplfResult TbdIemb::update(const GaussianBernoulli& b, const Work& work, int max_iterations) {
  field_.exchange(work.window, work.own, b.existence, zc_, sc_);
  measurement_.prepare(model_, problem_->sensor.noise_variance, work.window, problem_->frames[frame_], powers_, zc_,
                       sc_);
  IplfResult result = iplf_.run(b.mean, b.covariance, measurement_, max_iterations, options_.kl_threshold);
  if (model_.kind() == IembMeasurementKind::power && options_.power_likelihood == 1) {
    // L₀ and L₁ from the Gamma densities; L₁ = p(y | m') N(m'; m, P) / N(m'; m', P') (Laplace).
    const Eigen::LLT<Eigen::Matrix4d> prior(b.covariance), posterior(result.covariance);
    const Eigen::Vector4d shift = result.mean - b.mean;
    const double log_det_prior = 2.0 * prior.matrixL().toDenseMatrix().diagonal().array().log().sum();
    const double log_det_posterior = 2.0 * posterior.matrixL().toDenseMatrix().diagonal().array().log().sum();
    result.log_absent = measurement_.gamma_log_likelihood(nullptr);
    result.log_present = measurement_.gamma_log_likelihood(&result.mean) -
                         0.5 * (log_det_prior - log_det_posterior + shift.dot(prior.solve(shift)));
  }
  return result;
}

void TbdIemb::step(int k, std::vector<TbdEstimate>& estimates, SolveReport& report) {
  estimates.clear();
  if (skip_) {
    report.skipped = skip_reason_;
    return;
  }
  const TbdProblem& problem = *problem_;
  const TbdSensor& sensor = problem.sensor;
  frame_ = k;
  if (model_.kind() == IembMeasurementKind::power) {
    for (int j = 0; j < sensor.cells(); ++j) powers_[j] = 0.5 * problem.frames[k].col(j).squaredNorm();
  }

  // 1. Prediction (k > 0) or the initial objects (k = 0).
  if (k == 0) {
    for (const TbdPrior& prior : problem.initial_objects) {
      legacy_.push_back({prior.mean, positive_definite(prior.covariance, kCovarianceJitter), prior.existence,
                         next_label_++});
    }
  } else {
    const double t = problem.motion.scan_interval;
    Eigen::Matrix4d f = Eigen::Matrix4d::Identity();
    f(0, 2) = f(1, 3) = t;
    Eigen::Matrix<double, 4, 2> w = Eigen::Matrix<double, 4, 2>::Zero();
    w(0, 0) = w(1, 1) = 0.5 * t * t;
    w(2, 0) = w(3, 1) = t;
    const Eigen::Matrix4d q = problem.motion.driving_noise_variance * w * w.transpose();
    for (GaussianBernoulli& b : legacy_) {
      b.mean = f * b.mean;
      b.covariance = f * b.covariance * f.transpose() + q;
      b.existence *= sensor.inside(b.mean(0), b.mean(1)) ? problem.filter.survival_probability : 0.0;
    }
  }
  std::erase_if(legacy_, [](const GaussianBernoulli& b) { return !(b.existence > 0.0); });

  // 2. Predicted measurement moments and the field of per-cell totals (new Bernoullis' part fixed).
  const int count = static_cast<int>(legacy_.size());
  legacy_work_.resize(count);
  field_ = birth_field_;
  for (int i = 0; i < count; ++i) {
    if (!predicted_moments(legacy_[i], legacy_work_[i])) return covariance_failure(report, k);
    field_.add(legacy_work_[i].window, legacy_work_[i].own, legacy_[i].existence);
  }

  // 3. IPLF update of each legacy Bernoulli against the others' predicted terms.
  int most = 0;
  bool converged = true;
  for (int i = 0; i < count; ++i) {
    GaussianBernoulli& b = legacy_[i];
    const IplfResult result = update(b, legacy_work_[i], options_.iterations);
    b.existence = updated_existence(b.existence, result);
    b.mean = result.mean;
    b.covariance = result.covariance;
    most = std::max(most, result.iterations);
    converged = converged && result.converged;
  }
  std::erase_if(legacy_, [&](const GaussianBernoulli& b) { return !(b.existence >= options_.pruning_threshold); });

  // 4. New Bernoullis against the legacy posteriors (field: the new ones' predicted terms and
  //    the legacy Bernoullis' terms at their posterior).
  field_ = birth_field_;
  for (const GaussianBernoulli& b : legacy_) {
    if (!predicted_moments(b, scratch_work_)) return covariance_failure(report, k);
    field_.add(scratch_work_.window, scratch_work_.own, b.existence);
  }
  if (!births()) return covariance_failure(report, k);

  for (const GaussianBernoulli& b : legacy_) {
    if (b.existence >= options_.detection_threshold) estimates.push_back({b.mean, b.existence, b.label});
  }
  report.iterations = most;
  report.converged = converged;
}

// Screening: one pass per cell's new Bernoulli; those reaching r ≥ pruning_threshold are
// candidates. Serially, in decreasing log L₁/L₀, each candidate is updated by the full IPLF
// against the field (which holds the candidates kept before it) and kept if r ≥
// pruning_threshold and its mean is not within merge_distance of a kept one (per-cell lists
// of kept means, so the search is local).
bool TbdIemb::births() {
  if (!(birth_prior_.existence > 0.0)) return true;
  const TbdSensor& sensor = problem_->sensor;
  GaussianBernoulli b = birth_prior_;
  const auto at_cell = [&](int j) {
    b.mean = Eigen::Vector4d(sensor.centre_x(j % sensor.columns), sensor.centre_y(j / sensor.columns), 0.0, 0.0);
  };
  candidates_.clear();
  for (int j = 0; j < sensor.cells(); ++j) {
    at_cell(j);
    if (!predicted_moments(b, scratch_work_)) return false;
    const IplfResult result = update(b, scratch_work_, 1);
    if (updated_existence(b.existence, result) >= options_.pruning_threshold) {
      candidates_.push_back({j, result.log_present - result.log_absent});
    }
  }
  std::sort(candidates_.begin(), candidates_.end(), [](const Candidate& x, const Candidate& y) {
    return x.log_ratio != y.log_ratio ? x.log_ratio > y.log_ratio : x.cell < y.cell;
  });
  const auto cell_of = [&](const Eigen::Vector4d& m) {
    const double column = std::clamp(std::floor((m(0) - sensor.x_min) / sensor.cell_size), 0.0, sensor.columns - 1.0);
    const double row = std::clamp(std::floor((m(1) - sensor.y_min) / sensor.cell_size), 0.0, sensor.rows - 1.0);
    return static_cast<int>(row) * sensor.columns + static_cast<int>(column);
  };
  const int reach = static_cast<int>(std::ceil(options_.merge_distance / sensor.cell_size));
  const std::size_t first = legacy_.size();
  cell_next_.clear();
  for (const Candidate& candidate : candidates_) {
    at_cell(candidate.cell);
    if (!predicted_moments(b, scratch_work_)) return false;
    const IplfResult result = update(b, scratch_work_, options_.iterations);
    const double r = updated_existence(b.existence, result);
    if (!(r >= options_.pruning_threshold)) continue;
    const int home = cell_of(result.mean);
    const int row = home / sensor.columns, column = home % sensor.columns;
    bool near = false;
    for (int y = std::max(0, row - reach); y <= std::min(sensor.rows - 1, row + reach) && !near; ++y) {
      for (int x = std::max(0, column - reach); x <= std::min(sensor.columns - 1, column + reach) && !near; ++x) {
        for (int a = cell_head_[y * sensor.columns + x]; a >= 0 && !near; a = cell_next_[a]) {
          near = (legacy_[first + a].mean.head<2>() - result.mean.head<2>()).norm() < options_.merge_distance;
        }
      }
    }
    if (near) continue;
    // Kept: its predicted term leaves the field, its posterior term enters it.
    field_.remove(scratch_work_.window, scratch_work_.own, b.existence);
    legacy_.push_back({result.mean, result.covariance, r, next_label_++});
    if (!predicted_moments(legacy_.back(), scratch_work_)) return false;
    field_.add(scratch_work_.window, scratch_work_.own, r);
    cell_next_.push_back(cell_head_[home]);
    cell_head_[home] = static_cast<int>(cell_next_.size()) - 1;
  }
  for (std::size_t i = first; i < legacy_.size(); ++i) cell_head_[cell_of(legacy_[i].mean)] = -1;
  return true;
}

void TbdIemb::beliefs(std::vector<TbdBeliefSample>& samples) const {
  samples.clear();
  SigmaPoints sigma;
  for (const GaussianBernoulli& b : legacy_) {
    if (!make_sigma_points(b.mean, b.covariance, sigma)) continue;
    for (int p = 0; p < SigmaPoints::kCount; ++p) {
      samples.push_back({b.label, b.existence, sigma.points[p](0), sigma.points[p](1), sigma.weights[p]});
    }
  }
}

DABENCH_REGISTER_TBD_TRACKER(TbdIemb);

}  // namespace dabench
