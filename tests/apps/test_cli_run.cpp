// The command-line contract of `dabench run`, `run --shard` and `merge` (DESIGN.md, "Command
// line"), on the real executable: `run` rejects every bad experiment before creating its output
// folder, refuses a folder that holds a run unless --resume/--force (and then leaves it
// untouched), and refuses to resume a different run; merged shards equal the run; missing,
// duplicated, foreign, incomplete shards and bad K/N are one-line errors that leave no file.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "tests/support/cli_contract.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench::test::cli;

// ---------------------------------------------------------------------------------------------
// run: errors (each leaves the working folder untouched: no output folder, no file)

TEST_CASE("cli run: the good base experiment runs", "[cli][run]") {
  // The error cases below are this experiment with one thing broken.
  TempDir dir;
  dir.write("e.ini", kGoodExperiment);
  run_ok(dir, {"run", "e.ini", "--threads", "1"});
  CHECK(dir.exists("out/trials.csv"));
  CHECK(dir.exists("out/summary.csv"));
  CHECK(dir.exists("out/meta.json"));
}

TEST_CASE("cli run: bad experiment files are rejected before any output", "[cli][run]") {
  TempDir dir;
  SECTION("missing experiment file") {
    expect_error(dir, {"run", "nothere.ini"}, {"nothere.ini"});
  }
  SECTION("experiment path is a folder") {
    std::filesystem::create_directories(dir.work() / "folder.ini");
    expect_error(dir, {"run", "folder.ini"}, {"folder.ini"});
  }
  SECTION("experiment path is a device") {
    expect_error(dir, {"run", "/dev/full"}, {"/dev/full", "not a regular file"});
    expect_error(dir, {"run", "/dev/zero"}, {"/dev/zero", "not a regular file"});
  }
  SECTION("experiment file too large") {
    dir.write("huge.ini", std::string((1u << 20) + 1, '#'));
    expect_error(dir, {"run", "huge.ini"}, {"huge.ini", "at most 1048576 bytes"});
  }
  SECTION("malformed INI line") {
    dir.write("e.ini", experiment_with("this line has no equals sign\n"));
    expect_error(dir, {"run", "e.ini"}, {"e.ini", "this line has no equals sign"});
  }
  SECTION("unknown top-level key") {
    dir.write("e.ini", experiment_with("colour = blue\n"));
    expect_error(dir, {"run", "e.ini"}, {"e.ini", "colour"});
  }
  SECTION("unknown section") {
    dir.write("e.ini", experiment_with("", "[sweeps]\nspacing = 1\n"));
    expect_error(dir, {"run", "e.ini"}, {"e.ini", "sweeps"});
  }
  SECTION("unknown scenario") {
    std::string text = kGoodExperiment;
    text.replace(text.find("grid"), 4, "nosuchscenario");
    dir.write("e.ini", text);
    expect_error(dir, {"run", "e.ini"}, {"e.ini", "nosuchscenario"});
  }
  SECTION("missing scenario") {
    std::string text = kGoodExperiment;
    text.erase(text.find("scenario = grid\n"), 16);
    dir.write("e.ini", text);
    expect_error(dir, {"run", "e.ini"}, {"e.ini", "scenario"});
  }
  SECTION("unknown scenario parameter in [scenario]") {
    dir.write("e.ini", experiment_in("scenario", "width = 3\n"));
    expect_error(dir, {"run", "e.ini"}, {"e.ini", "width"});
  }
  SECTION("unknown scenario parameter in [sweep]") {
    dir.write("e.ini", experiment_in("sweep", "height = 1,2\n"));
    expect_error(dir, {"run", "e.ini"}, {"e.ini", "height"});
  }
  SECTION("a section opened twice") {
    dir.write("e.ini", experiment_with("", "[scenario]\npd = 0.5\n"));
    expect_error(dir, {"run", "e.ini"}, {"e.ini:12", "[scenario]", "first at line 7"});
  }
  SECTION("pd out of range") {
    dir.write("e.ini", experiment_in("scenario", "pd = 1.2\n"));
    expect_error(dir, {"run", "e.ini"}, {"e.ini", "pd", "1.2"});
  }
  SECTION("negative spacing in a sweep") {
    dir.write("e.ini", experiment_with("", "[sweep.more]\nspacing = 2, -1\n"));
    expect_error(dir, {"run", "e.ini"}, {"e.ini", "spacing", "-1"});
  }
  SECTION("rows = 0") {
    std::string text = kGoodExperiment;
    text.replace(text.find("rows = 1"), 8, "rows = 0");
    dir.write("e.ini", text);
    expect_error(dir, {"run", "e.ini"}, {"e.ini", "rows"});
  }
  SECTION("non-numeric scenario value") {
    dir.write("e.ini", experiment_in("scenario", "lambda_fa = lots\n"));
    expect_error(dir, {"run", "e.ini"}, {"e.ini", "lambda_fa", "lots"});
  }
  SECTION("trials = 0") {
    std::string text = kGoodExperiment;
    text.replace(text.find("trials = 3"), 10, "trials = 0");
    dir.write("e.ini", text);
    expect_error(dir, {"run", "e.ini"}, {"e.ini", "trials"});
  }
  SECTION("unknown algorithm") {
    dir.write("e.ini", experiment_with("algorithm = nosuchalgo\n"));
    expect_error(dir, {"run", "e.ini"}, {"e.ini", "nosuchalgo"});
  }
  SECTION("unknown algorithm parameter") {
    dir.write("e.ini", experiment_with("algorithm = bp:tolerance=1\n"));
    expect_error(dir, {"run", "e.ini"}, {"e.ini", "tolerance"});
  }
  SECTION("unknown reference") {
    std::string text = kGoodExperiment;
    text.replace(text.find("reference = exact"), 17, "reference = nosuchref");
    dir.write("e.ini", text);
    expect_error(dir, {"run", "e.ini"}, {"e.ini", "nosuchref"});
  }
  SECTION("range with zero step") {
    dir.write("e.ini", experiment_with("", "[sweep.b]\nspacing = 0:0:10\n"));
    expect_error(dir, {"run", "e.ini"}, {"e.ini", "0:0:10"});
  }
  SECTION("range with two parts") {
    dir.write("e.ini", experiment_with("", "[sweep.b]\nspacing = 0:1\n"));
    expect_error(dir, {"run", "e.ini"}, {"e.ini", "0:1"});
  }
  SECTION("tie to an unswept key") {
    dir.write("e.ini", experiment_with("", "[sweep.b]\nspacing = 1,2\ncols = @rows\n"));
    expect_error(dir, {"run", "e.ini"}, {"e.ini", "@rows"});
  }
}

