// Tests of the OTHR slant measurement function, eq (57) of jdt-vb-multipath-othr (Sec. IV-A,
// Table II): hand-computed values, the range rate against finite differences of the range,
// the analytic Jacobian against central differences, and symmetries of the four paths.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "scenarios/tracking/othr_geometry.hpp"

namespace DABENCH_TEST_FILE {

namespace {

using dabench::othr::GroundState;
using dabench::othr::kPathTable;
using dabench::othr::Path;
using dabench::othr::slant_jacobian;
using dabench::othr::slant_measurement;
using dabench::othr::SlantMeasurement;

constexpr double kPi = std::numbers::pi;

// Hand-picked target: g = 1800 km, ϑ = π/6 (sin ϑ = 1/2), ġ = 0.1 km/s, ϑ̇ = 8.7e-5 rad/s.
const GroundState kTarget{1800.0, 0.1, kPi / 6.0, 8.7e-5};

// Slant range of a CV trajectory through x at time t (seconds).
double range_at(const GroundState& x, const Path& path, double t, double d = dabench::othr::kBaseline) {
  const GroundState moved{x[0] + x[1] * t, x[1], x[2] + x[3] * t, x[3]};
  return slant_measurement(moved, path, d)[0];
}

}  // namespace

TEST_CASE("othr geometry: eq 57 at a hand-computed target", "[othr_geometry]") {
  // r_α = √(g²/4 + h_r²): h_r = h_E → √(810000 + 10000) = √820000; h_r = h_F → √(810000 + 67600).
  // g² − 2 d g sin ϑ + d² = 3240000 − 180000 + 10000 = 3070000, /4 = 767500, so
  // r_β = √(767500 + 10000) = √777500 (h_t = h_E) or √(767500 + 67600) = √835100 (h_t = h_F).
  // g − d sin ϑ = 1750; g sin ϑ = 900.
  const double ra_e = std::sqrt(820000.0), ra_f = std::sqrt(877600.0);
  const double rb_e = std::sqrt(777500.0), rb_f = std::sqrt(835100.0);
  struct Expected {
    double r_alpha, r_beta;
  };
  // Table II: EE (h_t, h_r) = (E, E), EF = (E, F), FE = (F, E), FF = (F, F).
  const Expected expected[4] = {{ra_e, rb_e}, {ra_f, rb_e}, {ra_e, rb_f}, {ra_f, rb_f}};
  for (int tau = 0; tau < 4; ++tau) {
    INFO("path " << kPathTable[tau].name);
    const auto [ra, rb] = expected[tau];
    const SlantMeasurement y = slant_measurement(kTarget, kPathTable[tau]);
    CHECK(std::abs(y[0] - (ra + rb)) < 1e-9);
    CHECK(std::abs(y[1] - 0.1 / 4.0 * (1800.0 / ra + 1750.0 / rb)) < 1e-12);
    CHECK(std::abs(y[2] - std::asin(900.0 / (2.0 * ra))) < 1e-12);
  }
  // Decimal values (EE): r = 1787.2981182411615 km, ṙ = 0.09931088473200844 km/s,
  // ζ = 0.5200711331941723 rad.
  const SlantMeasurement ee = slant_measurement(kTarget, kPathTable[0]);
  CHECK(ee[0] == Approx(1787.2981182411615).epsilon(1e-13));
  CHECK(ee[1] == Approx(0.09931088473200844).epsilon(1e-12));
  CHECK(ee[2] == Approx(0.5200711331941723).epsilon(1e-12));
}

TEST_CASE("othr geometry: range rate is the time derivative of the range up to the dropped bearing-rate term", "[othr_geometry]") {
  constexpr double h = 0.5;  // s; truncation ~h²·r'''/6 and rounding ~1e-13·r/h both < 1e-9
  for (const Path& path : kPathTable) {
    INFO("path " << path.name);
    // ϑ̇ = 0: eq (57)'s ṙ is exact.
    GroundState still = kTarget;
    still[3] = 0.0;
    const double fd_still = (range_at(still, path, h) - range_at(still, path, -h)) / (2.0 * h);
    CHECK(std::abs(fd_still - slant_measurement(still, path)[1]) < 1e-8);
    // ϑ̇ ≠ 0: the exact derivative adds −d g cos ϑ ϑ̇ / (4 r_β) (0.0038 km/s here), which the
    // printed eq (57) omits (see othr_geometry.hpp).
    const double fd = (range_at(kTarget, path, h) - range_at(kTarget, path, -h)) / (2.0 * h);
    const double r_beta = std::sqrt(767500.0 + path.transmit_height * path.transmit_height);
    const double omitted = -100.0 * 1800.0 * std::cos(kPi / 6.0) * 8.7e-5 / (4.0 * r_beta);
    CHECK(std::abs(fd - (slant_measurement(kTarget, path)[1] + omitted)) < 1e-8);
    CHECK(std::abs(omitted) > 3e-3);
  }
}

TEST_CASE("othr geometry: analytic Jacobian matches central differences", "[othr_geometry]") {
  const GroundState states[3] = {kTarget, {1550.0, -0.3, 0.44, -2e-4}, {1990.0, 0.25, 0.6, 1e-4}};
  const double steps[4] = {1e-3, 1e-6, 1e-7, 1e-7};
  for (const GroundState& x : states) {
    for (const Path& path : kPathTable) {
      const auto jac = slant_jacobian(x, path);
      for (int c = 0; c < 4; ++c) {
        GroundState up = x, down = x;
        up[c] += steps[c];
        down[c] -= steps[c];
        const SlantMeasurement numeric = (slant_measurement(up, path) - slant_measurement(down, path)) / (2.0 * steps[c]);
        for (int r = 0; r < 3; ++r) {
          INFO("path " << path.name << " row " << r << " column " << c);
          CHECK(jac(r, c) == Approx(numeric[r]).epsilon(1e-6).margin(1e-9));
        }
      }
      CHECK(jac.col(3).isZero());  // eq (57) does not depend on ϑ̇
    }
  }
}

TEST_CASE("othr geometry: path symmetries", "[othr_geometry]") {
  const GroundState x{1730.0, -0.15, 0.51, 5e-5};
  const SlantMeasurement ee = slant_measurement(x, kPathTable[0]), ef = slant_measurement(x, kPathTable[1]);
  const SlantMeasurement fe = slant_measurement(x, kPathTable[2]), ff = slant_measurement(x, kPathTable[3]);
  // r_α depends on h_r only and r_β on h_t only, so EE + FF = EF + FE for r and ṙ,
  // and ζ (through r_α) depends on the receive layer only.
  CHECK(std::abs((ee[0] + ff[0]) - (ef[0] + fe[0])) < 1e-9);
  CHECK(std::abs((ee[1] + ff[1]) - (ef[1] + fe[1])) < 1e-12);
  CHECK(ee[2] == fe[2]);
  CHECK(ef[2] == ff[2]);
  CHECK(ee[0] < ef[0]);
  CHECK(ef[0] < ff[0]);
  // Co-located transmitter and receiver (d = 0): EF and FE coincide; ϑ → −ϑ flips ζ only.
  const SlantMeasurement ef0 = slant_measurement(x, kPathTable[1], 0.0), fe0 = slant_measurement(x, kPathTable[2], 0.0);
  CHECK(std::abs(ef0[0] - fe0[0]) < 1e-9);
  CHECK(std::abs(ef0[1] - fe0[1]) < 1e-12);
  const GroundState mirrored{x[0], x[1], -x[2], -x[3]};
  const SlantMeasurement m = slant_measurement(mirrored, kPathTable[1], 0.0);
  CHECK(std::abs(m[0] - ef0[0]) < 1e-9);
  CHECK(std::abs(m[1] - ef0[1]) < 1e-12);
  CHECK(std::abs(m[2] + ef0[2]) < 1e-12);
  // Zero layer heights and d = 0: the slant measurement is the ground state itself.
  const Path ground{"ground", 0.0, 0.0};
  const SlantMeasurement flat = slant_measurement(x, ground, 0.0);
  CHECK(std::abs(flat[0] - x[0]) < 1e-9);
  CHECK(std::abs(flat[1] - x[1]) < 1e-12);
  CHECK(std::abs(flat[2] - x[2]) < 1e-12);
}

TEST_CASE("othr geometry: ground_state_from_slant inverts eq 57 on every path", "[othr_geometry]") {
  for (const auto& path : dabench::othr::kPathTable) {
    for (double g : {1500.0, 1750.0, 2000.0}) {
      for (double bearing : {0.43, 0.52, 0.6}) {
        const dabench::othr::GroundState x(g, -0.15, bearing, 8.7e-5);
        dabench::othr::GroundState back;
        REQUIRE(dabench::othr::ground_state_from_slant(dabench::othr::slant_measurement(x, path), path, back));
        CHECK(back[0] == Approx(g).epsilon(1e-12));
        CHECK(back[1] == Approx(-0.15).epsilon(1e-10));
        CHECK(back[2] == Approx(bearing).epsilon(1e-12));
        CHECK(back[3] == 0.0);  // ϑ̇ does not enter eq (57)
      }
    }
  }
  // A slant range shorter than the two layer heights allow has no ground state.
  dabench::othr::GroundState none;
  CHECK_FALSE(dabench::othr::ground_state_from_slant({150.0, 0.0, 0.5}, dabench::othr::kPathTable[3], none));
}

}  // namespace DABENCH_TEST_FILE
