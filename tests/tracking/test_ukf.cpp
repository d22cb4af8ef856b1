// Tests of the unscented Kalman filter and URTS smoother (algorithms/tracking/ukf.hpp): on a linear
// Gaussian model they must equal the Kalman filter and RTS smoother (written out here
// independently) to 1e-9, for the default and for other sigma-point parameters, with missing
// scans and per-scan measurement covariances; and the unscented transform of x² must give the
// closed-form mean m² + P and, with β = 2, the variance 4m²P + 2P².
#include <catch2/catch.hpp>

#include <cmath>
#include <optional>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "algorithms/tracking/ukf.hpp"
#include "harness/core/random_stream.hpp"

namespace DABENCH_TEST_FILE {

namespace {

using dabench::Gaussian;
using dabench::ScanMeasurement;
using dabench::UnscentedModel;
using dabench::UnscentedOptions;
using dabench::Vector;
using Eigen::MatrixXd;

struct LinearCase {
  MatrixXd F, Q, H;
  Gaussian prior;
  std::vector<std::optional<ScanMeasurement>> scans;
};

// A 4-state near-constant-velocity model with a 2-d linear measurement that mixes the
// coordinates; scans 3 and 7 have no measurement; R changes from scan to scan.
LinearCase make_case() {
  LinearCase c;
  const double T = 2.0;
  c.F = MatrixXd::Identity(4, 4);
  c.F(0, 1) = T;
  c.F(2, 3) = T;
  MatrixXd block(2, 2);
  block << T * T * T / 3.0, T * T / 2.0, T * T / 2.0, T;
  c.Q = MatrixXd::Zero(4, 4);
  c.Q.block(0, 0, 2, 2) = 0.05 * block;
  c.Q.block(2, 2, 2, 2) = 0.02 * block;
  c.H = MatrixXd::Zero(2, 4);
  c.H << 1.0, 0.0, 0.3, 0.0, -0.2, 0.0, 1.0, 0.5;
  c.prior.mean = Vector(4);
  c.prior.mean << 10.0, 1.0, -5.0, 0.5;
  c.prior.covariance = MatrixXd::Identity(4, 4);
  c.prior.covariance(0, 1) = c.prior.covariance(1, 0) = 0.3;
  dabench::RandomStream rng(42, 0, 0);
  Vector x = c.prior.mean;
  for (int k = 0; k < 12; ++k) {
    if (k > 0) x = c.F * x;
    if (k == 3 || k == 7) {
      c.scans.emplace_back();
      continue;
    }
    ScanMeasurement y;
    y.covariance = MatrixXd(2, 2);
    const double s = 0.5 + 0.1 * k;
    y.covariance << s, 0.1, 0.1, 2.0 * s;
    y.value = c.H * x + Vector::NullaryExpr(2, [&rng] { return rng.normal(); });
    c.scans.emplace_back(y);
  }
  return c;
}

UnscentedModel model_of(const LinearCase& c) {
  return {[F = c.F](const Vector& x) -> Vector { return F * x; }, c.Q,
          [H = c.H](const Vector& x) -> Vector { return H * x; }};
}

std::vector<Gaussian> kalman_filter(const LinearCase& c) {
  std::vector<Gaussian> out;
  Gaussian g = c.prior;
  for (std::size_t k = 0; k < c.scans.size(); ++k) {
    if (k > 0) {
      g.mean = c.F * g.mean;
      g.covariance = c.F * g.covariance * c.F.transpose() + c.Q;
    }
    if (c.scans[k]) {
      const MatrixXd S = c.H * g.covariance * c.H.transpose() + c.scans[k]->covariance;
      const MatrixXd K = g.covariance * c.H.transpose() * S.inverse();
      g.mean += K * (c.scans[k]->value - c.H * g.mean);
      g.covariance = (MatrixXd::Identity(4, 4) - K * c.H) * g.covariance;
    }
    out.push_back(g);
  }
  return out;
}

std::vector<Gaussian> rts_smoother(const LinearCase& c, const std::vector<Gaussian>& filtered) {
  std::vector<Gaussian> out = filtered;
  for (int k = static_cast<int>(filtered.size()) - 2; k >= 0; --k) {
    const MatrixXd predicted = c.F * filtered[k].covariance * c.F.transpose() + c.Q;
    const MatrixXd G = filtered[k].covariance * c.F.transpose() * predicted.inverse();
    out[k].mean = filtered[k].mean + G * (out[k + 1].mean - c.F * filtered[k].mean);
    out[k].covariance = filtered[k].covariance + G * (out[k + 1].covariance - predicted) * G.transpose();
  }
  return out;
}

double largest_difference(const std::vector<Gaussian>& a, const std::vector<Gaussian>& b) {
  double worst = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    worst = std::max(worst, (a[k].mean - b[k].mean).cwiseAbs().maxCoeff());
    worst = std::max(worst, (a[k].covariance - b[k].covariance).cwiseAbs().maxCoeff());
  }
  return worst;
}

}  // namespace