TEST_CASE("cli run: bad options are rejected before any output", "[cli][run]") {
  TempDir dir;
  dir.write("e.ini", kGoodExperiment);
  SECTION("--trials 0") {
    expect_error(dir, {"run", "e.ini", "--trials", "0"}, {"trials"});
  }
  SECTION("--threads 0") {
    expect_error(dir, {"run", "e.ini", "--threads", "0"}, {"threads"});
  }
  SECTION("--seed -1") {
    expect_error(dir, {"run", "e.ini", "--seed", "-1"}, {"seed"});
  }
  SECTION("--trials abc") {
    expect_error(dir, {"run", "e.ini", "--trials", "abc"}, {"trials"});
  }
  SECTION("--resume and --force together") {
    expect_error(dir, {"run", "e.ini", "--resume", "--force"}, {"--resume", "--force"});
  }
  SECTION("no experiment") {
    expect_error(dir, {"run"}, {"experiment"});
  }
  SECTION("two experiments") {
    expect_error(dir, {"run", "e.ini", "e.ini"}, {});
  }
}

TEST_CASE("cli run: a folder holding a run is refused and left byte-identical", "[cli][run]") {
  TempDir dir;
  dir.write("e.ini", kGoodExperiment);
  run_ok(dir, {"run", "e.ini", "--threads", "1"});
  REQUIRE(dir.exists("out/trials.csv"));

  SECTION("without --resume or --force") {
    expect_error(dir, {"run", "e.ini"}, {"out", "--resume", "--force"});
  }
  SECTION("with --out naming the same folder") {
    expect_error(dir, {"run", "e.ini", "--out", "out"}, {"out"});
  }
  SECTION("only meta.json left") {
    std::filesystem::remove(dir.work() / "out" / "trials.csv");
    expect_error(dir, {"run", "e.ini"}, {"out"});
  }
  SECTION("--resume with a different seed") {
    expect_error(dir, {"run", "e.ini", "--resume", "--seed", "6"}, {"out", "resume"});
  }
  SECTION("--resume with different trials") {
    expect_error(dir, {"run", "e.ini", "--resume", "--trials", "4"}, {"out", "resume"});
  }
  SECTION("--resume with a different experiment") {
    std::string text = kGoodExperiment;
    text.replace(text.find("spacing = 1, 2"), 14, "spacing = 1, 3");
    dir.write("e2.ini", text);
    expect_error(dir, {"run", "e2.ini", "--resume"}, {"out", "resume"});
  }
  SECTION("--resume with a different algorithm list") {
    dir.write("e2.ini", experiment_with("algorithm = bp:delta=1e-6\n"));
    expect_error(dir, {"run", "e2.ini", "--resume"}, {"out", "resume"});
  }
}

