#pragma once
// Over-the-horizon-radar (OTHR) multipath geometry of jdt-vb-multipath-othr, Sec. IV-A:
// a two-layer ionosphere (E at h_E = 100 km, F at h_F = 260 km), four propagation paths
// (Table II: τ = EE, EF, FE, FF — transmit on the first layer, receive on the second), a
// transmitter at distance d = 100 km from the receiver, and the slant measurement function
// of eq (57) mapping the ground state x = [g, ġ, ϑ, ϑ̇] (ground range km, km/s, bearing rad,
// rad/s) to y = [r, ṙ, ζ] (slant range km, slant range rate km/s, azimuth rad):
//
//   r = r_α + r_β,
//   ṙ = (ġ/4)·(g/r_α + (g − d sin ϑ)/r_β),
//   ζ = arcsin(g sin ϑ / (2 r_α)),
//   r_α = √(g²/4 + h_r²),  r_β = √((g² − 2 d g sin ϑ + d²)/4 + h_t²),
//
// h_t, h_r the transmit and receive layer heights of the path. Geometrically the receiver is
// at the origin, the target at g·(sin ϑ, cos ϑ), the transmitter at (d, 0); each hop reflects
// at mid-way, and r is half the total (out and back) group path.
//
// Reading: ṙ as printed is not the exact time derivative of r. It keeps the ġ terms and drops
// −d g cos ϑ ϑ̇ / (4 r_β), the bearing-rate term of ∂r_β/∂ϑ·ϑ̇ (for Table III targets about
// 0.0037 km/s, 3.7 σ_ṙ). We implement eq (57) as printed, since the paper's data and trackers
// use it; tests/tracking/test_othr_geometry.cpp checks the exact derivative differs by exactly this term.
// The paper gives no Jacobian; jacobian() is the analytic one of the printed eq (57) (its ϑ̇
// column is zero), tested against central differences.
#include <array>
#include <string_view>

#include <Eigen/Core>

#include "harness/tracking/problem.hpp"

namespace dabench::othr {

inline constexpr double kHeightE = 100.0;  // h_E, km
inline constexpr double kHeightF = 260.0;  // h_F, km
inline constexpr double kBaseline = 100.0; // d, transmitter–receiver distance, km
inline constexpr int kPaths = 4;           // N_P

struct Path {
  std::string_view name;
  double transmit_height;  // h_t, km
  double receive_height;   // h_r, km
};

// Table II, τ = 1..4 at indices 0..3.
inline constexpr std::array<Path, kPaths> kPathTable{{
    {"EE", kHeightE, kHeightE},
    {"EF", kHeightE, kHeightF},
    {"FE", kHeightF, kHeightE},
    {"FF", kHeightF, kHeightF},
}};

using GroundState = Eigen::Vector4d;    // [g, ġ, ϑ, ϑ̇]
using SlantMeasurement = Eigen::Vector3d;  // [r, ṙ, ζ]
using SlantJacobian = Eigen::Matrix<double, 3, 4>;

// Eq (57) for one path; requires g > 0 and |g sin ϑ| ≤ 2 r_α (always true for g > 0).
SlantMeasurement slant_measurement(const GroundState& x, const Path& path, double baseline = kBaseline);
SlantJacobian slant_jacobian(const GroundState& x, const Path& path, double baseline = kBaseline);

// The inverse of eq (57) on one path: the ground state [g, ġ, ϑ, 0] whose measurement is y
// (ϑ̇ does not enter eq (57), so it is returned as 0). From ζ, g sin ϑ = 2 r_α sin ζ; g solves
// r_α(g) + r_β(g) = r by Newton's method (r is increasing in g); then ϑ and ġ follow. Returns
// false when no g ∈ (0, 4r] fits (r below the path's two layer heights' reach, or |sin ϑ| > 1).
[[nodiscard]] bool ground_state_from_slant(const SlantMeasurement& y, const Path& path, GroundState& x, double baseline = kBaseline);

// The four paths of Table II with a common noise covariance R = diag(σ_r², σ_ṙ², σ_ζ²).
class OthrMeasurementModel final : public MultipathMeasurementModel {
 public:
  OthrMeasurementModel(double sigma_range, double sigma_range_rate, double sigma_azimuth);

  int state_dim() const override { return 4; }
  int measurement_dim() const override { return 3; }
  int paths() const override { return kPaths; }
  Vector measure(int path, const Vector& state) const override;
  Eigen::MatrixXd jacobian(int path, const Vector& state) const override;
  const Eigen::MatrixXd& noise_covariance(int) const override { return noise_; }
  [[nodiscard]] bool invert(int path, const Vector& measurement, Vector& state) const override;

 private:
  Eigen::MatrixXd noise_;
};

}  // namespace dabench::othr
