// A fresh run (--force) or merge (merge --force) into a folder that held an earlier run leaves
// only its own result files there: no targets.csv, steps.csv, ... of an experiment of another
// kind, while files dabench never writes (a study's plots and digests) stay. And every file a
// run of any kind writes is one run_file_names() knows.
#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "harness/run/run_folder.hpp"
#include "harness/run/run_plan.hpp"
#include "harness/run/runner.hpp"
#include "harness/run/shard_merge.hpp"
#include "tests/support/cli_runner.hpp"
#include "tests/support/run_files.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench;
using namespace dabench::test::cli;
namespace fs = std::filesystem;

namespace {

const char* const kTbd =
    "scenario = tbd\ntrials = 2\nseed = 3\nbeliefs = true\nalgorithm = tbd-bp:iterations=1,particles=100\n"
    "[scenario]\nlayout = toy\n";
const char* const kBearings =
    "scenario = bearings\ntrials = 2\nseed = 3\nalgorithm = jpda-bp\n[scenario]\nparticles = 50\nmean_targets = 2\n";
const char* const kGrid = "scenario = grid\ntrials = 2\nseed = 3\nalgorithm = bp\n[scenario]\nrows = 1\ncols = 3\n";
const char* const kOthr =
    "scenario = othr\ntrials = 2\nseed = 5\niterations = true\nalgorithm = test-iterating:iterations=1,from_draw=true\n"
    "[scenario]\nscans = 10\n";

std::set<std::string> files_in(const TempDir& dir, const std::string& folder) {
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir.work() / folder)) names.insert(entry.path().filename().string());
  return names;
}

RunPlan plan_of(const TempDir& dir, const std::string& ini) {
  RunOptions options;
  options.experiment_path = (dir.work() / ini).string();
  options.output = (dir.work() / "unused").string();
  return make_run_plan(options);
}

}  // namespace

TEST_CASE("force: a fresh run leaves none of an earlier run's result files, and keeps other files", "[run][force]") {
  TempDir dir;
  dir.write("tbd.ini", kTbd);
  dir.write("bearings.ini", kBearings);
  dir.write("grid.ini", kGrid);
  run_in(dir, "tbd.ini", "F", 1);
  CHECK(files_in(dir, "F") == std::set<std::string>{"trials.csv", "summary.csv", "meta.json", "checksums.csv", "steps.csv",
                                                     "estimates.csv", "frames.csv", "beliefs.csv"});
  dir.write("F/notes.txt", "a study's own file\n");
  run_in(dir, "bearings.ini", "F", 1, false, true);
  CHECK(files_in(dir, "F") ==
        std::set<std::string>{"trials.csv", "summary.csv", "meta.json", "checksums.csv", "targets.csv", "notes.txt"});
  run_in(dir, "grid.ini", "F", 2, false, true);
  CHECK(files_in(dir, "F") == std::set<std::string>{"trials.csv", "summary.csv", "meta.json", "checksums.csv", "notes.txt"});
  CHECK(dir.read("F/notes.txt") == "a study's own file\n");
}

TEST_CASE("force: merge --force replaces an earlier run of another kind", "[run][force][shard]") {
  TempDir dir;
  dir.write("tbd.ini", kTbd);
  dir.write("bearings.ini", kBearings);
  run_in(dir, "tbd.ini", "M", 1);
  for (int k = 1; k <= 2; ++k) {
    RunOptions options;
    options.experiment_path = (dir.work() / "bearings.ini").string();
    options.output = (dir.work() / fmt::format("s{}", k)).string();
    options.threads = 1;
    options.shard = Shard{k, 2};
    run_experiment(options);
  }
  MergeOptions merge;
  merge.output = (dir.work() / "M").string();
  merge.shards = {(dir.work() / "s1").string(), (dir.work() / "s2").string()};
  CHECK_THROWS_AS(merge_shards(merge), InputError);  // without --force the earlier run stays
  CHECK(dir.exists("M/steps.csv"));
  merge.force = true;
  merge_shards(merge);
  CHECK(files_in(dir, "M") == std::set<std::string>{"trials.csv", "summary.csv", "meta.json", "checksums.csv", "targets.csv"});
}

TEST_CASE("force: every kind's result files are known to run_file_names", "[run][force]") {
  TempDir dir;
  dir.write("tbd.ini", kTbd);
  dir.write("bearings.ini", kBearings);
  dir.write("grid.ini", kGrid);
  dir.write("othr.ini", kOthr);
  const std::vector<std::string>& known = run_file_names();
  std::set<std::string> seen;
  for (const char* ini : {"tbd.ini", "bearings.ini", "grid.ini", "othr.ini"}) {
    INFO(ini);
    for (const std::string& name : plan_of(dir, ini).output_files()) {
      CHECK(std::find(known.begin(), known.end(), name) != known.end());
      seen.insert(name);
    }
  }
  // And every known name is written by one of these plans (no stale entry in the list).
  CHECK(seen == std::set<std::string>(known.begin(), known.end()));
}

}  // namespace DABENCH_TEST_FILE