// ---------------------------------------------------------------------------------------------
// run --shard and merge

namespace {

// Columns of trials.csv but time_us.
CsvTable without_time(const CsvTable& table) {
  const std::size_t time = table.column("time_us");
  CsvTable kept = table;
  kept.header.erase(kept.header.begin() + static_cast<std::ptrdiff_t>(time));
  for (auto& row : kept.rows) row.erase(row.begin() + static_cast<std::ptrdiff_t>(time));
  return kept;
}

// kGoodExperiment (6 items: one block, so shards 2 and 3 of 3 are empty) as shards s1..s3 of 3.
void run_three_shards(const TempDir& dir) {
  dir.write("e.ini", kGoodExperiment);
  for (const char* k : {"1", "2", "3"}) run_ok(dir, {"run", "e.ini", "--threads", "1", "--shard", std::string(k) + "/3", "--out", std::string("s") + k});
}

}  // namespace

TEST_CASE("cli merge: shards merged from the command line equal the run", "[cli][shard]") {
  TempDir dir;
  run_three_shards(dir);
  run_ok(dir, {"run", "e.ini", "--threads", "1", "--out", "full"});
  const CliResult merged = run_ok(dir, {"merge", "m", "s3", "s1", "s2"});
  CHECK(contains(merged.err, "merged 3 shards, 6 trials"));
  CHECK(without_time(parse_csv(dir.read("m/trials.csv"))).rows == without_time(parse_csv(dir.read("full/trials.csv"))).rows);
  CHECK(dir.exists("m/summary.csv"));
  CHECK(contains(dir.read("m/meta.json"), "\"processes\": 3"));
  // Without --out a shard goes beside the experiment's output folder.
  run_ok(dir, {"run", "e.ini", "--threads", "1", "--shard", "2/2"});
  CHECK(dir.exists("out-shard-2-of-2/trials.csv"));
  CHECK(contains(dir.read("out-shard-2-of-2/meta.json"), "\"shard\": \"2/2\""));
  // --force replaces a merged run.
  expect_error(dir, {"merge", "m", "s1", "s2", "s3"}, {"m", "--force"});
  run_ok(dir, {"merge", "m", "s1", "s2", "s3", "--force"});
}

