#pragma once
// The IPLF update of TBD-IEMB (tbd_iemb.hpp, step 5; [C]: github.com/ESDavies/IPLF-IEMB-filter,
// TBDkFil.m, sigma_approximation.m, dist_kullback.m), generic in the measurement: iterated
// statistical linear regressions about the current iterate from 2n + 1 = 9 sigma points, each
// followed by the Kalman update of the prior, until successive iterates are within a KL bound.
// With block-diagonal noise, S = (diagonal blocks) + U Uᵀ with U of rank 13, so S⁻¹ and det S
// come from the Woodbury identity: O(13² d) per iteration for a measurement of d rows.
#include <array>
#include <vector>

#include <Eigen/Core>

namespace dabench {

// ---- sigma points [C: sigma_approximation.m] -------------------------------------------------

struct SigmaPoints {
  static constexpr int kCount = 9;                  // 2n + 1, n = 4
  static constexpr double kCentreWeight = 1.0 / 3;  // W₀
  std::array<Eigen::Vector4d, kCount> points;       // m, m + L_i (i = 1..4), m − L_i
  std::array<double, kCount> weights;               // W₀, then (1 − W₀)/(2n)
};
// L L ᵀ = n/(1 − W₀)·P (Cholesky). Returns false if P is not positive definite.
[[nodiscard]] bool make_sigma_points(const Eigen::Vector4d& mean, const Eigen::Matrix4d& covariance, SigmaPoints& out);

// Rows of a measurement vector at each sigma point (column s = point s).
using SigmaMatrix = Eigen::Matrix<double, Eigen::Dynamic, SigmaPoints::kCount>;

// ---- the IPLF update, generic in the measurement [C: TBDkFil.m] --------------------------------

// What one IPLF update sees: a measurement of `cells` blocks of q = 1 or 2 rows (d = q·cells),
// whose noise is block diagonal (no cross-block covariance besides the Bernoulli's own).
class IplfMeasurement {
 public:
  virtual ~IplfMeasurement() = default;
  int q = 1;
  int cells = 0;
  Eigen::VectorXd residual;  // z − E[z | the Bernoulli is absent] (≥ d entries)
  std::vector<Eigen::Matrix2d> absent_covariance;  // Cov[z_c | absent], per block (top-left q × q)
  // At the sigma points: rows 0..d−1 of column s of `h` = the Bernoulli's own mean contribution
  // at point s (h has ≥ d rows); noise[c] = Σ_s w_s Cov[z_c | x = point s] (top-left q × q).
  virtual void evaluate(const SigmaPoints& sigma, SigmaMatrix& h, std::vector<Eigen::Matrix2d>& noise) = 0;
};

struct IplfResult {
  Eigen::Vector4d mean = Eigen::Vector4d::Zero();
  Eigen::Matrix4d covariance = Eigen::Matrix4d::Zero();
  double log_present = 0.0;  // log L₁ = log N(z; ẑ, S) of the last iteration
  double log_absent = 0.0;   // log L₀ = log N(z; E[z | absent], Cov[z | absent])
  int iterations = 0;
  bool converged = true;     // false: stopped at the cap with KL ≥ the threshold
};

class IplfUpdate {
 public:
  // At most `max_iterations` SLR + Kalman passes from the prior (mean, covariance), which must
  // be positive definite; stops once the KL divergence between successive iterates < kl_threshold.
  IplfResult run(const Eigen::Vector4d& mean, const Eigen::Matrix4d& covariance, IplfMeasurement& measurement,
                 int max_iterations, double kl_threshold);

 private:
  static constexpr int kWhitened = SigmaPoints::kCount + 4 + 1;  // columns of M = [√w_s e_s, A, z − ẑ]
  void reserve(int rows, int blocks);
  template <class Block>
  double whiten(int q, int blocks, Block& m);
  SigmaMatrix h_;
  Eigen::Matrix<double, Eigen::Dynamic, kWhitened> m_;
  Eigen::VectorXd ybar_;
  std::vector<Eigen::Matrix2d> noise_;  // D's blocks
  Eigen::VectorXd l00_, l10_, l11_;     // their Cholesky factors: 1/l₀₀, l₁₀, 1/l₁₁
};

// KL(N(m0, P0) ‖ N(m1, P1)) [C: dist_kullback.m]; +∞ if P1 is not positive definite.
double kl_divergence(const Eigen::Vector4d& m0, const Eigen::Matrix4d& p0, const Eigen::Vector4d& m1,
                     const Eigen::Matrix4d& p1);

}  // namespace dabench
