// A frame cell that is not finite must make a track-before-detect tracker record a failure
// ("failed:…", written to trials.csv by the runner), not prune or recycle its potential objects
// as if they were unlikely (TBD-BP, both schedules, with a legacy PO or new POs only; TBD-MB,
// both associations).
#include <catch2/catch.hpp>

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "harness/core/random_stream.hpp"
#include "harness/core/solve_report.hpp"
#include "harness/tbd/problem.hpp"
#include "harness/tbd/registry.hpp"
#include "tests/support/tbd_frames.hpp"

namespace DABENCH_TEST_FILE {

namespace {

using dabench::TbdProblem;
using dabench::TbdSignal;

// A 10 × 10 D1 grid with an object at (4.5, 4.5) and cell (4, 4) (or (8, 8), away from it) set to `bad`.
TbdProblem poisoned(double bad, bool at_object, bool with_prior) {
  TbdProblem p = dabench::test::grid_problem(10, TbdSignal::fluctuating, 20231205, 0);
  dabench::RandomStream rng(20231205, 9, 0);
  p.frames.push_back(dabench::test::draw_frame(p.sensor, p.amplitude, {{4.5, 4.5}}, rng));
  p.frames[0](0, at_object ? 4 * 10 + 4 : 8 * 10 + 8) = bad;
  if (with_prior) {
    dabench::TbdPrior prior;
    prior.mean = Eigen::Vector4d(4.5, 4.5, 0.0, 0.0);
    prior.covariance = Eigen::Vector4d(0.05, 0.05, 1e-4, 1e-4).asDiagonal();
    prior.existence = 0.9;
    p.initial_objects.push_back(prior);
  }
  return p;
}

std::string first_step(const std::string& spec, const TbdProblem& p) {
  auto tracker = dabench::make_tbd_tracker(spec);
  tracker->start(p);
  std::vector<dabench::TbdEstimate> estimates;
  dabench::SolveReport report;
  tracker->step(0, estimates, report);
  return report.skipped;
}

}  // namespace

TEST_CASE("tbd trackers: a non-finite frame cell is a recorded failure, not a pruned object", "[tbd][non_finite]") {
  using Catch::Matchers::Contains;
  using Catch::Matchers::StartsWith;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const char* spec : {"tbd-bp:particles=200", "tbd-bp:particles=200,schedule=joint", "tbd-bp:particles=200,iterations=1",
                           "tbd-mb:particles=200", "tbd-mb:particles=200,association=none"}) {
    for (const bool with_prior : {true, false}) {
      INFO(spec << (with_prior ? ", a prior on the object" : ", new objects only"));
      const std::string why = first_step(spec, poisoned(nan, true, with_prior));
      CHECK_THAT(why, StartsWith("failed:step 1: ") && Contains("is not finite"));
      // The same frame without the bad cell is solved.
      CHECK(first_step(spec, poisoned(1.0, true, with_prior)).empty());
    }
  }
}

}  // namespace DABENCH_TEST_FILE
