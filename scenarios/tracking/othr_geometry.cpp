#include "scenarios/tracking/othr_geometry.hpp"

#include <algorithm>
#include <cmath>

namespace dabench::othr {

namespace {

// The pieces of eq (57) shared by the measurement and its Jacobian.
struct Rays {
  double g, g_dot, sin_b, cos_b;
  double r_alpha;  // √(g²/4 + h_r²)
  double r_beta;   // √((g² − 2 d g sin ϑ + d²)/4 + h_t²)
  double offset;   // g − d sin ϑ

  Rays(const GroundState& x, const Path& path, double d)
      : g(x[0]), g_dot(x[1]), sin_b(std::sin(x[2])), cos_b(std::cos(x[2])) {
    r_alpha = std::sqrt(g * g / 4.0 + path.receive_height * path.receive_height);
    r_beta = std::sqrt((g * g - 2.0 * d * g * sin_b + d * d) / 4.0 + path.transmit_height * path.transmit_height);
    offset = g - d * sin_b;
  }
};

}  // namespace

SlantMeasurement slant_measurement(const GroundState& x, const Path& path, double baseline) {
  const Rays k(x, path, baseline);
  return {k.r_alpha + k.r_beta,
          k.g_dot / 4.0 * (k.g / k.r_alpha + k.offset / k.r_beta),
          std::asin(k.g * k.sin_b / (2.0 * k.r_alpha))};
}

SlantJacobian slant_jacobian(const GroundState& x, const Path& path, double d) {
  const Rays k(x, path, d);
  const double ra3 = k.r_alpha * k.r_alpha * k.r_alpha;
  const double rb3 = k.r_beta * k.r_beta * k.r_beta;
  // ∂r_α/∂g = g/(4 r_α); ∂r_β/∂g = (g − d sin ϑ)/(4 r_β); ∂r_β/∂ϑ = −d g cos ϑ/(4 r_β).
  const double dra_dg = k.g / (4.0 * k.r_alpha);
  const double drb_dg = k.offset / (4.0 * k.r_beta);
  const double drb_db = -d * k.g * k.cos_b / (4.0 * k.r_beta);
  // ṙ = (ġ/4)(A + B), A = g/r_α, B = (g − d sin ϑ)/r_β.
  const double dA_dg = 1.0 / k.r_alpha - k.g * k.g / (4.0 * ra3);
  const double dB_dg = 1.0 / k.r_beta - k.offset * k.offset / (4.0 * rb3);
  const double dB_db = -d * k.cos_b / k.r_beta + k.offset * d * k.g * k.cos_b / (4.0 * rb3);
  // ζ = asin(u), u = g sin ϑ/(2 r_α).
  const double u = k.g * k.sin_b / (2.0 * k.r_alpha);
  const double dz_du = 1.0 / std::sqrt(1.0 - u * u);
  const double du_dg = k.sin_b / (2.0 * k.r_alpha) - k.g * k.g * k.sin_b / (8.0 * ra3);
  const double du_db = k.g * k.cos_b / (2.0 * k.r_alpha);

  SlantJacobian jac = SlantJacobian::Zero();
  jac(0, 0) = dra_dg + drb_dg;
  jac(0, 2) = drb_db;
  jac(1, 0) = k.g_dot / 4.0 * (dA_dg + dB_dg);
  jac(1, 1) = (k.g / k.r_alpha + k.offset / k.r_beta) / 4.0;
  jac(1, 2) = k.g_dot / 4.0 * dB_db;
  jac(2, 0) = dz_du * du_dg;
  jac(2, 2) = dz_du * du_db;
  return jac;
}

bool ground_state_from_slant(const SlantMeasurement& y, const Path& path, GroundState& x, double d) {
  const double r = y[0], sin_z = std::sin(y[2]);
  const double hr2 = path.receive_height * path.receive_height, ht2 = path.transmit_height * path.transmit_height;
  double g = r;  // r ≈ g at OTHR ranges (each hop is about g/2 long)
  for (int step = 0; step < 50; ++step) {
    const double r_alpha = std::sqrt(g * g / 4.0 + hr2);
    const double r_beta2 = (g * g - 4.0 * d * r_alpha * sin_z + d * d) / 4.0 + ht2;
    if (!(r_beta2 > 0.0)) return false;
    const double r_beta = std::sqrt(r_beta2);
    const double dra = g / (4.0 * r_alpha);
    const double slope = dra + (2.0 * g - 4.0 * d * dra * sin_z) / (8.0 * r_beta);
    const double next = std::clamp(g - (r_alpha + r_beta - r) / slope, 1e-9, 4.0 * r);
    const bool done = std::abs(next - g) <= 1e-12 * std::max(1.0, g);
    g = next;
    if (done) break;
  }
  const double r_alpha = std::sqrt(g * g / 4.0 + hr2);
  const double sin_b = 2.0 * r_alpha * sin_z / g;
  if (!(std::abs(sin_b) <= 1.0)) return false;
  const double r_beta = std::sqrt((g * g - 2.0 * d * g * sin_b + d * d) / 4.0 + ht2);
  if (!(std::abs(r_alpha + r_beta - r) <= 1e-9 * std::max(1.0, r))) return false;
  const double rate_factor = (g / r_alpha + (g - d * sin_b) / r_beta) / 4.0;
  x = GroundState(g, y[1] / rate_factor, std::asin(sin_b), 0.0);
  return true;
}

OthrMeasurementModel::OthrMeasurementModel(double sigma_range, double sigma_range_rate, double sigma_azimuth)
    : noise_(Eigen::Vector3d(sigma_range * sigma_range, sigma_range_rate * sigma_range_rate,
                             sigma_azimuth * sigma_azimuth)
                 .asDiagonal()) {}

Vector OthrMeasurementModel::measure(int path, const Vector& state) const {
  return slant_measurement(state, kPathTable[path]);
}

bool OthrMeasurementModel::invert(int path, const Vector& measurement, Vector& state) const {
  GroundState x;
  if (measurement.size() != 3 || !ground_state_from_slant(measurement, kPathTable[path], x)) return false;
  state = x;
  return true;
}

Eigen::MatrixXd OthrMeasurementModel::jacobian(int path, const Vector& state) const {
  return slant_jacobian(state, kPathTable[path]);
}

}  // namespace dabench::othr
