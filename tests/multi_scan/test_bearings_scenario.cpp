// Tests of the "bearings" scenario (multiscan-convex-variational, Sec. IV): draw statistics
// against their sampling distributions (tolerance 5 standard errors, fixed seeds), eq (33)
// against an independent evaluation and one hand-computed value, the particle representation
// (region, wedge, weights ∝ L(φ)², exact proposal density) and determinism.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "harness/core/params.hpp"
#include "scenarios/multi_scan/bearings.hpp"

namespace DABENCH_TEST_FILE {

namespace {

using dabench::BearingsDetails;
using dabench::BearingsOptions;
using dabench::BearingsScenario;
using dabench::KeyValue;
using dabench::MultiScanSample;
using dabench::RandomStream;

constexpr std::uint64_t kSeed = 20160401;
constexpr double kPi = std::numbers::pi;

BearingsOptions options_from(const std::vector<KeyValue>& settings) {
  return dabench::make_options<BearingsOptions>(settings, "bearings");
}

double wrapped(double angle) { return std::remainder(angle, 2.0 * kPi); }

}  // namespace

TEST_CASE("bearings: target count false alarms and detections match their distributions", "[bearings]") {
  const BearingsScenario scenario(options_from({{"particles", "1"}, {"scans_per_sensor", "3"}}));
  constexpr int kDraws = 3000;
  double targets = 0.0, target_squares = 0.0, false_alarms = 0.0, detections = 0.0;
  int scans = 0;
  MultiScanSample sample;
  for (int k = 0; k < kDraws; ++k) {
    RandomStream rng(kSeed, 0, static_cast<std::uint32_t>(k));
    scenario.generate(rng, sample);
    const double n = sample.problem.tracks();
    targets += n;
    target_squares += n * n;
    false_alarms += sample.false_alarms;
    detections += sample.detections;
    scans += sample.problem.scan_count();
    REQUIRE(sample.problem.scan_count() == 12);
    REQUIRE(sample.problem.validate().empty());
  }
  const double mean = targets / kDraws;
  CHECK(std::fabs(mean - 8.0) < 5.0 * std::sqrt(8.0 / kDraws));
  CHECK(std::fabs(target_squares / kDraws - mean * mean - 8.0) < 1.0);  // Poisson: variance = mean
  CHECK(std::fabs(false_alarms / scans - 1.0) < 5.0 * std::sqrt(1.0 / scans));
  const double chances = targets * 12.0;  // target-scan pairs
  CHECK(std::fabs(detections / chances - 0.9) < 5.0 * std::sqrt(0.9 * 0.1 / chances));
}

TEST_CASE("bearings: factors follow eq 33 and one value checked by hand", "[bearings]") {
  const BearingsOptions options = options_from({{"particles", "50"}});
  const BearingsScenario scenario(options);
  MultiScanSample sample;
  BearingsDetails details;
  RandomStream rng(kSeed, 1, 0);
  scenario.generate(rng, sample, &details);
  REQUIRE(sample.problem.tracks() > 0);
  REQUIRE(sample.problem.scan_count() == 4);
  const double sd = kPi / 180.0;
  const double clutter_density = 1.0 / (kPi / 2.0);
  int checked = 0;
  for (int t = 0; t < 4; ++t) {
    REQUIRE(details.scan_sensor[t] == t);
    const Eigen::Vector2d sensor = BearingsScenario::sensor_position(t);
    for (int i = 0; i < sample.problem.tracks(); ++i) {
      const auto& factor = sample.problem.scans[t].factor[i];
      for (int h : {0, 17, 50}) {  // two particles and the truth probe
        const Eigen::Vector2d x = details.targets[i].particles.row(h).transpose();
        CHECK(factor(h, 0) == Approx(0.1));
        for (int j = 1; j <= sample.problem.scans[t].measurements; ++j) {
          const double difference = wrapped(details.bearings[t][j - 1] - std::atan2(x.y() - sensor.y(), x.x() - sensor.x()));
          const double expected = std::exp(-0.5 * difference * difference / (sd * sd)) / (std::sqrt(2.0 * kPi) * sd) *
                                  0.9 / clutter_density;
          if (std::fabs(difference) > 37.0 * sd) {
            CHECK(factor(h, j) == 0.0);
          } else {
            CHECK(factor(h, j) == Approx(expected).epsilon(1e-12));
            ++checked;
          }
        }
      }
    }
  }
  CHECK(checked > 0);
  // By hand: a bearing 1° (= σ) off the prediction gives 0.9·(π/2)/(√(2π)·π/180)·e^{−1/2}
  // = 81/√(2π)·e^{−1/2} = 19.59963...
  const double one_sigma = 0.9 / clutter_density / (std::sqrt(2.0 * kPi) * sd) * std::exp(-0.5);
  CHECK(one_sigma == Approx(19.59963).epsilon(1e-6));
}

TEST_CASE("bearings: particles lie on the initialising bearing inside the region with weights L squared",
          "[bearings]") {
  const BearingsScenario scenario(options_from({{"particles", "400"}, {"poisson_targets", "0"}, {"mean_targets", "6"}}));
  MultiScanSample sample;
  BearingsDetails details;
  RandomStream rng(kSeed, 2, 0);
  scenario.generate(rng, sample, &details);
  REQUIRE(sample.problem.tracks() == 6);
  for (int i = 0; i < 6; ++i) {
    const auto& target = details.targets[i];
    REQUIRE(target.particles.rows() == 401);
    REQUIRE(sample.truth_probe[i] == 400);
    CHECK(target.particles.row(400).transpose() == target.truth);
    const Eigen::Vector2d corner = BearingsScenario::sensor_position(target.init_sensor);
    const double start = BearingsScenario::wedge_start(target.init_sensor);
    double weighted_bearing = 0.0, weight_sum = 0.0;
    for (int p = 0; p < 400; ++p) {
      const Eigen::Vector2d x = target.particles.row(p).transpose();
      CHECK(x.cwiseAbs().maxCoeff() <= 100.0 + 1e-9);
      const double phi = wrapped(std::atan2(x.y() - corner.y(), x.x() - corner.x()) - start);
      const double length = BearingsScenario::ray_length(phi);
      CHECK(sample.problem.prior[i][p] == Approx(length * length / 40000.0).epsilon(1e-9));
      CHECK(sample.density_scale[i][p] == Approx(400.0 * target.proposal_density[p]).epsilon(1e-12));
      // g(x) = TN(φ)·2/L² ≤ the untruncated normal's peak / mass · 2/L²: at least positive.
      CHECK(target.proposal_density[p] > 0.0);
      weighted_bearing += sample.problem.prior[i][p] * phi;
      weight_sum += sample.problem.prior[i][p];
    }
    // The bearing posterior is N(φ_m, 0.1°²) (up to the wedge): the weighted mean is within
    // 5 standard errors (0.1°/√400) of the measured bearing unless the wedge truncates it.
    const double measured = target.init_bearing;
    if (measured > 0.01 && measured < kPi / 2 - 0.01) {
      CHECK(std::fabs(weighted_bearing / weight_sum - measured) < 5.0 * (0.1 * kPi / 180.0) / 20.0);
    }
    // Truth probe: prior ε·L(φ*)², scale N·g(x*)/ε.
    const double probe_phi = wrapped(std::atan2(target.truth.y() - corner.y(), target.truth.x() - corner.x()) - start);
    const double probe_length = BearingsScenario::ray_length(probe_phi);
    CHECK(sample.problem.prior[i][400] == Approx(1e-6 * probe_length * probe_length / 40000.0).epsilon(1e-9));
    CHECK(sample.density_scale[i][400] == Approx(400.0 * target.proposal_density[400] / 1e-6).epsilon(1e-12));
  }
}

TEST_CASE("bearings: the proposal density integrates to one over the region", "[bearings]") {
  // Σ_p 1/g(x_p) / N estimates the area the proposal covers (E_g[1/g] = |support|), which is
  // the region minus nothing: 40000 within Monte Carlo error. Using particles of many tracks.
  const BearingsScenario scenario(options_from({{"particles", "20000"}, {"poisson_targets", "0"}, {"mean_targets", "1"},
                                                {"init_noise_deg", "30"}}));
  MultiScanSample sample;
  BearingsDetails details;
  RandomStream rng(kSeed, 3, 0);
  scenario.generate(rng, sample, &details);
  double sum = 0.0, squares = 0.0;
  for (int p = 0; p < 20000; ++p) {
    const double inverse = 1.0 / details.targets[0].proposal_density[p];
    sum += inverse;
    squares += inverse * inverse;
  }
  const double mean = sum / 20000.0;
  const double se = std::sqrt((squares / 20000.0 - mean * mean) / 20000.0);
  CHECK(std::fabs(mean - 40000.0) < 5.0 * se);
}

TEST_CASE("bearings: the same stream gives the same draw", "[bearings]") {
  const BearingsScenario scenario(options_from({{"particles", "30"}}));
  MultiScanSample a, b;
  RandomStream first(kSeed, 4, 7), second(kSeed, 4, 7);
  scenario.generate(first, a);
  scenario.generate(second, b);
  REQUIRE(a.problem.tracks() == b.problem.tracks());
  for (int i = 0; i < a.problem.tracks(); ++i) CHECK(a.problem.prior[i] == b.problem.prior[i]);
  for (int t = 0; t < a.problem.scan_count(); ++t) {
    for (int i = 0; i < a.problem.tracks(); ++i) CHECK(a.problem.scans[t].factor[i] == b.problem.scans[t].factor[i]);
  }
}

TEST_CASE("bearings: invalid parameters are refused with the field named", "[bearings]") {
  CHECK(BearingsOptions{.particles = 0}.validate().find("particles") != std::string::npos);
  CHECK(BearingsOptions{.mean_targets = 2.5, .poisson_targets = false}.validate().find("integer") != std::string::npos);
  CHECK(BearingsOptions{.pd = 1.0}.validate().find("pd") != std::string::npos);
  CHECK(BearingsOptions{.clutter_mean = 0.0}.validate().find("clutter_mean") != std::string::npos);
  CHECK(BearingsOptions{.scans_per_sensor = 0}.validate().find("scans_per_sensor") != std::string::npos);
}

TEST_CASE("bearings: init_sensor = corner initialises every track from init_corner",
          "[bearings]") {
  const BearingsScenario random(options_from({{"particles", "40"}, {"scans_per_sensor", "3"}, {"init_sensor", "random"}}));
  for (const int corner : {0, 2, 3}) {
    INFO("init_corner " << corner);
    const BearingsScenario fixed(options_from({{"particles", "40"}, {"scans_per_sensor", "3"}, {"init_sensor", "corner"},
                                               {"init_corner", std::to_string(corner)}}));
    for (std::uint32_t trial = 0; trial < 5; ++trial) {
      MultiScanSample a, b;
      BearingsDetails da, db;
      RandomStream ra(kSeed, 8, trial), rb(kSeed, 8, trial);
      random.generate(ra, a, &da);
      fixed.generate(rb, b, &db);
      REQUIRE(da.targets.size() == db.targets.size());
      // The same stream up to the first target whose corner differs (its particles then take
      // other numbers): the targets before it are the same, and its own position.
      bool same_stream = true;
      for (std::size_t i = 0; i < db.targets.size(); ++i) {
        const auto& t = db.targets[i];
        CHECK(t.init_sensor == corner);
        if (same_stream) CHECK(t.truth == da.targets[i].truth);
        same_stream = same_stream && da.targets[i].init_sensor == corner;
        // The particles lie on the bearing from that corner: within 6 init s.d. of its measured bearing.
        const Eigen::Vector2d c = BearingsScenario::sensor_position(corner);
        for (int p = 0; p < 40; ++p) {
          const Eigen::Vector2d d = t.particles.row(p).transpose() - c;
          const double phi = wrapped(std::atan2(d.y(), d.x()) - BearingsScenario::wedge_start(corner));
          CHECK(std::abs(phi - t.init_bearing) < 6.0 * 0.1 * kPi / 180.0);
        }
      }
      CHECK(da.scan_sensor == db.scan_sensor);
    }
  }
  CHECK(BearingsOptions{.init_corner = 4}.validate().find("init_corner") != std::string::npos);
}

TEST_CASE("bearings: scan_order = grouped takes each sensor's scans together", "[bearings]") {
  for (const int rounds : {1, 3}) {
    INFO("scans per sensor " << rounds);
    const auto order = [&](const char* scan_order) {
      const BearingsScenario scenario(options_from({{"particles", "20"}, {"scans_per_sensor", std::to_string(rounds)},
                                                    {"scan_order", scan_order}}));
      MultiScanSample sample;
      BearingsDetails details;
      RandomStream rng(kSeed, 9, 0);
      scenario.generate(rng, sample, &details);
      REQUIRE(static_cast<int>(details.scan_sensor.size()) == 4 * rounds);
      for (int t = 0; t < 4 * rounds; ++t) CHECK(details.scan_sensor[t] == scenario.scan_sensor(t));
      return details.scan_sensor;
    };
    const std::vector<int> round_robin = order("round_robin"), grouped = order("grouped");
    for (int t = 0; t < 4 * rounds; ++t) {
      CHECK(round_robin[t] == t % 4);
      CHECK(grouped[t] == t / rounds);
    }
    if (rounds == 1) CHECK(round_robin == grouped);
  }
}

TEST_CASE("bearings: init_sensor = site at a corner draws what corner draws", "[bearings]") {
  const BearingsScenario corner(options_from({{"particles", "50"}, {"init_sensor", "corner"}, {"init_corner", "1"}}));
  const BearingsScenario site(
      options_from({{"particles", "50"}, {"init_sensor", "site"}, {"init_site_x", "100"}, {"init_site_y", "-100"}}));
  for (std::uint32_t trial = 0; trial < 3; ++trial) {
    MultiScanSample a, b;
    BearingsDetails da, db;
    RandomStream ra(kSeed, 10, trial), rb(kSeed, 10, trial);
    corner.generate(ra, a, &da);
    site.generate(rb, b, &db);
    REQUIRE(a.problem.tracks() == b.problem.tracks());
    for (int i = 0; i < a.problem.tracks(); ++i) {
      CHECK(da.targets[i].particles == db.targets[i].particles);
      CHECK(a.problem.prior[i] == b.problem.prior[i]);
      CHECK(a.density_scale[i] == b.density_scale[i]);
      CHECK(db.targets[i].init_sensor == -1);
    }
    for (int t = 0; t < a.problem.scan_count(); ++t) {
      for (int i = 0; i < a.problem.tracks(); ++i) CHECK(a.problem.scans[t].factor[i] == b.problem.scans[t].factor[i]);
    }
  }
}

TEST_CASE("bearings: the region seen from a site: its wedge and each ray's segment against brute force", "[bearings]") {
  // The corner view by the general slab test reproduces L(φ) inside the wedge (on its edges the
  // ray runs along a side of the region, where rounding decides; generate() never keeps such a
  // bearing: its segment has no area).
  BearingsScenario::InitView general = BearingsScenario::corner_view(2);
  general.corner = false;
  for (const double phi : {1e-9, 0.3, kPi / 4, 1.2, kPi / 2 - 1e-9}) {
    const auto [near, far] = BearingsScenario::ray_segment(general, phi);
    CHECK(near == Approx(0.0).margin(1e-9));
    CHECK(far == Approx(BearingsScenario::ray_length(phi)).epsilon(1e-12));
  }
  RandomStream rng(kSeed, 11, 0);
  for (const Eigen::Vector2d& site : {Eigen::Vector2d(0.0, -250.0), Eigen::Vector2d(-300.0, 40.0),
                                     Eigen::Vector2d(0.0, -100.0), Eigen::Vector2d(180.0, 260.0)}) {
    INFO("site " << site.transpose());
    const BearingsScenario::InitView view = BearingsScenario::site_view(site);
    CHECK_FALSE(view.corner);
    CHECK(view.span > 0.0);
    CHECK(view.span <= kPi + 1e-12);
    // Every point of the region lies in the wedge, and points near its edges reach both ends.
    double lo = 10.0, hi = -10.0;
    for (int k = 0; k < 20000; ++k) {
      const Eigen::Vector2d x(rng.uniform(-100.0, 100.0), rng.uniform(-100.0, 100.0));
      const double phi = wrapped(std::atan2(x.y() - site.y(), x.x() - site.x()) - view.start);
      lo = std::min(lo, phi);
      hi = std::max(hi, phi);
      // x lies on its ray's segment.
      const auto [near, far] = BearingsScenario::ray_segment(view, phi);
      const double r = (x - site).norm();
      CHECK(r >= near - 1e-9);
      CHECK(r <= far + 1e-9);
    }
    CHECK(lo >= -1e-12);
    CHECK(hi <= view.span + 1e-12);
    CHECK(lo < 0.02);
    CHECK(hi > view.span - 0.02);
    // Just outside a segment is outside the region; just inside is inside.
    for (int k = 0; k < 200; ++k) {
      const double phi = view.span * (0.01 + 0.98 * rng.uniform());
      const auto [near, far] = BearingsScenario::ray_segment(view, phi);
      REQUIRE(far > near);
      const Eigen::Vector2d u(std::cos(view.start + phi), std::sin(view.start + phi));
      const auto inside = [](const Eigen::Vector2d& x) { return x.cwiseAbs().maxCoeff() <= 100.0 + 1e-9; };
      CHECK(inside(site + (0.5 * (near + far)) * u));
      CHECK(inside(site + (far - 1e-6) * u));
      CHECK_FALSE(inside(site + (far + 1e-3) * u));
      if (near > 1e-3) CHECK_FALSE(inside(site + (near - 1e-3) * u));
    }
  }
}

TEST_CASE("bearings: from a site the particles and weights represent the uniform prior times the bearing",
          "[bearings]") {
  // E_g[1/g] is the area the proposal covers: the whole region (40000) when the initialising
  // bearing is vague (30°), within Monte Carlo error; each particle's prior is (r_out² − r_in²) / 40000.
  const BearingsScenario scenario(options_from({{"particles", "20000"}, {"poisson_targets", "0"}, {"mean_targets", "2"},
                                                {"init_noise_deg", "30"}, {"init_sensor", "site"},
                                                {"init_site_x", "-40"}, {"init_site_y", "-220"}}));
  MultiScanSample sample;
  BearingsDetails details;
  RandomStream rng(kSeed, 12, 0);
  scenario.generate(rng, sample, &details);
  const BearingsScenario::InitView view = BearingsScenario::site_view({-40.0, -220.0});
  for (int i = 0; i < 2; ++i) {
    const auto& target = details.targets[i];
    CHECK(target.init_sensor == -1);
    double sum = 0.0, squares = 0.0;
    for (int p = 0; p < 20000; ++p) {
      const Eigen::Vector2d x = target.particles.row(p).transpose();
      CHECK(x.cwiseAbs().maxCoeff() <= 100.0 + 1e-9);
      const double phi = wrapped(std::atan2(x.y() + 220.0, x.x() + 40.0) - view.start);
      const auto [near, far] = BearingsScenario::ray_segment(view, phi);
      CHECK(sample.problem.prior[i][p] == Approx((far * far - near * near) / 40000.0).epsilon(1e-9));
      const double inverse = 1.0 / target.proposal_density[p];
      sum += inverse;
      squares += inverse * inverse;
    }
    const double mean = sum / 20000.0;
    const double se = std::sqrt((squares / 20000.0 - mean * mean) / 20000.0);
    CHECK(std::fabs(mean - 40000.0) < 5.0 * se);
    CHECK(target.particles.row(20000).transpose() == target.truth);
  }
  CHECK(BearingsOptions{.init_sensor = BearingsScenario::kInitSite, .init_site_x = 50.0, .init_site_y = 99.0}
            .validate()
            .find("init_site") != std::string::npos);
  CHECK(BearingsOptions{.init_sensor = BearingsScenario::kInitSite, .init_site_x = 0.0, .init_site_y = -100.0}
            .validate()
            .empty());
}

}  // namespace DABENCH_TEST_FILE
