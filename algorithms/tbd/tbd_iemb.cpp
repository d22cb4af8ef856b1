#include "algorithms/tbd/tbd_iemb.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <fmt/format.h>

#include "harness/tbd/registry.hpp"

namespace dabench {

namespace {

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
