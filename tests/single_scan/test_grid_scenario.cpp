// Tests of the "grid" scenario (Williams & Lau 2014, Sec. V): the covariance recursion against
// closed forms, the draw statistics against their sampling distributions (tolerance = 5
// standard errors, fixed seeds), the weights against an independent evaluation of eq (11).
#include <catch2/catch.hpp>

#include <Eigen/LU>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "harness/core/params.hpp"
#include "harness/single_scan/registry.hpp"
#include "scenarios/single_scan/grid.hpp"

namespace DABENCH_TEST_FILE {

namespace {

using dabench::GridDetails;
using dabench::GridOptions;
using dabench::GridScenario;
using dabench::KeyValue;
using dabench::RandomStream;
using dabench::ScenarioSample;

constexpr std::uint64_t kSeed = 20140601;

GridOptions options_from(const std::vector<KeyValue>& settings) {
  return dabench::make_options<GridOptions>(settings, "grid");
}

// One axis of the process noise of an interval tau: q [[tau³/3, tau²/2], [tau²/2, tau]].
Eigen::Matrix2d axis_noise(double q, double tau) {
  Eigen::Matrix2d Q;
  Q << q * tau * tau * tau / 3.0, q * tau * tau / 2.0, q * tau * tau / 2.0, q * tau;
  return Q;
}

template <class Matrix>
bool near(const Matrix& a, const Matrix& b, double tol) {
  return (a - b).cwiseAbs().maxCoeff() <= tol * std::max(1.0, b.cwiseAbs().maxCoeff());
}

double nis(const Eigen::Vector2d& z, const GridDetails::Target& t) {
  const Eigen::Vector2d d = z - t.estimate;
  return d.dot(t.innovation.inverse() * d);
}

}  // namespace

TEST_CASE("grid: parameters bind in the documented order and defaults are valid", "[grid]") {
  GridOptions options;
  dabench::ParamList params;
  options.bind(params);
  std::vector<std::string> keys;
  for (const auto& entry : params.entries()) keys.push_back(entry.key);
  CHECK(keys == std::vector<std::string>{"rows", "cols", "spacing", "pd", "lambda_fa", "r", "q", "T",
                                         "steps", "gate_miss", "weight_floor"});
  CHECK(options.validate().empty());
  CHECK(options.gate_threshold() == Approx(18.420680743952367).epsilon(1e-14));  // −2 ln 1e-4

  const auto* entry = dabench::single_scan_scenario_registry().find("grid");
  REQUIRE(entry != nullptr);
  CHECK(entry->create({{"rows", "3"}, {"spacing", "0"}}) != nullptr);
}

TEST_CASE("grid: bad configurations are rejected naming the field", "[grid]") {
  using Catch::Matchers::Contains;
  const std::vector<std::pair<KeyValue, std::string>> bad = {
      {{"pd", "0"}, "pd"},           {{"pd", "1"}, "pd"},         {{"spacing", "-1"}, "spacing"},
      {{"rows", "0"}, "rows"},       {{"cols", "-2"}, "cols"},    {{"lambda_fa", "0"}, "lambda_fa"},
      {{"r", "0"}, "r = "},          {{"q", "-0.1"}, "q = "},     {{"T", "0"}, "T = "},
      {{"steps", "-1"}, "steps"},    {{"gate_miss", "1"}, "gate_miss"}, {{"gate_miss", "0"}, "gate_miss"},
      {{"spacing", "1e9"}, "expected false alarms"},
  };
  for (const auto& [setting, field] : bad) {
    INFO(setting.key << "=" << setting.value);
    CHECK_THROWS_AS(options_from({setting}), dabench::InputError);
    CHECK_THROWS_WITH(options_from({setting}), Contains(field));
  }
  CHECK_THROWS_WITH(options_from({{"rows", "1000"}, {"cols", "1000"}}), Contains("rows*cols = 1000000"));
  CHECK_NOTHROW(options_from({{"rows", "10"}, {"cols", "10"}, {"spacing", "0"}, {"q", "0"}, {"steps", "0"}}));
}

TEST_CASE("grid: covariance recursion matches closed forms", "[grid]") {
  const double q = 0.01, T = 1.0, r = 1.0;
  const dabench::ConstantVelocityModel model(q, T, r);
  auto never = [](int) { return false; };
  auto always = [](int) { return true; };

  // One predict from P = 0 gives Q.
  CHECK(dabench::prior_covariance(model, 0, never) == model.q1);
  CHECK(near(model.q1, axis_noise(q, T), 1e-15));

  // With no detections, k predicts give Σ_{l<k} F^l Q F^l' (4×4), which for the CV model equals
  // the noise of one interval of length k·T.
  const Eigen::Matrix4d F = dabench::lift(model.f), Q = dabench::lift(model.q1);
  for (int steps : {1, 4, 29}) {
    Eigen::Matrix4d sum = Eigen::Matrix4d::Zero(), Fl = Eigen::Matrix4d::Identity();
    for (int l = 0; l <= steps; ++l, Fl = F * Fl) sum += Fl * Q * Fl.transpose();
    const Eigen::Matrix2d p = dabench::prior_covariance(model, steps, never);
    CHECK(near(dabench::lift(p), sum, 1e-12));
    CHECK(near(p, axis_noise(q, (steps + 1) * T), 1e-12));
  }

  // One detected step, by hand per axis: P = Q = [[a, b], [b, c]], s = a + r,
  // update → [[a − a²/s, b − ab/s], [., c − b²/s]], then predict with F = [[1, T], [0, 1]].
  {
    const double a = q * T * T * T / 3.0, b = q * T * T / 2.0, c = q * T, s = a + r;
    const double ua = a - a * a / s, ub = b - a * b / s, uc = c - b * b / s;
    Eigen::Matrix2d expected = axis_noise(q, T);
    expected(0, 0) += ua + 2.0 * T * ub + T * T * uc;
    expected(0, 1) += ub + T * uc;
    expected(1, 0) += ub + T * uc;
    expected(1, 1) += uc;
    CHECK(near(dabench::prior_covariance(model, 1, always), expected, 1e-14));
  }

  // The per-axis recursion equals the 4×4 Kalman filter with H = I2 ⊗ [1 0], R = r·I2, for an
  // arbitrary detection pattern and other (q, T, r).
  {
    const dabench::ConstantVelocityModel other(0.3, 0.5, 2.0);
    Eigen::Matrix<double, 2, 4> H = Eigen::Matrix<double, 2, 4>::Zero();
    H(0, 0) = H(1, 2) = 1.0;
    const Eigen::Matrix2d R = 2.0 * Eigen::Matrix2d::Identity();
    const Eigen::Matrix4d F4 = dabench::lift(other.f), Q4 = dabench::lift(other.q1);
    auto pattern = [](int k) { return k % 3 != 1; };
    Eigen::Matrix4d P = Eigen::Matrix4d::Zero();
    for (int k = 0; k < 12; ++k) {
      P = F4 * P * F4.transpose() + Q4;
      if (pattern(k)) {
        const Eigen::Matrix<double, 4, 2> K = P * H.transpose() * (H * P * H.transpose() + R).inverse();
        P = P - K * H * P;
      }
    }
    P = F4 * P * F4.transpose() + Q4;
    CHECK(near(dabench::lift(dabench::prior_covariance(other, 12, pattern)), P, 1e-12));
  }

  // Always detected: the prior converges to the fixed point of the Riccati recursion.
  const Eigen::Matrix2d steady = dabench::prior_covariance(model, 500, always);
  CHECK(near(model.predict(model.update(steady)), steady, 1e-12));
  CHECK(steady(0, 0) < dabench::prior_covariance(model, 500, never)(0, 0));
}

TEST_CASE("grid: the generator uses the recursion with per-target detection histories", "[grid]") {
  auto priors = [](const std::string& pd) {
    const GridScenario grid(options_from({{"pd", pd}, {"steps", "7"}}));
    RandomStream rng(kSeed, 0, 0);
    ScenarioSample sample;
    GridDetails details;
    grid.generate(rng, sample, &details);
    std::vector<Eigen::Matrix4d> out;
    for (const auto& t : details.targets) out.push_back(t.prior);
    return out;
  };
  const dabench::ConstantVelocityModel model(0.01, 1.0, 1.0);
  for (const auto& P : priors("1e-9")) CHECK(P == dabench::lift(dabench::prior_covariance(model, 7, [](int) { return false; })));
  for (const auto& P : priors("0.999999999999")) {
    CHECK(P == dabench::lift(dabench::prior_covariance(model, 7, [](int) { return true; })));
  }
  const auto mixed = priors("0.6");
  int distinct = 0;
  for (std::size_t i = 1; i < mixed.size(); ++i) distinct += mixed[i] != mixed[0];
  CHECK(distinct > 0);
}

TEST_CASE("grid: false alarms are Poisson with mean lambda_fa times the gate-covering area", "[grid]") {
  SECTION("q = 0, steps = 0: estimates are exact, S = rI, the box is known in advance") {
    const double spacing = 3.0, lambda = 0.1, r = 1.0, gamma = -2.0 * std::log(1e-4);
    const GridScenario grid(options_from({{"spacing", "3"}, {"lambda_fa", "0.1"}, {"q", "0"}, {"steps", "0"}}));
    const double w = std::sqrt(gamma * r);
    const double area = (2.0 * spacing + 2.0 * w) * (1.0 * spacing + 2.0 * w);
    const int draws = 4000;
    double total = 0.0;
    ScenarioSample sample;
    GridDetails details;
    for (int t = 0; t < draws; ++t) {
      RandomStream rng(kSeed, 1, static_cast<std::uint32_t>(t));
      grid.generate(rng, sample, &details);
      total += sample.false_alarms;
    }
    CHECK(details.area() == Approx(area).epsilon(1e-12));
    CHECK(details.box_lo.x() == Approx(-w).epsilon(1e-12));
    CHECK(details.box_hi.y() == Approx(spacing + w).epsilon(1e-12));
    const double mean = lambda * area, se = std::sqrt(mean / draws);
    CHECK(std::abs(total / draws - mean) < 5.0 * se);
  }
  SECTION("defaults: the box covers every gate and the count matches its area") {
    const GridScenario grid(options_from({{"lambda_fa", "0.05"}}));
    const double gamma = grid.options().gate_threshold();
    const int draws = 3000;
    double excess = 0.0, variance = 0.0;
    ScenarioSample sample;
    GridDetails details;
    for (int t = 0; t < draws; ++t) {
      RandomStream rng(kSeed, 2, static_cast<std::uint32_t>(t));
      grid.generate(rng, sample, &details);
      Eigen::Vector2d lo = Eigen::Vector2d::Constant(1e300), hi = -lo;
      for (const auto& target : details.targets) {
        const Eigen::Vector2d half(std::sqrt(gamma * target.innovation(0, 0)), std::sqrt(gamma * target.innovation(1, 1)));
        lo = lo.cwiseMin(target.estimate - half);
        hi = hi.cwiseMax(target.estimate + half);
      }
      REQUIRE((details.box_lo - lo).norm() < 1e-12);
      REQUIRE((details.box_hi - hi).norm() < 1e-12);
      for (const auto& z : details.measurements) {  // every kept measurement lies in some gate, so in the box
        REQUIRE((z.array() >= lo.array()).all());
        REQUIRE((z.array() <= hi.array()).all());
      }
      const double mean = 0.05 * details.area();
      excess += sample.false_alarms - mean;
      variance += mean;
    }
    CHECK(std::abs(excess) / std::sqrt(variance) < 5.0);
  }
}

TEST_CASE("grid: detection rate is pd and gate misses occur at rate gate_miss", "[grid][release-only]") {
  SECTION("pd = 0.3, gate_miss = 0.05 on 2x3 targets") {
    const GridScenario grid(options_from({{"pd", "0.3"}, {"gate_miss", "0.05"}}));
    const int draws = 6000, n = 6;
    double detections = 0.0, gated_out = 0.0;
    ScenarioSample sample;
    GridDetails details;
    for (int t = 0; t < draws; ++t) {
      RandomStream rng(kSeed, 3, static_cast<std::uint32_t>(t));
      grid.generate(rng, sample, &details);
      int detected = 0, kept = 0;
      for (int i = 0; i < n; ++i) {
        detected += details.targets[i].detected;
        kept += sample.true_measurement[i] > 0;
      }
      REQUIRE(detected == sample.detections);
      REQUIRE(kept == sample.detections - sample.gated_out_detections);
      detections += sample.detections;
      gated_out += sample.gated_out_detections;
    }
    const double trials = draws * n;
    CHECK(std::abs(detections / trials - 0.3) < 5.0 * std::sqrt(0.3 * 0.7 / trials));
    CHECK(std::abs(gated_out / detections - 0.05) < 5.0 * std::sqrt(0.05 * 0.95 / detections));
  }
  SECTION("default gate_miss = 1e-4 on 10x10 targets (loose)") {
    const GridScenario grid(options_from({{"rows", "10"}, {"cols", "10"}}));
    const int draws = 2000;
    double detections = 0.0, gated_out = 0.0;
    ScenarioSample sample;
    for (int t = 0; t < draws; ++t) {
      RandomStream rng(kSeed, 4, static_cast<std::uint32_t>(t));
      grid.generate(rng, sample);
      detections += sample.detections;
      gated_out += sample.gated_out_detections;
    }
    const double trials = draws * 100.0;
    CHECK(std::abs(detections / trials - 0.6) < 5.0 * std::sqrt(0.6 * 0.4 / trials));
    const double expected = 1e-4 * detections;  // ≈ 12: Poisson-like count
    CHECK(std::abs(gated_out - expected) < 5.0 * std::sqrt(expected));
  }
}

TEST_CASE("grid: normalised innovation squared of true detections is chi-square(2)", "[grid]") {
  // Mean 2 and variance 4 only if the estimate noise is N(0, HPH') and z noise is N(0, R).
  for (const std::string r : {"1", "0.1"}) {
    INFO("r = " << r);
    const GridScenario grid(options_from({{"r", r}, {"pd", "0.9"}}));
    std::vector<double> values;
    ScenarioSample sample;
    GridDetails details;
    for (int t = 0; t < 2000; ++t) {
      RandomStream rng(kSeed, 5, static_cast<std::uint32_t>(t));
      grid.generate(rng, sample, &details);
      for (const auto& target : details.targets) {
        if (target.detected) values.push_back(nis(target.measurement, target));
      }
    }
    const double count = static_cast<double>(values.size());
    double mean = 0.0, var = 0.0;
    for (double v : values) mean += v / count;
    for (double v : values) var += (v - mean) * (v - mean) / (count - 1.0);
    CHECK(std::abs(mean - 2.0) < 5.0 * 2.0 / std::sqrt(count));
    CHECK(std::abs(var - 4.0) < 5.0 * std::sqrt(128.0 / count));  // Var of s² for Exp(mean 2): 128/N
  }
}

TEST_CASE("grid: weights equal eq (11) inside the gate and 0 outside or below the floor", "[grid]") {
  int floored = 0;
  for (const std::vector<KeyValue>& settings : std::vector<std::vector<KeyValue>>{
           {{"rows", "1"}, {"cols", "1"}, {"lambda_fa", "0.1"}},
           {{"spacing", "0"}, {"pd", "0.9"}},
           {{"spacing", "2"}, {"r", "10"}, {"lambda_fa", "0.0316"}},
           {{"spacing", "2"}, {"lambda_fa", "0.1"}, {"weight_floor", "0.5"}}}) {
    const GridScenario grid(options_from(settings));
    const GridOptions& o = grid.options();
    const double gamma = o.gate_threshold();
    ScenarioSample sample;
    GridDetails details;
    int checked_true = 0;
    for (int t = 0; t < 300; ++t) {
      RandomStream rng(kSeed, 6, static_cast<std::uint32_t>(t));
      grid.generate(rng, sample, &details);
      const auto& psi = sample.problem.psi;
      REQUIRE(sample.problem.validate().empty());
      REQUIRE(sample.problem.has_unit_side_weights());
      REQUIRE(sample.problem.context.pd == o.pd);
      REQUIRE(sample.problem.context.lambda_fa == o.lambda_fa);
      REQUIRE(psi.rows() == o.rows * o.cols);
      REQUIRE(psi.cols() == static_cast<Eigen::Index>(details.measurements.size()));
      REQUIRE(psi.cols() <= sample.detections + sample.false_alarms);
      for (Eigen::Index j = 0; j < psi.cols(); ++j) REQUIRE(psi.col(j).maxCoeff() > 0.0);
      for (Eigen::Index i = 0; i < psi.rows(); ++i) {
        const auto& target = details.targets[i];
        const double norm = 2.0 * std::numbers::pi * std::sqrt(target.innovation.determinant());
        for (Eigen::Index j = 0; j < psi.cols(); ++j) {
          const double d2 = nis(details.measurements[j], target);
          const double eq11 = o.pd * std::exp(-0.5 * d2) / norm / (o.lambda_fa * (1.0 - o.pd));
          const double expected = d2 > gamma || eq11 < o.weight_floor ? 0.0 : eq11;
          floored += d2 <= gamma && eq11 < o.weight_floor;
          REQUIRE(psi(i, j) == Approx(expected).epsilon(1e-12).margin(0.0));
        }
        const int column = sample.true_measurement[i];
        if (column > 0) {
          REQUIRE(target.detected);
          REQUIRE(details.measurements[column - 1] == target.measurement);
          REQUIRE(psi(i, column - 1) > 0.0);
          ++checked_true;
        } else if (target.detected) {
          const double d2 = nis(target.measurement, target);
          const double eq11 = o.pd * std::exp(-0.5 * d2) / norm / (o.lambda_fa * (1.0 - o.pd));
          REQUIRE((d2 > gamma || eq11 < o.weight_floor));
        }
      }
    }
    CHECK(checked_true > 100);
  }
  CHECK(floored > 100);  // the floor case really removed gated weights
}

TEST_CASE("grid: measurement order does not reveal the true measurement", "[grid]") {
  // After a uniform shuffle, target 0's measurement is uniform over the m kept columns:
  // position/(m−1) has mean 1/2 and variance (m+1)/(12(m−1)).
  const GridScenario grid(options_from({{"pd", "0.9"}}));
  double sum = 0.0, variance = 0.0;
  int used = 0;
  ScenarioSample sample;
  for (int t = 0; t < 6000; ++t) {
    RandomStream rng(kSeed, 7, static_cast<std::uint32_t>(t));
    grid.generate(rng, sample);
    const int m = sample.problem.measurements();
    if (sample.true_measurement[0] == 0 || m < 2) continue;
    sum += (sample.true_measurement[0] - 1) / (m - 1.0) - 0.5;
    variance += (m + 1.0) / (12.0 * (m - 1.0));
    ++used;
  }
  REQUIRE(used > 4000);
  CHECK(std::abs(sum) < 5.0 * std::sqrt(variance));
}

TEST_CASE("grid: a draw is a function of (seed, point, trial) alone", "[grid]") {
  const GridScenario grid(options_from({{"rows", "3"}, {"spacing", "2"}}));
  auto draw = [&](ScenarioSample& sample, std::uint32_t trial) {
    RandomStream rng(kSeed, 9, trial);
    grid.generate(rng, sample);
  };
  ScenarioSample a, b, c;
  draw(a, 11);
  draw(b, 12);
  draw(b, 11);  // reuse a sample that held another draw
  REQUIRE(a.problem.psi.rows() == b.problem.psi.rows());
  REQUIRE(a.problem.psi.cols() == b.problem.psi.cols());
  CHECK(a.problem.psi == b.problem.psi);
  CHECK(a.true_measurement == b.true_measurement);
  CHECK(a.false_alarms == b.false_alarms);
  CHECK(a.detections == b.detections);

  // Filling details does not change the draw.
  RandomStream rng(kSeed, 9, 11);
  GridDetails details;
  grid.generate(rng, c, &details);
  CHECK(c.problem.psi == a.problem.psi);

  draw(c, 12);
  const bool differs = c.problem.psi.cols() != a.problem.psi.cols() || c.problem.psi != a.problem.psi;
  CHECK(differs);
}

}  // namespace DABENCH_TEST_FILE
