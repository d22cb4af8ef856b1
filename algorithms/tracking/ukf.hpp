#pragma once
// Unscented Kalman filter and fixed-interval unscented Rauch–Tung–Striebel smoother (URTS),
// as used per propagation path by JDT-VB Module 1 (jdt-vb-multipath-othr, Sec. III-B, eq (31)
// and [35]: Särkkä, "Unscented Rauch–Tung–Striebel smoother", IEEE TAC 2008, Algorithms 1–2).
//
// Sigma points (scaled unscented transform, Julier & Uhlmann; Wan & van der Merwe): for an
// n-dimensional N(m, P) with λ = α²(n + κ) − n and S S^T = P (Cholesky),
//   X_0 = m,  X_i = m + √(n + λ) S_i,  X_{n+i} = m − √(n + λ) S_i  (i = 1..n),
//   W^m_0 = λ/(n + λ),  W^c_0 = λ/(n + λ) + 1 − α² + β,  W^m_i = W^c_i = 1/(2(n + λ)).
// Defaults α = 1, β = 2, κ = 0: λ = 0, so the 2n points sit at m ± √n S_i with equal positive
// weights and the centre point carries W^m_0 = 0, W^c_0 = 2 (harmless: its deviation from the
// mean is zero for linear maps). For linear maps the transform is exact for any valid
// parameters, so the UKF and URTS then equal the Kalman filter and RTS smoother.
//
// A scan may have no measurement (the update is skipped) and each measurement carries its own
// covariance (JDT-VB's synthetic measurements, eq (36), have R̄ = R / Σ_j E[a]).
//
// Failure: every covariance factorised here by Cholesky — the state's (for its sigma points), the
// innovation covariance S of an update and the predicted covariance P⁻ of a smoother step — is
// checked; one that is not positive definite (or not finite) throws UnscentedFailure instead
// of filling every later estimate with NaN. A tracker reports it as its run's `failed:` status.
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "harness/core/matrix_types.hpp"

namespace dabench {

// what(): "ukf: <which> covariance not positive definite at scan <k>", <which> = state,
// innovation or predicted (JDT-VB also throws it with `marginal` for a marginal of q(x) that is
// no covariance, which no coupling can join to the next); k = first_scan + the index of the
// scan in the call (the scan passed to unscented_update); " at scan" is left out where no scan
// is known (unscented_transform).
class UnscentedFailure : public std::runtime_error {
 public:
  UnscentedFailure(const std::string& which, int scan);
  int scan() const { return scan_; }  // -1 if unknown

 private:
  int scan_;
};

struct UnscentedOptions {
  double alpha = 1.0;  // spread of the sigma points, in (0, 1]
  double beta = 2.0;   // prior-knowledge term of W^c_0 (2 is optimal for Gaussians), >= 0
  double kappa = 0.0;  // secondary scaling, n + κ > 0

  std::string validate(int dimension) const;  // "" if valid for this state dimension
};

struct Gaussian {
  Vector mean;
  Eigen::MatrixXd covariance;
};

struct UnscentedModel {
  std::function<Vector(const Vector&)> transition;  // f: x_{k+1} = f(x_k) + v, v ~ N(0, Q)
  Eigen::MatrixXd process_covariance;               // Q
  std::function<Vector(const Vector&)> measure;     // h: y = h(x) + w, w ~ N(0, R)
};

struct ScanMeasurement {
  Vector value;               // y_k
  Eigen::MatrixXd covariance; // R_k
};

// (M + Mᵀ)/2: a covariance update's rounding asymmetry removed.
inline Eigen::MatrixXd symmetrised(const Eigen::MatrixXd& m) { return 0.5 * (m + m.transpose()); }

// Filtered estimates p(x_k | y_0..k) for k = 0..K−1, starting from `prior` = p(x_0).
// `first_scan`: the run's number of scans[0], for failure messages.
std::vector<Gaussian> unscented_filter(const Gaussian& prior, const std::vector<std::optional<ScanMeasurement>>& scans,
                                       const UnscentedModel& model, const UnscentedOptions& options = {},
                                       int first_scan = 0);

// Smoothed estimates p(x_k | y_0..K−1) from the filter's output (URTS, Särkkä 2008, Alg. 2).
std::vector<Gaussian> unscented_smoother(const std::vector<Gaussian>& filtered, const UnscentedModel& model,
                                         const UnscentedOptions& options = {}, int first_scan = 0);

// One update (Särkkä 2008, Alg. 1 update step) of `x` with measurement y = h(x) + w, w ~ N(0, R);
// `scan` names the scan in a failure message.
void unscented_update(Gaussian& x, const ScanMeasurement& y, const std::function<Vector(const Vector&)>& h,
                      const UnscentedOptions& options = {}, int scan = -1);

// The unscented transform of N(m, P) through g: mean, covariance and the cross-covariance
// Cov(x, g(x)). Exposed for tests and for gating (predicted measurement and its covariance).
struct UnscentedTransform {
  Vector mean;
  Eigen::MatrixXd covariance;
  Eigen::MatrixXd cross;  // n_x × n_g
};
UnscentedTransform unscented_transform(const Gaussian& x, const std::function<Vector(const Vector&)>& g,
                                       const UnscentedOptions& options = {});

}  // namespace dabench
