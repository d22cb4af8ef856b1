// `dabench schedule RUN_DIR`: the wall time a run's work would take on W workers, from the run's
// own trials.csv; one error line for a folder that is not a run or bad --workers.
#include <catch2/catch.hpp>

#include <sstream>
#include <string>
#include <vector>

#include "tests/support/cli_runner.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench::test::cli;

namespace {

std::vector<std::vector<std::string>> csv_rows(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    std::vector<std::string> fields;
    std::istringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) fields.push_back(cell);
    rows.push_back(fields);
  }
  return rows;
}

}  // namespace

TEST_CASE("cli schedule: predictions over a finished multi-scan run", "[cli][schedule]") {
  TempDir dir;
  dir.write("multi.ini",
            "scenario = bearings\ntrials = 6\nseed = 3\nalgorithm = jpda-bp\nalgorithm = msbp\n"
            "[scenario]\nparticles = 100\nmean_targets = 2\n");
  REQUIRE(run_dabench(dir, {"run", "multi.ini", "--out", "run", "--threads", "2"}).status == 0);
  const CliResult csv = run_dabench(dir, {"schedule", "run", "--workers", "1,2,100", "--format", "csv"});
  INFO(csv.err);
  REQUIRE(csv.status == 0);
  const auto rows = csv_rows(csv.out);
  REQUIRE(rows.size() == 4);
  CHECK(rows[0][0] == "workers");
  CHECK(rows[1][1] == "12");  // 6 trials × 2 algorithms
  for (std::size_t r = 1; r < rows.size(); ++r) {
    const double bound = std::stod(rows[r][4]), wall = std::stod(rows[r][5]), old_wall = std::stod(rows[r][7]);
    CHECK(wall >= bound * (1 - 1e-12));
    CHECK(old_wall >= bound * (1 - 1e-12));
  }
  CHECK(std::stod(rows[1][5]) == Approx(std::stod(rows[1][2])));  // 1 worker: the total
  CHECK(std::stod(rows[3][5]) == Approx(std::stod(rows[3][3])));  // 100 workers: the longest unit
  CHECK(std::stod(rows[3][7]) == Approx(std::stod(rows[3][2])));  // 6 items: one 8-item block
  const CliResult table = run_dabench(dir, {"schedule", "run"});
  REQUIRE(table.status == 0);
  CHECK(contains(table.out, "12 units (6 items x 2)"));
  CHECK(csv_rows(table.out).size() == 7);  // title, header, 5 worker counts
}

TEST_CASE("cli run --costs-from: a rerun ordered by a previous run's times writes the same files", "[cli][schedule]") {
  TempDir dir;
  dir.write("multi.ini",
            "scenario = bearings\ntrials = 5\nseed = 9\nalgorithm = jpda-bp\nalgorithm = msbp\n"
            "[scenario]\nparticles = 100\nmean_targets = 2\n[sweep]\nscans_per_sensor = 1, 2\n");
  REQUIRE(run_dabench(dir, {"run", "multi.ini", "--out", "first", "--threads", "2"}).status == 0);
  const CliResult again = run_dabench(dir, {"run", "multi.ini", "--out", "again", "--threads", "3", "--costs-from", "first"});
  INFO(again.err);
  REQUIRE(again.status == 0);
  CHECK(dir.read("again/targets.csv") == dir.read("first/targets.csv"));
  // A shard reads its own units' times out of the whole run's.
  REQUIRE(run_dabench(dir, {"run", "multi.ini", "--shard", "2/2", "--out", "shard", "--costs-from", "first"}).status == 0);

  dir.write("other.ini", "scenario = bearings\ntrials = 4\nseed = 9\nalgorithm = jpda-bp\n[scenario]\nparticles = 100\n");
  const CliResult other = run_dabench(dir, {"run", "other.ini", "--out", "x", "--costs-from", "first"});
  CHECK(other.status == 2);
  CHECK(contains(other.err, "--costs-from first: first/trials.csv holds 10 items of 2 algorithms, this run 4 of 1"));
  CHECK_FALSE(dir.exists("x"));
  dir.write("single.ini", "scenario = grid\ntrials = 4\nreference = exact\nalgorithm = bp\n");
  const CliResult single = run_dabench(dir, {"run", "single.ini", "--out", "y", "--costs-from", "first"});
  CHECK(single.status == 2);
  CHECK(contains(single.err, "single-scan items run in order"));
}

TEST_CASE("cli schedule: bad input is one error line", "[cli][schedule]") {
  TempDir dir;
  for (const auto& [args, mention] : std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"schedule", "nowhere"}, "no trials.csv, runs.csv or summary.csv"},
           {{"schedule", "."}, "no trials.csv, runs.csv or summary.csv"},
           {{"schedule", ".", "--workers", "0"}, "--workers '0' must be a list of counts"},
           {{"schedule", ".", "--workers", "4,,8"}, "schedule: --workers '4,,8' has an empty item"},
           {{"schedule", ".", "--format", "xml"}, "--format must be table or csv"},
           {{"schedule"}, "schedule: the option '--run' is required"}}) {
    const CliResult result = run_dabench(dir, args);
    INFO(result.err);
    CHECK(result.status == 2);
    CHECK(result.out.empty());
    CHECK(contains(result.err, mention));
  }
}

}  // namespace DABENCH_TEST_FILE
