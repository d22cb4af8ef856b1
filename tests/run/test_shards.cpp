// Shards (`dabench run --shard K/N`, RunPlan::shard_items/global_item) and `dabench merge`
// (harness/run/shard_merge.hpp):
//  - the partition: blocks of kItemsPerBlock items dealt round robin; over the N shards every
//    item appears exactly once, each shard's items ascend and lie in its own blocks, for item
//    counts around block edges and more shards than blocks;
//  - for a small experiment of each problem kind, shards 1..3 of 3 merged equal the unsharded
//    run: every CSV byte-identical (those with timing columns: identical once those are
//    dropped), meta.json identical apart from the process fields;
//  - a shard cut mid-item and finished with --resume merges to the same files.
// The CLI's refusals (missing, duplicated, incomplete, foreign shards) are in tests/apps.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

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

RunOutcome run_shard(const TempDir& dir, const std::string& ini, const std::string& out, std::optional<Shard> shard,
                     int threads = 1, bool resume = false) {
  RunOptions options;
  options.experiment_path = (dir.work() / ini).string();
  options.output = (dir.work() / out).string();
  options.threads = threads;
  options.shard = shard;
  options.resume = resume;
  return run_experiment(options);
}

void merge_into(const TempDir& dir, const std::string& out, const std::vector<std::string>& shards) {
  MergeOptions options;
  options.output = (dir.work() / out).string();
  for (const std::string& shard : shards) options.shards.push_back((dir.work() / shard).string());
  merge_shards(options);
}

// Columns that hold timings, as scripts/same_results.py names them.
bool is_timing(const std::string& column) {
  static const std::regex timing("^(time_us|step_time_us|tet_s|[a-z_]*_seconds)(_(count|mean|se|median|p5|p95))?$");
  return std::regex_match(column, timing);
}

CsvTable without_timing(const CsvTable& table) {
  CsvTable kept;
  std::vector<std::size_t> columns;
  for (std::size_t c = 0; c < table.header.size(); ++c) {
    if (!is_timing(table.header[c])) columns.push_back(c);
  }
  for (const std::size_t c : columns) kept.header.push_back(table.header[c]);
  for (const auto& row : table.rows) {
    std::vector<std::string> fields;
    for (const std::size_t c : columns) fields.push_back(c < row.size() ? row[c] : "<missing>");
    kept.rows.push_back(std::move(fields));
  }
  return kept;
}

// meta.json without the fields that say how (not what) it ran.
std::string without_process_fields(const std::string& meta) {
  static const std::set<std::string> process = {"command_line", "threads", "processes", "host", "resumed",
                                                "start_time",   "end_time", "wall_seconds", "work_fraction"};
  std::istringstream lines(meta);
  std::string line, kept;
  while (std::getline(lines, line)) {
    const auto open = line.find('"'), close = line.find("\": ");
    if (open != std::string::npos && close != std::string::npos && process.count(line.substr(open + 1, close - open - 1))) continue;
    kept += line + "\n";
  }
  return kept;
}

// Every file of `expected` is in `actual` with the same contents (timings and process fields aside).
void check_same_run(const TempDir& dir, const std::string& expected, const std::string& actual) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir.work() / expected)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  REQUIRE(std::find(names.begin(), names.end(), "trials.csv") != names.end());
  for (const std::string& name : names) {
    INFO("file " << name);
    REQUIRE(dir.exists(actual + "/" + name));
    const std::string a = dir.read(expected + "/" + name), b = dir.read(actual + "/" + name);
    if (name == "checksums.csv") continue;  // of whole rows, timings included: the merge verifies them
    if (name == "meta.json") {
      CHECK(without_process_fields(a) == without_process_fields(b));
      CHECK(b.find("\"shard\"") == std::string::npos);
      continue;
    }
    const CsvTable table = parse_csv(a);
    const bool timed = std::any_of(table.header.begin(), table.header.end(), is_timing);
    if (timed) {
      check_same(without_timing(table), without_timing(parse_csv(b)));
    } else {
      CHECK(a == b);  // byte for byte
    }
  }
}

// Runs `ini` unsharded (2 threads) and as shards 1..3 of 3 (1 thread), merges, compares.
void check_shards_merge_to_run(const std::string& ini_text) {
  TempDir dir;
  dir.write("e.ini", ini_text);
  const RunOutcome full = run_shard(dir, "e.ini", "full", std::nullopt, 2);
  long long shard_items = 0;
  for (int k = 1; k <= 3; ++k) {
    const RunOutcome shard = run_shard(dir, "e.ini", fmt::format("s{}", k), Shard{k, 3});
    CHECK_FALSE(shard.interrupted);
    shard_items += shard.items_total;
  }
  CHECK(shard_items == full.items_total);
  merge_into(dir, "merged", {"s2", "s3", "s1"});  // any order
  check_same_run(dir, "full", "merged");
}

}  // namespace

