#include "algorithms/tracking/ukf.hpp"

#include <cmath>

#include <Eigen/Cholesky>
#include <fmt/format.h>

namespace dabench {

UnscentedFailure::UnscentedFailure(const std::string& which, int scan)
    : std::runtime_error(scan >= 0 ? fmt::format("ukf: {} covariance not positive definite at scan {}", which, scan)
                                   : fmt::format("ukf: {} covariance not positive definite", which)),
      scan_(scan) {}

namespace {

// The Cholesky factor of `covariance`; throws UnscentedFailure if it is not positive definite
// (Eigen's LLT fails on a non-positive pivot) or not finite (a NaN pivot passes that test).
Eigen::LLT<Eigen::MatrixXd> cholesky(const Eigen::MatrixXd& covariance, const char* which, int scan) {
  Eigen::LLT<Eigen::MatrixXd> llt(covariance);
  if (llt.info() != Eigen::Success || !llt.matrixLLT().allFinite()) throw UnscentedFailure(which, scan);
  return llt;
}

// Sigma points (columns) and weights of N(m, P), see the header.
struct SigmaPoints {
  Eigen::MatrixXd points;  // n × (2n + 1)
  Vector mean_weights, covariance_weights;
};

SigmaPoints sigma_points(const Gaussian& x, const UnscentedOptions& o, int scan) {
  const int n = static_cast<int>(x.mean.size());
  const double lambda = o.alpha * o.alpha * (n + o.kappa) - n;
  const Eigen::LLT<Eigen::MatrixXd> llt = cholesky(x.covariance, "state", scan);
  const Eigen::MatrixXd spread = std::sqrt(n + lambda) * Eigen::MatrixXd(llt.matrixL());
  SigmaPoints s;
  s.points.resize(n, 2 * n + 1);
  s.points.col(0) = x.mean;
  for (int i = 0; i < n; ++i) {
    s.points.col(1 + i) = x.mean + spread.col(i);
    s.points.col(1 + n + i) = x.mean - spread.col(i);
  }
  s.mean_weights = Vector::Constant(2 * n + 1, 1.0 / (2.0 * (n + lambda)));
  s.covariance_weights = s.mean_weights;
  s.mean_weights[0] = lambda / (n + lambda);
  s.covariance_weights[0] = lambda / (n + lambda) + 1.0 - o.alpha * o.alpha + o.beta;
  return s;
}

UnscentedTransform transform(const Gaussian& x, const std::function<Vector(const Vector&)>& g,
                             const UnscentedOptions& options, int scan) {
  const SigmaPoints s = sigma_points(x, options, scan);
  const int count = static_cast<int>(s.points.cols());
  std::vector<Vector> mapped(count);
  for (int i = 0; i < count; ++i) mapped[i] = g(s.points.col(i));
  const int m = static_cast<int>(mapped[0].size());
  UnscentedTransform t;
  t.mean = Vector::Zero(m);
  for (int i = 0; i < count; ++i) t.mean += s.mean_weights[i] * mapped[i];
  t.covariance = Eigen::MatrixXd::Zero(m, m);
  t.cross = Eigen::MatrixXd::Zero(x.mean.size(), m);
  for (int i = 0; i < count; ++i) {
    const Vector dy = mapped[i] - t.mean;
    t.covariance += s.covariance_weights[i] * dy * dy.transpose();
    t.cross += s.covariance_weights[i] * (s.points.col(i) - x.mean) * dy.transpose();
  }
  return t;
}

}  // namespace

std::string UnscentedOptions::validate(int dimension) const {
  if (!(alpha > 0.0 && alpha <= 1.0)) return fmt::format("alpha = {} must be in (0, 1]", alpha);
  if (!(beta >= 0.0)) return fmt::format("beta = {} must be >= 0", beta);
  if (!(dimension + kappa > 0.0)) return fmt::format("kappa = {} must exceed -{} (the state dimension)", kappa, dimension);
  return {};
}

UnscentedTransform unscented_transform(const Gaussian& x, const std::function<Vector(const Vector&)>& g,
                                       const UnscentedOptions& options) {
  return transform(x, g, options, -1);
}

void unscented_update(Gaussian& x, const ScanMeasurement& y, const std::function<Vector(const Vector&)>& h,
                      const UnscentedOptions& options, int scan) {
  const UnscentedTransform u = transform(x, h, options, scan);
  const Eigen::MatrixXd S = u.covariance + y.covariance;
  const Eigen::MatrixXd gain = cholesky(S, "innovation", scan).solve(u.cross.transpose()).transpose();  // C S⁻¹
  x.mean += gain * (y.value - u.mean);
  x.covariance = symmetrised(x.covariance - gain * S * gain.transpose());
}

std::vector<Gaussian> unscented_filter(const Gaussian& prior, const std::vector<std::optional<ScanMeasurement>>& scans,
                                       const UnscentedModel& model, const UnscentedOptions& options, int first_scan) {
  std::vector<Gaussian> filtered;
  filtered.reserve(scans.size());
  Gaussian current = prior;
  for (std::size_t k = 0; k < scans.size(); ++k) {
    const int scan = first_scan + static_cast<int>(k);
    if (k > 0) {  // predict (Särkkä 2008, Alg. 1 prediction step)
      const UnscentedTransform p = transform(current, model.transition, options, scan);
      current.mean = p.mean;
      current.covariance = symmetrised(p.covariance + model.process_covariance);
    }
    if (scans[k]) unscented_update(current, *scans[k], model.measure, options, scan);
    filtered.push_back(current);
  }
  return filtered;
}

std::vector<Gaussian> unscented_smoother(const std::vector<Gaussian>& filtered, const UnscentedModel& model,
                                         const UnscentedOptions& options, int first_scan) {
  std::vector<Gaussian> smoothed = filtered;
  for (int k = static_cast<int>(filtered.size()) - 2; k >= 0; --k) {
    // Särkkä 2008, Alg. 2: m⁻ and P⁻ of x_{k+1} from the filtered x_k, D = C (P⁻)⁻¹.
    const int scan = first_scan + k;
    const UnscentedTransform p = transform(filtered[k], model.transition, options, scan);
    const Eigen::MatrixXd predicted = p.covariance + model.process_covariance;
    const Eigen::MatrixXd gain = cholesky(predicted, "predicted", scan).solve(p.cross.transpose()).transpose();
    smoothed[k].mean = filtered[k].mean + gain * (smoothed[k + 1].mean - p.mean);
    smoothed[k].covariance =
        symmetrised(filtered[k].covariance + gain * (smoothed[k + 1].covariance - predicted) * gain.transpose());
  }
  return smoothed;
}

}  // namespace dabench
