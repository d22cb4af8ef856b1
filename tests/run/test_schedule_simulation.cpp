// `dabench schedule`'s simulation (harness/run/schedule_simulation.hpp): per-unit times read from
// a run's trials.csv by its kind's time column (one unit per row, or per item for single scan),
// and wall times that match hand-computed schedules.
#include <catch2/catch.hpp>

#include <string>

#include "harness/core/errors.hpp"
#include "harness/run/schedule_simulation.hpp"
#include "tests/support/cli_runner.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench;
using dabench::test::cli::TempDir;

namespace {

// A run folder's meta.json as far as read_run_costs reads it: the scenario, which says the kind.
void write_meta(const TempDir& dir, const std::string& scenario) {
  dir.write("meta.json", "{\"scenario\": \"" + scenario + "\", \"status\": \"complete\"}\n");
}

RunCosts one_point(int parts, std::vector<double> unit_seconds) {
  RunCosts costs;
  costs.parts = parts;
  costs.unit_seconds = std::move(unit_seconds);
  costs.item_points.assign(costs.unit_seconds.size() / static_cast<std::size_t>(parts), 0);
  return costs;
}

}  // namespace

TEST_CASE("schedule: per-unit times from trials.csv of each kind", "[run][schedule]") {
  TempDir dir;
  dir.write("trials.csv",
        "point,x,trial,seed,algorithm,status,n_targets,time_us\n"
        "0,1,0,7,cv,ok,3,1000000\n0,1,0,7,\"cvs:a=1,b=2\",ok,3,3000000\n"
        "1,2,0,7,cv,ok,3,2000000\n1,2,0,7,\"cvs:a=1,b=2\",skipped:no_targets,0,\n");
  write_meta(dir, "bearings");
  RunCosts costs = read_run_costs(dir.work().string(), "schedule");
  CHECK(costs.kind->name() == "multi-scan");
  CHECK_FALSE(costs.shared_items());
  CHECK(costs.parts == 2);
  CHECK(costs.points == 2);
  CHECK_FALSE(costs.from_means);
  CHECK(costs.item_points == std::vector<int>{0, 1});
  CHECK(costs.unit_seconds == std::vector<double>{1.0, 3.0, 2.0, 0.0});

  TempDir single;  // single scan: an item is one unit, its rows' times together
  single.write("trials.csv",
        "point,spacing,trial,seed,algorithm,status,n_targets,n_measurements,max_error,mean_error,time_us\n"
        "0,1,0,1,exact,ok,6,5,0,0,30\n0,1,0,1,bp,ok,6,5,0.01,0.001,2\n0,1,1,1,exact,ok,6,5,0,0,10\n0,1,1,1,bp,ok,6,5,0,0,4\n");
  write_meta(single, "grid");
  costs = read_run_costs(single.work().string(), "schedule");
  CHECK(costs.shared_items());
  CHECK(costs.parts == 1);
  REQUIRE(costs.unit_seconds.size() == 2);
  CHECK(costs.unit_seconds[0] == Approx(32e-6));
  CHECK(costs.unit_seconds[1] == Approx(14e-6));

  TempDir tbd;  // a track-before-detect report's runs.csv, sorted by algorithm: step_time_us × n_steps
  tbd.write("runs.csv",
            "point,trial,algorithm,n_steps,gospa,step_time_us\n0,0,tbd-bp,50,1.5,2000\n0,1,tbd-bp,50,1.5,1000\n"
            "0,0,tbd-mb,50,1.4,100\n0,1,tbd-mb,50,1.4,300\n");
  write_meta(tbd, "tbd");
  costs = read_run_costs(tbd.work().string(), "schedule");
  CHECK(costs.parts == 2);
  REQUIRE(costs.unit_seconds.size() == 4);  // items in trial order, each with its algorithms in file order
  CHECK(costs.unit_seconds[0] == Approx(0.1));
  CHECK(costs.unit_seconds[1] == Approx(0.005));
  CHECK(costs.unit_seconds[2] == Approx(0.05));
  CHECK(costs.unit_seconds[3] == Approx(0.015));

  TempDir means;  // a committed study's summary.csv: each trial costs its point's means
  means.write("summary.csv",
              "point,spacing,algorithm,trials,ok,max_error_mean,time_us_count,time_us_mean\n"
              "0,1,exact,3,3,0,3,30\n0,1,bp,3,3,0.01,3,2\n1,2,exact,2,2,0,2,10\n1,2,bp,2,2,0,2,4\n");
  write_meta(means, "grid");
  costs = read_run_costs(means.work().string(), "schedule");
  CHECK(costs.from_means);
  CHECK(costs.shared_items());
  CHECK(costs.item_points == std::vector<int>{0, 0, 0, 1, 1});
  CHECK(costs.unit_seconds[2] == Approx(32e-6));
  CHECK(costs.unit_seconds[4] == Approx(14e-6));
  CHECK(read_run_costs(means.work().string(), "schedule", 1).item_points == std::vector<int>{0, 1});  // the first trial of each point

  TempDir uneven;
  uneven.write("trials.csv", "point,trial,algorithm,tet_s\n0,0,a,1\n0,0,b,1\n0,1,a,1\n");
  write_meta(uneven, "othr");
  CHECK_THROWS_WITH(read_run_costs(uneven.work().string(), "schedule"), Catch::Contains("item 0,1 has 1 rows, the first had 2"));
  TempDir empty;
  CHECK_THROWS_WITH(read_run_costs(empty.work().string(), "schedule"), Catch::Contains("no trials.csv, runs.csv or summary.csv"));
  empty.write("trials.csv", "point,trial,time_us\n0,0,1\n");
  CHECK_THROWS_WITH(read_run_costs(empty.work().string(), "schedule"),
                    Catch::Equals("schedule: " + empty.work().string() + ": meta.json is missing (its scenario says the run's kind)"));
  write_meta(empty, "othr");  // a tracking run's time is tet_s, not time_us
  CHECK_THROWS_WITH(read_run_costs(empty.work().string(), "schedule"),
                    Catch::EndsWith("trials.csv: no point, trial and tet_s columns (a tracking run's)"));
  write_meta(empty, "tbd");
  CHECK_THROWS_WITH(read_run_costs(empty.work().string(), "schedule"),
                    Catch::EndsWith("no point, trial and step_time_us and n_steps columns (a track-before-detect run's)"));
  write_meta(empty, "no-such-scenario");
  CHECK_THROWS_WITH(read_run_costs(empty.work().string(), "schedule"),
                    Catch::Contains("scenario 'no-such-scenario' is of no problem kind this build knows"));
}

