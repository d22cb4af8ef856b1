// Tests of the track-before-detect scenario "tbd" (scenarios/tbd/tbd.hpp; docs/models/track-before-detect.md §1.3,
// §2.3): cell statistics against their closed forms (Rayleigh background, every cell's χ²₂ law
// given the truth, object energy, the d2 mean), the truth layouts, the model handed to trackers,
// determinism and option errors. Fixed seeds; means are checked to 5 standard errors, KS
// statistics against the 1 % critical value 1.628/√n (tests/support/kolmogorov_smirnov.hpp).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "harness/tbd/registry.hpp"
#include "scenarios/tbd/tbd.hpp"
#include "tests/support/input_error.hpp"
#include "tests/support/kolmogorov_smirnov.hpp"
#include "tests/support/scenario_draws.hpp"

namespace DABENCH_TEST_FILE {

namespace {

using namespace dabench;
using dabench::test::RunningMoments;

constexpr std::uint64_t kSeed = 20230711;

constexpr auto scenario_from = &dabench::test::scenario_from<TbdImageScenario>;

// For the truth tests: the same 32 m region in 8 × 8 cells of 4 m, so the same law of the truth
// (the anchors are fractions of the region) at 1/16 of the cost of the frames.
std::vector<KeyValue> coarse(std::vector<KeyValue> settings) {
  settings.insert(settings.end(), {{"columns", "8"}, {"rows", "8"}, {"cell_size", "4"}});
  return settings;
}

double ks_critical_1_percent(std::size_t n) { return 1.628 / std::sqrt(static_cast<double>(n)); }

// Positions of the objects existing at step k.
std::vector<Eigen::Vector2d> positions_at(const TbdTruth& truth, int k) {
  std::vector<Eigen::Vector2d> positions;
  for (const auto& object : truth.objects) {
    if (object.alive[k]) positions.push_back(object.states.col(k).head<2>());
  }
  return positions;
}

// Distance from p to the nearest edge of the region.
double to_border(const TbdSensor& s, const Eigen::Vector2d& p) {
  return std::min({p.x() - s.x_min, s.x_max() - p.x(), p.y() - s.y_min, s.y_max() - p.y()});
}

// First and last alive step (0-based), −1 if never alive; requires the alive steps to be
// contiguous and exactly the non-NaN columns.
std::pair<int, int> lifetime(const TbdTruth::Object& object) {
  int first = -1, last = -1;
  for (int k = 0; k < static_cast<int>(object.alive.size()); ++k) {
    INFO("step " << k);
    REQUIRE(object.alive[k] == !std::isnan(object.states(0, k)));
    if (!object.alive[k]) continue;
    if (first < 0) first = k;
    REQUIRE((last < 0 || last == k - 1));
    last = k;
  }
  return {first, last};
}

}  // namespace

TEST_CASE("tbd scenario: background cells are Rayleigh(sigma) in magnitude", "[tbd][scenario]") {
  for (const char* variance_text : {"1", "4"}) {
    const double sigma = std::sqrt(std::stod(variance_text));
    const TbdImageScenario scenario = scenario_from({{"noise_variance", variance_text}});
    const TbdSensor& sensor = scenario.sensor();
    const double reach = TbdImageScenario::kSupportRadius * std::sqrt(sensor.spread_variance);
    std::vector<double> pit;  // F(‖z_j‖) = 1 − exp(−‖z‖²/(2σ²))
    RunningMoments magnitude;
    double below = 0.0;
    TbdSample sample;
    for (int run = 0; run < 12; ++run) {
      RandomStream rng(kSeed, 0, run);
      scenario.generate(rng, sample);
      for (int k = 0; k < sample.problem.steps(); ++k) {
        const auto objects = positions_at(sample.truth, k);
        for (int row = 0; row < sensor.rows; ++row) {
          for (int column = 0; column < sensor.columns; ++column) {
            const Eigen::Vector2d c{sensor.centre_x(column), sensor.centre_y(row)};
            // Background: outside every object's support.
            if (std::any_of(objects.begin(), objects.end(), [&](const auto& p) { return (c - p).norm() <= reach; })) continue;
            const double r = sample.problem.frames[k].col(row * sensor.columns + column).norm() / sigma;
            magnitude.add(r);
            below += r < 0.25 ? 1.0 : 0.0;
            pit.push_back(1.0 - std::exp(-0.5 * r * r));
          }
        }
      }
    }
    const double ks = dabench::test::ks_uniform_statistic(pit);
    INFO("noise_variance " << variance_text << ", cells " << magnitude.n << ": mean " << magnitude.mean() << ", s.d. "
                           << magnitude.sd() << ", below 0.25 " << below / magnitude.n << ", KS " << ks);
    REQUIRE(magnitude.n > 3e5);  // ≈ 12 runs × 50 frames × (1024 − ~4·100 support cells)
    // Rayleigh(1): mean √(π/2), s.d. √((4 − π)/2) = 0.6551; P(R < 0.25) = 1 − e^{−1/32}.
    const double mean = std::sqrt(std::numbers::pi / 2.0);
    const double p_below = 1.0 - std::exp(-1.0 / 32.0);
    CHECK(std::abs(magnitude.mean() - mean) < 5.0 * 0.6551 / std::sqrt(magnitude.n));
    CHECK(std::abs(magnitude.sd() - 0.6551) < 0.005);
    CHECK(std::abs(below / magnitude.n - p_below) < 5.0 * std::sqrt(p_below * (1.0 - p_below) / magnitude.n));
    CHECK(ks < ks_critical_1_percent(pit.size()));
  }
}

TEST_CASE("tbd scenario: given the truth every cell is N(m_j, s_j I) with the model's m_j, s_j", "[tbd][scenario]") {
  // m_j = Σ_n μ_j(x_n), s_j = σ² + Σ_n c_j(x_n) over the objects alive at k (every cell, no
  // support cut): ‖z_j − m_j‖²/(2 s_j) ~ Exp(1), and E Σ_j ‖z_j‖² = Σ_j (‖m_j‖² + 2 s_j) with
  // Var ‖z_j‖² = 4 s_j² + 4 s_j ‖m_j‖².
  for (const char* signal : {"d1", "d2", "d3"}) {
    const TbdImageScenario scenario = scenario_from({{"signal", signal}});
    const TbdSensor& sensor = scenario.sensor();
    const double gamma = scenario.options().amplitude;
    std::vector<double> pit;
    double excess = 0.0, expected = 0.0, variance = 0.0;
    TbdSample sample;
    for (int run = 0; run < 8; ++run) {
      RandomStream rng(kSeed, 1, run);
      scenario.generate(rng, sample);
      for (int k = 0; k < sample.problem.steps(); ++k) {
        const auto objects = positions_at(sample.truth, k);
        for (int row = 0; row < sensor.rows; ++row) {
          for (int column = 0; column < sensor.columns; ++column) {
            Eigen::Vector2d m = Eigen::Vector2d::Zero();
            double s = sensor.noise_variance;
            for (const auto& p : objects) {
              const auto h = sensor.contribution(column, row, p.x(), p.y(), gamma);
              m += h.mean;
              s += h.variance;
            }
            const Eigen::Vector2d z = sample.problem.frames[k].col(row * sensor.columns + column);
            pit.push_back(1.0 - std::exp(-(z - m).squaredNorm() / (2.0 * s)));
            excess += z.squaredNorm();
            expected += m.squaredNorm() + 2.0 * s;
            variance += 4.0 * s * s + 4.0 * s * m.squaredNorm();
          }
        }
      }
    }
    const double ks = dabench::test::ks_uniform_statistic(pit);
    INFO("signal " << signal << ", cells " << pit.size() << ": KS " << ks << ", energy z-score "
                   << (excess - expected) / std::sqrt(variance));
    CHECK(ks < ks_critical_1_percent(pit.size()));
    CHECK(std::abs(excess - expected) < 5.0 * std::sqrt(variance));
  }
}

TEST_CASE("tbd scenario: a cell-centred d1 object adds sigma_S^2 gamma g_j to E|z_j|^2, 2 pi sigma_h^2 gamma in all", "[tbd][scenario]") {
  for (const char* scale_text : {"1", "0.5"}) {
    const double scale = std::stod(scale_text);
    const TbdImageScenario scenario = scenario_from({{"sigma_s2", scale_text}});
    const TbdSensor& sensor = scenario.sensor();
    REQUIRE(sensor.spread_variance == 0.5);
    const Eigen::Vector2d p{16.5, 16.5};  // centre of cell (16, 16)
    constexpr int kDraws = 4000;
    RunningMoments own, side, diagonal, total;
    Eigen::Matrix2Xd frame;
    for (int draw = 0; draw < kDraws; ++draw) {
      RandomStream rng(kSeed, 2, draw);
      dabench::draw_tbd_frame(sensor, 60.0, {p}, rng, frame);
      own.add(frame.col(16 * 32 + 16).squaredNorm());
      side.add(frame.col(16 * 32 + 17).squaredNorm());
      diagonal.add(frame.col(17 * 32 + 17).squaredNorm());
      double sum = 0.0;
      for (int row = 9; row <= 23; ++row) {
        for (int column = 9; column <= 23; ++column) sum += frame.col(row * 32 + column).squaredNorm() - 2.0;
      }
      total.add(sum);
    }
    // E‖z‖² = 2(σ² + c) with c = σ_S² (γ/2) g; its s.d. is 2(σ² + c) (a scaled χ²₂).
    for (const auto& [moments, distance2] : {std::pair{own, 0.0}, std::pair{side, 1.0}, std::pair{diagonal, 2.0}}) {
      const double e = 2.0 + scale * 60.0 * std::exp(-distance2 / (2.0 * 0.5));
      INFO("sigma_s2 " << scale << ", squared distance " << distance2 << ": mean " << moments.mean() << " vs " << e);
      CHECK(std::abs(moments.mean() - e) < 5.0 * e / std::sqrt(kDraws));
    }
    // Σ_j g_j = 2π σ_h²/Δ² (Poisson summation: relative error 2e^{−π²} per axis), so the
    // excess is σ_S² γ π = 188.5 for the defaults; per-draw s.d. ≈ 82 (σ_S² = 1).
    double lattice = 0.0;
    for (int row = 9; row <= 23; ++row) {
      for (int column = 9; column <= 23; ++column) lattice += sensor.spread(column, row, p.x(), p.y());
    }
    CHECK(lattice == Approx(2.0 * std::numbers::pi * 0.5).epsilon(3e-4));
    const double e = scale * 60.0 * lattice;
    INFO("sigma_s2 " << scale << ": excess " << total.mean() << " vs " << e << " (s.d. " << total.sd() << ")");
    CHECK(std::abs(total.mean() - e) < 5.0 * total.sd() / std::sqrt(kDraws));
  }
}

TEST_CASE("tbd scenario: toy frames hold the energy of two objects, 2 x 188.5", "[tbd][scenario]") {
  const TbdImageScenario scenario = scenario_from({{"layout", "toy"}});
  constexpr int kRuns = 3000;
  RunningMoments total;
  TbdSample sample;
  for (int run = 0; run < kRuns; ++run) {
    RandomStream rng(kSeed, 3, run);
    scenario.generate(rng, sample);
    total.add(sample.problem.frames[0].colwise().squaredNorm().sum() - 2.0 * 100.0);
  }
  // Σ_j g_j at a cell corner is 2π σ_h² (1 − 2e^{−π²})² = π (1 − 2.1e-4), for each object.
  const double e = 2.0 * 60.0 * std::numbers::pi * std::pow(1.0 - 2.0 * std::exp(-std::numbers::pi * std::numbers::pi), 2);
  INFO("excess " << total.mean() << " vs " << e << " (s.d. " << total.sd() << ")");
  CHECK(std::abs(total.mean() - e) < 5.0 * total.sd() / std::sqrt(kRuns));
}

TEST_CASE("tbd scenario: the d2 mean is (gamma psi_j(p), 0)", "[tbd][scenario]") {
  const TbdImageScenario scenario = scenario_from({{"signal", "d2"}});
  const TbdSensor& sensor = scenario.sensor();
  REQUIRE(sensor.spread_variance == 1.5);
  const Eigen::Vector2d p{16.3, 16.8};
  constexpr int kDraws = 4000;
  Eigen::Matrix2Xd sum = Eigen::Matrix2Xd::Zero(2, sensor.cells());
  Eigen::Matrix2Xd frame;
  for (int draw = 0; draw < kDraws; ++draw) {
    RandomStream rng(kSeed, 4, draw);
    dabench::draw_tbd_frame(sensor, 60.0, {p}, rng, frame);
    sum += frame;
  }
  // ψ_j = Δ²/(2π σ_h²) exp(−‖c_j − p‖²/(2σ_h²)); per-component variance σ² + σ_S² g² ≤ 2.
  for (int row = 14; row <= 19; ++row) {
    for (int column = 13; column <= 19; ++column) {
      const double d2 = std::pow(column + 0.5 - p.x(), 2) + std::pow(row + 0.5 - p.y(), 2);
      const double g = std::exp(-d2 / 3.0);
      const double psi = g / (2.0 * std::numbers::pi * 1.5);
      const double se = std::sqrt((1.0 + g * g) / kDraws);
      const Eigen::Vector2d mean = sum.col(row * 32 + column) / kDraws;
      INFO("cell (" << column << ", " << row << "): mean " << mean.transpose() << " vs " << 60.0 * psi);
      CHECK(std::abs(mean.x() - 60.0 * psi) < 5.0 * se);
      CHECK(std::abs(mean.y()) < 5.0 * se);
    }
  }
}

TEST_CASE("tbd scenario: the d3 signal is a mean sqrt(rho gamma) g_j e_1 plus (1 - rho) of d1's fluctuation",
          "[tbd][scenario]") {
  // μ_j = (√(ργ) g, 0), c_j = (1 − ρ) σ_S² (γ/2) g: per cell E z = μ_j and E‖z − μ_j‖² = 2(σ² + c_j).
  const TbdImageScenario scenario = scenario_from({{"signal", "d3"}, {"mean_share", "0.5"}, {"spread_variance", "0.6"}});
  const TbdSensor& sensor = scenario.sensor();
  REQUIRE(sensor.spread_variance == 0.6);
  const Eigen::Vector2d p{16.3, 16.8};
  constexpr int kDraws = 4000;
  Eigen::Matrix2Xd sum = Eigen::Matrix2Xd::Zero(2, sensor.cells());
  Eigen::VectorXd squares = Eigen::VectorXd::Zero(sensor.cells());
  Eigen::Matrix2Xd frame;
  for (int draw = 0; draw < kDraws; ++draw) {
    RandomStream rng(kSeed, 5, draw);
    dabench::draw_tbd_frame(sensor, 60.0, {p}, rng, frame);
    sum += frame;
    squares += frame.colwise().squaredNorm().transpose();
  }
  for (int row = 15; row <= 18; ++row) {
    for (int column = 15; column <= 18; ++column) {
      const double g = std::exp(-(std::pow(column + 0.5 - p.x(), 2) + std::pow(row + 0.5 - p.y(), 2)) / 1.2);
      const double mu = std::sqrt(0.5 * 60.0) * g, c = 0.5 * 0.5 * 60.0 * g;
      const double se = std::sqrt((1.0 + c) / kDraws);
      const Eigen::Vector2d mean = sum.col(row * 32 + column) / kDraws;
      const double energy = squares(row * 32 + column) / kDraws;
      INFO("cell (" << column << ", " << row << "): mean " << mean.transpose() << " vs " << mu << ", E|z|^2 " << energy
                    << " vs " << mu * mu + 2.0 * (1.0 + c));
      CHECK(std::abs(mean.x() - mu) < 5.0 * se);
      CHECK(std::abs(mean.y()) < 5.0 * se);
      // Var ‖z‖² = 4 s² + 4 s μ² for z ~ N(μ, s I₂), s = 1 + c.
      const double s = 1.0 + c;
      CHECK(std::abs(energy - (mu * mu + 2.0 * s)) < 5.0 * std::sqrt((4.0 * s * s + 4.0 * s * mu * mu) / kDraws));
    }
  }
  // ρ = 0 is d1, bit for bit (the same draws, the same contributions).
  const TbdImageScenario d1 = scenario_from({{"signal", "d1"}, {"spread_variance", "0.6"}});
  const TbdImageScenario d3 = scenario_from({{"signal", "d3"}, {"mean_share", "0"}, {"spread_variance", "0.6"}});
  TbdSample a, b;
  RandomStream rng_a(kSeed, 6, 0), rng_b(kSeed, 6, 0);
  d1.generate(rng_a, a);
  d3.generate(rng_b, b);
  for (int k = 0; k < a.problem.steps(); ++k) CHECK(a.problem.frames[k] == b.problem.frames[k]);
  // The defaults are the fit of results/tbd/REPORT.md (experiments/tbd/calibration.py).
  const TbdImageScenario defaults = scenario_from({{"signal", "d3"}});
  CHECK(defaults.sensor().mean_share == dabench::kMeanShareD3);
  CHECK(defaults.sensor().spread_variance == dabench::kSpreadD3);
}

TEST_CASE("tbd scenario: crossing windows scale with the number of steps", "[tbd][scenario]") {
  const auto w50 = TbdImageScenario::crossing_windows(50);
  CHECK(w50.birth_last == 20);
  CHECK(w50.death_first == 30);
  CHECK(w50.middle == 25);
  CHECK(w50.slow_last == 35);
  const auto w100 = TbdImageScenario::crossing_windows(100);
  CHECK((w100.birth_last == 40 && w100.death_first == 60 && w100.middle == 50 && w100.slow_last == 70));
  for (int steps = 1; steps <= 300; ++steps) {
    INFO("steps " << steps);
    const auto w = TbdImageScenario::crossing_windows(steps);
    CHECK(1 <= w.birth_last);
    CHECK(w.birth_last <= w.middle);
    CHECK(w.middle <= w.death_first);
    CHECK(w.death_first <= steps);
    CHECK((1 <= w.slow_last && w.slow_last <= steps));
  }
}

TEST_CASE("tbd scenario: crossing truth has the documented lifetimes, anchors and speeds", "[tbd][scenario]") {
  const TbdImageScenario scenario = scenario_from(coarse({}));
  const TbdSensor& sensor = scenario.sensor();
  constexpr int kRuns = 500;
  RunningMoments birth, death, mid_x, mid_y;
  int entered = 0, left = 0;
  TbdSample sample;
  for (int run = 0; run < kRuns; ++run) {
    RandomStream rng(kSeed, 5, run);
    scenario.generate(rng, sample);
    REQUIRE(sample.problem.steps() == 50);
    REQUIRE(sample.truth.objects.size() == 5);
    for (int n = 0; n < 5; ++n) {
      INFO("run " << run << " object " << n);
      const auto& object = sample.truth.objects[n];
      REQUIRE(object.states.cols() == 50);
      const auto [first, last] = lifetime(object);
      for (int k = first; k <= last; ++k) REQUIRE(sensor.inside(object.states(0, k), object.states(1, k)));
      if (n == 0) {  // the slow object: steps 1..35, speed 0.05 m/step
        CHECK(first == 0);
        CHECK(last == 34);
        CHECK(object.states.col(17).tail<2>().norm() == Approx(0.05).epsilon(1e-12));
        CHECK((object.states.col(17).head<2>() - Eigen::Vector2d{12.7, 7.5}).norm() < 2.5);
        continue;
      }
      // Crossing: alive at the middle step 25 with the drawn speed; born in 1..20 and dead in
      // 30..50 unless it crossed the border.
      REQUIRE(object.alive[24]);
      const double speed = object.states.col(24).tail<2>().norm();
      CHECK((speed >= 0.1 && speed <= 0.3));
      mid_x.add(object.states(0, 24));
      mid_y.add(object.states(1, 24));
      if (first >= 20) {
        ++entered;
        CHECK(to_border(sensor, object.states.col(first).head<2>()) < 0.4);
      } else {
        birth.add(first + 1);
      }
      if (last < 29) {
        ++left;
        CHECK(to_border(sensor, object.states.col(last).head<2>()) < 0.4);
      } else {
        death.add(last + 1);
      }
    }
  }
  INFO("entered " << entered << ", left " << left << ", birth mean " << birth.mean() << ", death mean " << death.mean());
  CHECK(entered + left < 10);  // the crossing stays inside but for rare draws
  // Uniform on 1..20: mean 10.5, s.d. 5.77; on 30..50: mean 40, s.d. 6.06.
  CHECK(std::abs(birth.mean() - 10.5) < 5.0 * 5.77 / std::sqrt(birth.n));
  CHECK(std::abs(birth.sd() - 5.77) < 0.25);
  CHECK(std::abs(death.mean() - 40.0) < 5.0 * 6.06 / std::sqrt(death.n));
  CHECK(std::abs(death.sd() - 6.06) < 0.25);
  // Positions at the middle step ~ N((22.5, 18.5), 0.5² I).
  CHECK(std::abs(mid_x.mean() - 22.5) < 5.0 * 0.5 / std::sqrt(mid_x.n));
  CHECK(std::abs(mid_y.mean() - 18.5) < 5.0 * 0.5 / std::sqrt(mid_y.n));
  CHECK(std::abs(mid_x.sd() - 0.5) < 0.04);
  CHECK(std::abs(mid_y.sd() - 0.5) < 0.04);
}

TEST_CASE("tbd scenario: noise-free truth is straight-line NCV, objects leave and never return", "[tbd][scenario]") {
  // 100 steps: windows 1..40 / 60..100 around the middle step 50; at up to 0.3 m/step over 50
  // steps some crossing objects reach the border.
  const TbdImageScenario scenario = scenario_from(coarse({{"steps", "100"}, {"truth_noise_variance", "0"}, {"scan_interval", "2"}}));
  const TbdSensor& sensor = scenario.sensor();
  int left = 0, entered = 0;
  TbdSample sample;
  for (int run = 0; run < 200; ++run) {
    RandomStream rng(kSeed, 6, run);
    scenario.generate(rng, sample);
    for (std::size_t n = 0; n < sample.truth.objects.size(); ++n) {
      const auto& object = sample.truth.objects[n];
      const auto [first, last] = lifetime(object);  // contiguous: nobody comes back
      REQUIRE(first >= 0);
      for (int k = first + 1; k <= last; ++k) {
        const Eigen::Vector4d x = object.states.col(k - 1);
        const Eigen::Vector4d expected{x[0] + 2.0 * x[2], x[1] + 2.0 * x[3], x[2], x[3]};
        REQUIRE((object.states.col(k) - expected).cwiseAbs().maxCoeff() < 1e-12);
      }
      if (n == 0) continue;  // the slow object (steps 1..70) never reaches the border
      const Eigen::Vector4d a = object.states.col(first), b = object.states.col(last);
      const bool outside_before = !sensor.inside(a[0] - 2.0 * a[2], a[1] - 2.0 * a[3]);
      const bool outside_after = !sensor.inside(b[0] + 2.0 * b[2], b[1] + 2.0 * b[3]);
      if (first + 1 > 40) CHECK(outside_before);  // born after the birth window: it entered
      if (last + 1 < 60) CHECK(outside_after);    // dead before the death window: it left
      entered += outside_before ? 1 : 0;
      left += outside_after ? 1 : 0;
    }
  }
  INFO("crossing objects that entered " << entered << ", left " << left << " (of 800)");
  CHECK(entered > 0);
  CHECK(left > 0);
}

TEST_CASE("tbd scenario: persistent objects start at step 1 in the middle half and mostly stay", "[tbd][scenario]") {
  const TbdImageScenario scenario = scenario_from(coarse({{"layout", "persistent"}, {"objects", "7"}}));
  const TbdSensor& sensor = scenario.sensor();
  constexpr int kRuns = 300;
  int stayed = 0, total = 0;
  TbdSample sample;
  for (int run = 0; run < kRuns; ++run) {
    RandomStream rng(kSeed, 7, run);
    scenario.generate(rng, sample);
    REQUIRE(sample.truth.objects.size() == 7);
    for (const auto& object : sample.truth.objects) {
      const auto [first, last] = lifetime(object);
      REQUIRE(first == 0);
      CHECK((object.states(0, 0) >= 8.0 && object.states(0, 0) <= 24.0));
      CHECK((object.states(1, 0) >= 8.0 && object.states(1, 0) <= 24.0));
      const double speed = object.states.col(0).tail<2>().norm();
      CHECK((speed >= 0.1 && speed <= 0.3));
      ++total;
      if (last == 49) ++stayed;
      else CHECK(to_border(sensor, object.states.col(last).head<2>()) < 0.4);
    }
  }
  // Documented: 0.879 stay all 50 steps (40 000 objects); se √(0.879 · 0.121/2100) = 0.0071.
  const double fraction = static_cast<double>(stayed) / total;
  INFO("fraction inside for all 50 steps: " << fraction);
  CHECK(std::abs(fraction - 0.879) < 5.0 * 0.0071);
}

TEST_CASE("tbd scenario: toy layout is the supplement's 10 x 10 example", "[tbd][scenario]") {
  const TbdImageScenario scenario = scenario_from({{"layout", "toy"}, {"columns", "10"}});
  TbdSample sample;
  RandomStream rng(kSeed, 8, 0);
  scenario.generate(rng, sample);
  CHECK(sample.problem.sensor.columns == 10);
  CHECK(sample.problem.sensor.rows == 10);
  CHECK(sample.problem.sensor.cell_size == 1.0);
  REQUIRE(sample.problem.steps() == 1);
  CHECK(sample.problem.frames[0].cols() == 100);
  REQUIRE(sample.truth.objects.size() == 2);
  CHECK(sample.truth.objects[0].states.col(0) == Eigen::Vector4d(4.0, 4.0, 0.0, 0.0));
  CHECK(sample.truth.objects[1].states.col(0) == Eigen::Vector4d(5.0, 5.0, 0.0, 0.0));
  CHECK((sample.truth.objects[0].alive[0] && sample.truth.objects[1].alive[0]));
}

TEST_CASE("tbd scenario: the problem carries the options' model", "[tbd][scenario]") {
  const TbdImageScenario scenario = scenario_from({{"signal", "d2"}, {"sigma_s2", "2"}, {"noise_variance", "1.5"},
                                                {"amplitude", "40"}, {"driving_noise_variance", "0.001"},
                                                {"scan_interval", "0.5"}, {"survival_probability", "0.999"},
                                                {"birth_mean", "0.02"}, {"birth_speed_sd", "0.2"},
                                                {"columns", "24"}, {"rows", "16"}, {"cell_size", "0.5"}});
  TbdSample sample;
  sample.problem.trial_key = {7, 8, 9};  // the harness's to set
  RandomStream rng(kSeed, 9, 0);
  scenario.generate(rng, sample);
  const dabench::TbdProblem& p = sample.problem;
  CHECK(p.sensor.signal == dabench::TbdSignal::deterministic);
  CHECK(p.sensor.signal_scale == 2.0);
  CHECK(p.sensor.noise_variance == 1.5);
  CHECK(p.sensor.spread_variance == 1.5);  // d2's own
  CHECK((p.sensor.columns == 24 && p.sensor.rows == 16 && p.sensor.cell_size == 0.5));
  CHECK((p.sensor.x_max() == 12.0 && p.sensor.y_max() == 8.0));
  CHECK(p.amplitude == 40.0);
  CHECK(p.motion.scan_interval == 0.5);
  CHECK(p.motion.driving_noise_variance == 0.001);
  CHECK(p.filter.survival_probability == 0.999);
  CHECK(p.filter.birth_mean == 0.02);
  CHECK(p.filter.birth_speed_sd == 0.2);
  CHECK((p.trial_key.seed == 7 && p.trial_key.point == 8 && p.trial_key.trial == 9));
  REQUIRE(p.steps() == 50);
  for (const auto& frame : p.frames) CHECK(frame.cols() == 24 * 16);
  // Anchors scale with the region: the slow object sits near (12.7, 7.5)·(12/32, 8/32).
  CHECK((sample.truth.objects[0].states.col(17).head<2>() - Eigen::Vector2d{12.7 * 12.0 / 32.0, 7.5 * 8.0 / 32.0}).norm() < 2.5);
  CHECK(scenario_from({{"spread_variance", "0.8"}}).sensor().spread_variance == 0.8);
  CHECK(scenario_from({}).sensor().spread_variance == 0.5);
}

TEST_CASE("tbd scenario: registry builds it, same trial gives bit-identical frames, another trial others", "[tbd][scenario]") {
  const auto* entry = dabench::tbd_scenario_registry().find("tbd");
  REQUIRE(entry != nullptr);
  const auto scenario = entry->create({{"objects", "4"}});
  const auto other_layout = entry->create({{"layout", "persistent"}, {"objects", "9"}, {"steps", "60"}});
  TbdSample a, b, c;
  RandomStream rng_a(kSeed, 10, 3), rng_b(kSeed, 10, 3), rng_c(kSeed, 10, 4), rng_other(kSeed, 10, 5);
  other_layout->generate(rng_other, b);  // b is reused: generate must overwrite everything
  scenario->generate(rng_a, a);
  scenario->generate(rng_b, b);
  scenario->generate(rng_c, c);
  REQUIRE(a.problem.steps() == 50);
  REQUIRE(b.problem.steps() == 50);
  REQUIRE(b.truth.objects.size() == 4);
  bool same = true, differs = false;
  for (int k = 0; k < 50; ++k) {
    same = same && a.problem.frames[k] == b.problem.frames[k];
    differs = differs || a.problem.frames[k] != c.problem.frames[k];
  }
  for (int n = 0; n < 4; ++n) {
    const auto& x = a.truth.objects[n];
    const auto& y = b.truth.objects[n];
    same = same && x.alive == y.alive;
    for (int k = 0; k < 50; ++k) same = same && (!x.alive[k] || x.states.col(k) == y.states.col(k));
  }
  CHECK(same);
  CHECK(differs);
}

TEST_CASE("tbd scenario: bad options are one-line errors naming the field", "[tbd][scenario]") {
  const auto* entry = dabench::tbd_scenario_registry().find("tbd");
  REQUIRE(entry != nullptr);
  const auto message = [&](std::vector<KeyValue> settings) {
    return dabench::test::input_error_message([&] { entry->create(settings); });
  };
  using Catch::Matchers::Contains;
  CHECK_THAT(message({{"objects", "0"}}), Contains("objects = 0"));
  CHECK_THAT(message({{"steps", "0"}}), Contains("steps = 0"));
  CHECK_THAT(message({{"columns", "0"}}), Contains("columns"));
  CHECK_THAT(message({{"cell_size", "0"}}), Contains("cell_size"));
  CHECK_THAT(message({{"noise_variance", "0"}}), Contains("noise_variance = 0"));
  CHECK_THAT(message({{"noise_variance", "-1"}}), Contains("noise_variance"));
  CHECK_THAT(message({{"sigma_s2", "-1"}}), Contains("sigma_s2"));
  CHECK_THAT(message({{"spread_variance", "-0.5"}}), Contains("spread_variance"));
  CHECK_THAT(message({{"truth_noise_variance", "-1"}}), Contains("truth_noise_variance"));
  CHECK_THAT(message({{"survival_probability", "1.5"}}), Contains("survival_probability"));
  CHECK_THAT(message({{"scan_interval", "0"}}), Contains("scan_interval"));
  CHECK_THAT(message({{"layout", "diagonal"}}), Contains("layout") && Contains("crossing, persistent, toy"));
  CHECK_THAT(message({{"signal", "d4"}}), Contains("signal") && Contains("d1, d2, d3"));
  CHECK_THAT(message({{"mean_share", "1.5"}}), Contains("mean_share = 1.5"));
  CHECK_THAT(message({{"frame", "experiments/tbd/fig1a-frame.csv"}}), Contains("frame") && Contains("layout = toy"));
  CHECK_THAT(message({{"layout", "toy"}, {"frame", "/dev/zero"}}), Contains("/dev/zero: not a regular file"));
  CHECK_THAT(message({{"layout", "toy"}, {"objects", "3"}}), Contains("objects = 3") && Contains("toy"));
  CHECK_THAT(message({{"layout", "toy"}, {"rows", "12"}}), Contains("rows = 12") && Contains("toy"));
  CHECK_THAT(message({{"layout", "toy"}, {"steps", "5"}}), Contains("steps = 5"));
  CHECK_THAT(message({{"colour", "1"}}), Contains("unknown parameter 'colour'"));
  for (const auto& line : {message({{"objects", "0"}}), message({{"layout", "toy"}, {"cell_size", "2"}})}) {
    CHECK(line.find('\n') == std::string::npos);
  }
  CHECK_NOTHROW(entry->create({{"layout", "toy"}, {"objects", "2"}, {"steps", "1"}, {"rows", "10"}}));
}

}  // namespace DABENCH_TEST_FILE