TEST_CASE("shards: every item in exactly one shard, in its own blocks, ascending", "[run][shard]") {
  for (const long long items : {1LL, 7LL, 8LL, 9LL, 23LL, 24LL, 25LL, 100LL}) {
    for (const int count : {1, 2, 3, 5, 16}) {
      INFO(items << " items, " << count << " shards");
      RunPlan plan;
      plan.point_params.resize(1);
      plan.trials = items;
      std::vector<long long> seen;
      for (int index = 1; index <= count; ++index) {
        plan.shard = Shard{index, count};
        long long previous = -1;
        for (long long local = 0; local < plan.shard_items(); ++local) {
          const long long item = plan.global_item(local);
          CHECK(item > previous);
          CHECK((item / kItemsPerBlock) % count == index - 1);
          previous = item;
          seen.push_back(item);
        }
      }
      std::sort(seen.begin(), seen.end());
      std::vector<long long> all(static_cast<std::size_t>(items));
      for (long long k = 0; k < items; ++k) all[static_cast<std::size_t>(k)] = k;
      CHECK(seen == all);
    }
  }
  RunPlan plan;
  plan.point_params.resize(2);
  plan.trials = 25;  // 50 items: blocks 0..6, block 6 holds 2
  plan.shard = Shard{1, 3};
  CHECK(plan.shard_items() == 8 + 8 + 2);  // blocks 0, 3, 6
  CHECK(plan.global_item(8) == 24);
  CHECK(plan.global_item(17) == 49);
  plan.shard = Shard{3, 3};
  CHECK(plan.shard_items() == 16);  // blocks 2, 5
  CHECK(plan.shard_label() == "3/3");
}

TEST_CASE("shards: merged shards equal the unsharded run, single scan", "[run][shard]") {
  // 2 points × 25 trials = 50 items in 7 blocks: shard 1 has blocks 0, 3 and the short 6.
  check_shards_merge_to_run(
      "scenario = grid\ntrials = 25\nseed = 11\nreference = exact\nalgorithm = bp\nalgorithm = bp:delta=1e-3,check_every=1\n"
      "[scenario]\nrows = 1\ncols = 3\n[sweep]\nspacing = 1, 3\n");
}

TEST_CASE("shards: merged shards equal the unsharded run, multi scan", "[run][shard]") {
  check_shards_merge_to_run(
      "scenario = bearings\ntrials = 10\nseed = 3\nalgorithm = jpda-bp\n[scenario]\nparticles = 100\n"
      "mean_targets = 2\n[sweep]\nscans_per_sensor = 1, 2\n");
}

TEST_CASE("shards: merged shards equal the unsharded run, tracking", "[run][shard]") {
  check_shards_merge_to_run(
      "scenario = othr\ntrials = 6\nseed = 5\nalgorithm = test-first-measurement\n"
      "algorithm = test-fixed-track:g=1750,theta=0.48,first_scan=0,length=10\n[scenario]\nscans = 10\n"
      "[sweep]\npd = 0.75, 0.4\nclutter = 5, 20\n");
}

TEST_CASE("shards: merged shards equal the unsharded run, track-before-detect", "[run][shard]") {
  // 10 items in 2 blocks: shard 3 of 3 holds none and still merges.
  check_shards_merge_to_run(
      "scenario = tbd\ntrials = 10\nseed = 5\nalgorithm = tbd-bp:particles=100\n[scenario]\nlayout = persistent\n"
      "objects = 1\nsteps = 4\ncolumns = 10\nrows = 10\n");
}

TEST_CASE("shards: a shard cut mid-item and resumed merges to the same files", "[run][shard]") {
  // Multi-scan: targets.csv is a per-item file, trimmed on resume in the plan's item numbering.
  TempDir dir;
  dir.write("e.ini", "scenario = bearings\ntrials = 10\nseed = 3\nalgorithm = jpda-bp\n[scenario]\nparticles = 100\n"
                     "mean_targets = 2\n[sweep]\nscans_per_sensor = 1, 2\n");
  run_shard(dir, "e.ini", "full", std::nullopt);
  for (int k = 1; k <= 2; ++k) run_shard(dir, "e.ini", fmt::format("s{}", k), Shard{k, 2});
  // Shard 1 of 2 holds blocks 0 and 2 (items 0..7, 16..19); cut both files inside item 17.
  const std::string trials = dir.read("s1/trials.csv"), targets = dir.read("s1/targets.csv");
  const std::size_t cut_trials = offset_of_item(trials, 17, 10) + 5, cut_targets = offset_of_item(targets, 17, 10) + 5;
  REQUIRE(cut_trials < trials.size());
  REQUIRE(cut_targets < targets.size());
  write_run_files(dir, "s1", {{"trials.csv", trials.substr(0, cut_trials)}, {"targets.csv", targets.substr(0, cut_targets)}});
  const RunOutcome resumed = run_shard(dir, "e.ini", "s1", Shard{1, 2}, 1, /*resume=*/true);
  CHECK(resumed.items_total == 12);
  CHECK(dir.read("s1/targets.csv") == targets);
  merge_into(dir, "merged", {"s1", "s2"});
  check_same_run(dir, "full", "merged");
}

}  // namespace DABENCH_TEST_FILE