TEST_CASE("ukf: on a linear model the UKF and URTS equal the Kalman filter and RTS smoother", "[ukf]") {
  const LinearCase c = make_case();
  const UnscentedModel model = model_of(c);
  const std::vector<Gaussian> kf = kalman_filter(c);
  const std::vector<Gaussian> rts = rts_smoother(c, kf);
  const UnscentedOptions settings[3] = {{}, {0.5, 2.0, 1.0}, {1.0, 0.0, -1.0}};
  for (const UnscentedOptions& options : settings) {
    INFO("alpha " << options.alpha << " beta " << options.beta << " kappa " << options.kappa);
    REQUIRE(options.validate(4).empty());
    const std::vector<Gaussian> ukf = dabench::unscented_filter(c.prior, c.scans, model, options);
    const std::vector<Gaussian> urts = dabench::unscented_smoother(ukf, model, options);
    REQUIRE(ukf.size() == 12);
    CHECK(largest_difference(ukf, kf) < 1e-9);
    CHECK(largest_difference(urts, rts) < 1e-9);
  }
  // The smoother changes the early estimates (so the comparison above is not vacuous) and
  // leaves the last one as filtered.
  CHECK((rts[0].mean - kf[0].mean).norm() > 1e-2);
  CHECK(largest_difference({rts.back()}, {kf.back()}) == 0.0);
}

TEST_CASE("ukf: unscented transform of x squared has the closed-form moments", "[ukf]") {
  Gaussian x;
  x.mean = Vector::Constant(1, 2.0);
  x.covariance = MatrixXd::Constant(1, 1, 0.5);
  const auto square = [](const Vector& v) -> Vector { return v.array().square().matrix(); };
  const auto t = dabench::unscented_transform(x, square);
  CHECK(std::abs(t.mean[0] - (4.0 + 0.5)) < 1e-12);                     // m² + P
  CHECK(std::abs(t.covariance(0, 0) - (4.0 * 4.0 * 0.5 + 2.0 * 0.25)) < 1e-12);  // 4m²P + 2P²
  CHECK(std::abs(t.cross(0, 0) - 2.0 * 2.0 * 0.5) < 1e-12);             // Cov(x, x²) = 2mP
  // Any valid α, κ keep the mean exact (the sigma points match the first two moments).
  const auto t2 = dabench::unscented_transform(x, square, {0.3, 2.0, 2.0});
  CHECK(std::abs(t2.mean[0] - 4.5) < 1e-12);
}

TEST_CASE("ukf: invalid sigma-point parameters are named", "[ukf]") {
  CHECK(UnscentedOptions{0.0, 2.0, 0.0}.validate(4).find("alpha") != std::string::npos);
  CHECK(UnscentedOptions{1.0, -1.0, 0.0}.validate(4).find("beta") != std::string::npos);
  CHECK(UnscentedOptions{1.0, 2.0, -4.0}.validate(4).find("kappa") != std::string::npos);
  CHECK(UnscentedOptions{}.validate(4).empty());
}

TEST_CASE("ukf: a covariance that is not positive definite is reported with its scan", "[ukf]") {
  using dabench::UnscentedFailure;
  const LinearCase c = make_case();
  UnscentedModel model = model_of(c);
  const auto failure_of = [](const auto& call) -> std::string {
    try {
      call();
    } catch (const UnscentedFailure& failure) {
      return failure.what();
    }
    return "no failure";
  };

  // The state covariance of the sigma points: indefinite, or with a NaN (LLT alone passes it).
  Gaussian bad = c.prior;
  bad.covariance(3, 3) = -1.0;
  CHECK(failure_of([&] { dabench::unscented_transform(bad, model.measure); }) ==
        "ukf: state covariance not positive definite");
  bad.covariance(3, 3) = std::nan("");
  CHECK(failure_of([&] { dabench::unscented_transform(bad, model.measure); }) ==
        "ukf: state covariance not positive definite");

  // Process noise that removes more than the state holds: P⁻ = F P Fᵀ + Q is indefinite, so the
  // sigma points of scan 1 fail; scans are numbered from first_scan.
  UnscentedModel shrinking = model;
  shrinking.process_covariance = -1e3 * MatrixXd::Identity(4, 4);
  CHECK(failure_of([&] { dabench::unscented_filter(c.prior, c.scans, shrinking, {}, 10); }) ==
        "ukf: state covariance not positive definite at scan 11");

  // A measurement covariance that makes S indefinite, at scan 5 of the run.
  std::vector<std::optional<ScanMeasurement>> scans = c.scans;
  scans[5]->covariance = -1e3 * MatrixXd::Identity(2, 2);
  try {
    dabench::unscented_filter(c.prior, scans, model);
    FAIL("no failure");
  } catch (const UnscentedFailure& failure) {
    CHECK(std::string(failure.what()) == "ukf: innovation covariance not positive definite at scan 5");
    CHECK(failure.scan() == 5);
  }

  // The smoother's predicted covariance P⁻ of scan k + 1, at the last step (k = K − 2).
  const std::vector<Gaussian> filtered = dabench::unscented_filter(c.prior, c.scans, model);
  CHECK(failure_of([&] { dabench::unscented_smoother(filtered, shrinking, {}, 100); }) ==
        "ukf: predicted covariance not positive definite at scan 110");
}

}  // namespace DABENCH_TEST_FILE