TEST_CASE("cli merge: missing, duplicated, foreign or incomplete shards are one-line errors", "[cli][shard]") {
  TempDir dir;
  run_three_shards(dir);
  SECTION("missing") { expect_error(dir, {"merge", "m", "s1", "s3"}, {"missing", "2/3"}); }
  SECTION("duplicated") { expect_error(dir, {"merge", "m", "s1", "s2", "s3", "s2"}, {"2/3", "twice"}); }
  SECTION("another seed") {
    run_ok(dir, {"run", "e.ini", "--threads", "1", "--shard", "2/3", "--seed", "6", "--out", "f2"});
    expect_error(dir, {"merge", "m", "s1", "f2", "s3"}, {"f2", "another run"});
  }
  SECTION("another experiment") {
    std::string text = kGoodExperiment;
    text.replace(text.find("spacing = 1, 2"), 14, "spacing = 1, 3");
    dir.write("e2.ini", text);
    run_ok(dir, {"run", "e2.ini", "--threads", "1", "--shard", "3/3", "--out", "f3"});
    expect_error(dir, {"merge", "m", "s1", "s2", "f3"}, {"f3", "another run"});
  }
  SECTION("another split") {
    run_ok(dir, {"run", "e.ini", "--threads", "1", "--shard", "2/2", "--out", "h2"});
    expect_error(dir, {"merge", "m", "s1", "h2", "s3"}, {"h2", "2/2"});
  }
  SECTION("not a shard") {
    run_ok(dir, {"run", "e.ini", "--threads", "1", "--out", "full"});
    expect_error(dir, {"merge", "m", "s1", "full", "s3"}, {"full", "not a shard"});
  }
  SECTION("incomplete") {
    std::string meta = dir.read("s2/meta.json");
    meta.replace(meta.find("\"status\": \"complete\""), 20, "\"status\": \"interrupted\"");
    dir.write("s2/meta.json", meta);
    expect_error(dir, {"merge", "m", "s1", "s2", "s3"}, {"s2", "interrupted", "--resume"});
  }
  SECTION("rows of another shard") {
    dir.write("s3/trials.csv", dir.read("s1/trials.csv"));
    expect_error(dir, {"merge", "m", "s1", "s2", "s3"}, {"s3/trials.csv:2: not the row the shard wrote"});
    dir.write("s3/checksums.csv", dir.read("s1/checksums.csv"));  // rows checksummed, but not shard 3's
    expect_error(dir, {"merge", "m", "s1", "s2", "s3"}, {"s3/trials.csv", "shard 3/3"});
  }
  SECTION("a split into a million, one shard given: the first eight missing named, the rest counted") {
    std::string meta = dir.read("s1/meta.json");
    meta.replace(meta.find("\"shard\": \"1/3\""), 14, "\"shard\": \"1/1000000\"");
    dir.write("s1/meta.json", meta);
    expect_error(dir, {"merge", "m", "s1"}, {"shards missing: 2/1000000, 3/1000000", "9/1000000 and 999991 more",
                                            "(given 1 of 1000000)"});
  }
  SECTION("not a folder") { expect_error(dir, {"merge", "m", "s1", "nothere", "s3"}, {"nothere", "meta.json"}); }
  SECTION("no shards") { expect_error(dir, {"merge", "m"}, {"merge", "shard folders"}); }
  SECTION("into a shard") { expect_error(dir, {"merge", "s1", "s1", "s2", "s3"}, {"s1", "shard 1/3"}); }
}

TEST_CASE("cli run --shard: bad values and a resume of another shard are one-line errors", "[cli][shard]") {
  TempDir dir;
  dir.write("e.ini", kGoodExperiment);
  for (const char* bad : {"0/3", "4/3", "3", "a/b", "1/0", "-1/2"}) {
    INFO("--shard " << bad);
    expect_error(dir, {"run", "e.ini", "--shard", bad}, {"--shard", bad});
  }
  run_ok(dir, {"run", "e.ini", "--threads", "1", "--shard", "1/2", "--out", "s"});
  expect_error(dir, {"run", "e.ini", "--shard", "2/2", "--out", "s", "--resume"}, {"s", "shard 1/2", "shard 2/2"});
  expect_error(dir, {"run", "e.ini", "--out", "s", "--resume"}, {"s", "shard 1/2", "no shard"});
}

}  // namespace DABENCH_TEST_FILE