TEST_CASE("schedule: simulated wall times of hand-computed schedules", "[run][schedule]") {
  // 4 items × (1 s, 4 s) on one point.
  const RunCosts costs = one_point(2, {1, 4, 1, 4, 1, 4, 1, 4});
  CHECK(schedule_lower_bound(costs, 2) == 10.0);
  CHECK(schedule_lower_bound(costs, 16) == 4.0);
  // One worker: everything in a row.
  CHECK(simulate_work_queue(costs, 1).wall_seconds == 20.0);
  CHECK(simulate_work_queue(costs, 1).work_fraction == 1.0);
  // The old 8-item block holds all 4 items: one worker of two does everything.
  CHECK(simulate_item_blocks(costs, 2).wall_seconds == 20.0);
  CHECK(simulate_item_blocks(costs, 2).work_fraction == 0.5);
  // Longest first on 2 workers: t=0 units 0 (1 s) and 1 (4 s); at 1 part 0 is timed, part 1 not
  // yet: unit 3 (4 s, to 5); at 4 part 1 is timed: unit 5 (to 8); at 5 unit 7 (to 9); then the
  // 1 s units 2, 4, 6 at 8, 9, 9: done at 10 = total / 2.
  const SchedulePrediction two = simulate_work_queue(costs, 2);
  CHECK(two.wall_seconds == 10.0);
  CHECK(two.work_fraction == 1.0);
  // 8 workers: every unit at once; the 4 s units bound the wall.
  CHECK(simulate_work_queue(costs, 8).wall_seconds == 4.0);
}

}  // namespace DABENCH_TEST_FILE
