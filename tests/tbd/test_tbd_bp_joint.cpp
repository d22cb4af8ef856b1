// Tests of TBD-BP's joint schedule (algorithms/tbd/tbd_bp.hpp: legacy and new POs exchange
// messages in every one of the L iterations; kept new POs enter the field with their
// cell-excluded messages):
//  - without new POs (birth_mean = 0) it is the serial schedule, bit for bit;
//  - at L = 1 the legacy POs' beliefs are the serial schedule's (the new POs speak after the
//    legacy POs' only sweep), at L = 2 they differ exactly when a new PO is kept within their
//    reach;
//  - an object born from the grid is reported once while present and pruned after it leaves.
#include <catch2/catch.hpp>

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "algorithms/tbd/tbd_bp.hpp"
#include "harness/core/random_stream.hpp"
#include "harness/core/solve_report.hpp"
#include "harness/tbd/problem.hpp"
#include "tests/support/input_error.hpp"
#include "tests/support/tbd_frames.hpp"

namespace DABENCH_TEST_FILE {

namespace {

using namespace dabench;
using namespace dabench::test;

constexpr std::uint64_t kSeed = 20231205;

// `steps` frames of a 12 × 12 D2 grid holding objects at `positions` (static).
TbdProblem static_scene(const std::vector<Eigen::Vector2d>& positions, int steps, std::uint32_t trial) {
  TbdProblem p = dabench::test::grid_problem(12, TbdSignal::deterministic, kSeed, trial);
  RandomStream rng(kSeed, 3, trial);
  for (int k = 0; k < steps; ++k) p.frames.push_back(dabench::test::draw_frame(p.sensor, p.amplitude, positions, rng));
  return p;
}

struct Outcome {
  std::vector<std::vector<TbdEstimate>> estimates;
  std::vector<std::vector<double>> legacy_x;  // per step: the particles' x of every PO, in order
};

Outcome run(const TbdProblem& p, int schedule, int iterations) {
  TbdBpOptions options;
  options.schedule = schedule;
  options.iterations = iterations;
  options.particles = 500;
  TbdBp tracker(options);
  tracker.start(p);
  Outcome out;
  for (int k = 0; k < p.steps(); ++k) {
    std::vector<TbdEstimate> estimates;
    SolveReport report;
    tracker.step(k, estimates, report);
    REQUIRE(report.skipped.empty());
    out.estimates.push_back(estimates);
    std::vector<double> xs;
    for (const auto& o : tracker.objects()) xs.insert(xs.end(), o.x.begin(), o.x.end());
    out.legacy_x.push_back(xs);
  }
  return out;
}

}  // namespace

TEST_CASE("tbd-bp joint schedule: without new POs it is the serial schedule, bit for bit", "[tbd][tbd_bp][joint]") {
  TbdProblem p = static_scene({{5.5, 6.5}, {6.6, 6.9}}, 3, 0);
  p.filter.birth_mean = 0.0;
  p.initial_objects = {prior_at(5.5, 6.5, 0.02, 1.0), prior_at(6.6, 6.9, 0.02, 1.0)};
  for (const int iterations : {1, 2, 3}) {
    INFO("L = " << iterations);
    const Outcome serial = run(p, TbdBp::kSerial, iterations), joint = run(p, TbdBp::kJoint, iterations);
    CHECK(serial.legacy_x == joint.legacy_x);
  }
}

TEST_CASE("tbd-bp joint schedule: legacy POs hear kept new POs from the second iteration on", "[tbd][tbd_bp][joint]") {
  // A known object at (5.5, 6.5) and a new one at (7.5, 6.5), 2 m apart: their windows
  // (4σ_h = 2.83 m) overlap. At step 0 the new one is born; the legacy PO's particles after the
  // step depend on the new PO's messages only if it heard them (L ≥ 2 under `joint`).
  TbdProblem p = static_scene({{5.5, 6.5}, {7.5, 6.5}}, 1, 1);
  p.initial_objects = {prior_at(5.5, 6.5, 0.02, 1.0)};
  const Outcome serial1 = run(p, TbdBp::kSerial, 1), joint1 = run(p, TbdBp::kJoint, 1);
  const Outcome serial2 = run(p, TbdBp::kSerial, 2), joint2 = run(p, TbdBp::kJoint, 2);
  for (const Outcome* o : {&serial1, &joint1, &serial2, &joint2}) {
    REQUIRE(o->estimates[0].size() == 2);  // the known object and one born object
    CHECK((o->estimates[0][1].state.head<2>() - Eigen::Vector2d(7.5, 6.5)).norm() < 0.5);
  }
  // The legacy PO's particles come first in legacy_x (then the born PO's).
  const auto legacy = [](const Outcome& o) { return std::vector<double>(o.legacy_x[0].begin(), o.legacy_x[0].begin() + 500); };
  CHECK(legacy(serial1) == legacy(joint1));
  CHECK(legacy(serial2) != legacy(joint2));
  CHECK(serial2.estimates[0][0].state != joint2.estimates[0][0].state);
}

TEST_CASE("tbd-bp joint schedule: an object born from the grid is reported once while present, then pruned",
          "[tbd][tbd_bp][joint]") {
  for (const int iterations : {1, 2}) {
    for (std::uint32_t trial = 0; trial < 2; ++trial) {
      INFO("L = " << iterations << ", trial " << trial);
      TbdProblem p = dabench::test::grid_problem(12, TbdSignal::deterministic, kSeed, trial);
      RandomStream rng(kSeed, 12, trial);
      for (int k = 0; k < 8; ++k) {
        const std::vector<Eigen::Vector2d> present{{5.5 + 0.1 * k, 6.5}};
        p.frames.push_back(dabench::test::draw_frame(p.sensor, p.amplitude, k < 5 ? present : std::vector<Eigen::Vector2d>{}, rng));
      }
      const Outcome o = run(p, TbdBp::kJoint, iterations);
      for (int k = 0; k < 8; ++k) {
        INFO("step " << k);
        if (k < 5) {
          REQUIRE(o.estimates[k].size() == 1);
          CHECK((o.estimates[k][0].state.head<2>() - Eigen::Vector2d(5.5 + 0.1 * k, 6.5)).norm() < 0.5);
          CHECK(o.estimates[k][0].label == o.estimates[0][0].label);
        } else {
          CHECK(o.estimates[k].empty());
        }
      }
    }
  }
}

TEST_CASE("tbd-bp joint schedule: it needs the Gaussian messages with interaction", "[tbd][tbd_bp][joint]") {
  using Catch::Matchers::Contains;
  const auto message = [](std::vector<dabench::KeyValue> settings) {
    return dabench::test::input_error_message([&] { dabench::make_options<TbdBpOptions>(settings, "tbd-bp"); });
  };
  CHECK_THAT(message({{"schedule", "joint"}, {"exact_kappa", "true"}}), Contains("schedule = joint"));
  CHECK_THAT(message({{"schedule", "joint"}, {"interaction", "false"}}), Contains("interaction = true"));
  CHECK_NOTHROW(dabench::make_options<TbdBpOptions>({{"schedule", "joint"}}, "tbd-bp"));
}

}  // namespace DABENCH_TEST_FILE
