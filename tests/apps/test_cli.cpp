// The command-line contract of DESIGN.md ("Command line") that every command shares, on the
// real executable: an unknown or missing command fails with one stderr line and no stdout;
// `list` names the algorithms, the scenarios and the experiment files; `--version` and every
// command's `--help`/`-h` print on stdout and exit 0. The commands' own contracts:
// test_cli_solve.cpp, test_cli_run.cpp, test_cli_schedule.cpp.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include <fmt/format.h>

#include "harness/core/build_info.hpp"
#include "tests/support/cli_contract.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench::test::cli;

// ---------------------------------------------------------------------------------------------
// commands

TEST_CASE("cli: unknown or missing command fails without stdout", "[cli]") {
  TempDir dir;
  const auto before = snapshot(dir.work());
  SECTION("unknown command") {
    const CliResult result = run_dabench(dir, {"frobnicate"});
    CHECK(result.status != 0);
    CHECK(result.out.empty());
    REQUIRE(!result.err.empty());
    CHECK(contains(split_lines(result.err)[0], "frobnicate"));
  }
  SECTION("no command") {
    const CliResult result = run_dabench(dir, {});
    CHECK(result.status != 0);
    CHECK(result.out.empty());
    REQUIRE(!result.err.empty());
    CHECK(contains(split_lines(result.err)[0], "command"));
  }
  CHECK(snapshot(dir.work()) == before);
}

// DESIGN.md: "on bad input a one-line message". The unknown/missing-command paths also print
// the usage text (5 lines) on stderr.
TEST_CASE("cli: unknown or missing command prints exactly one stderr line", "[cli]") {
  TempDir dir;
  CHECK(count_newlines(run_dabench(dir, {"frobnicate"}).err) == 1);
  CHECK(count_newlines(run_dabench(dir, {}).err) == 1);
}

TEST_CASE("cli list: names algorithms with parameters and scenarios and experiments", "[cli]") {
  TempDir dir;
  const CliResult result = run_ok(dir, {"list"});
  CHECK(result.err.empty());
  for (const char* word : {"bp", "exact", "grid", "check_every", "delta", "max_events", "spacing", "quickstart.ini"}) {
    INFO("list should mention " << word);
    CHECK(contains(result.out, word));
  }
  CHECK(snapshot(dir.work()).empty());
  // A section's summaries start in one column, however long its longest name.
  const auto summary_column = [&](const std::string& name) {
    const std::size_t line = result.out.find("\n  " + name + " ");
    REQUIRE(line != std::string::npos);
    return result.out.find_first_not_of(' ', line + 3 + name.size()) - line;
  };
  CHECK(summary_column("bp") == summary_column("modified-cheap-jpda"));
  // A study's experiment files are listed by their path under experiments/, aligned the same way.
  CHECK(summary_column("quickstart.ini") == summary_column("multiscan/reading-corner-grouped.ini"));
  CHECK(summary_column("bp_paper/exp1.ini") == summary_column("quickstart.ini"));
}

TEST_CASE("cli help: prints the usage on stdout", "[cli]") {
  TempDir dir;
  const CliResult result = run_ok(dir, {"--help"});
  CHECK(contains(result.out, "dabench solve"));
  CHECK(contains(result.out, "dabench run"));
  CHECK(contains(result.out, "dabench merge"));
  CHECK(contains(result.out, "dabench --version"));
  CHECK(contains(result.out, "dabench COMMAND --help"));
  CHECK(result.err.empty());
}

TEST_CASE("cli help: --help and -h on every command print its usage and options, exit 0", "[cli]") {
  // Each command's own options appear; required options and the experiment are not needed, and
  // --help wins over the other words of a valid command line. Nothing is written.
  TempDir dir;
  dir.write("e.ini", kGoodExperiment);
  const auto before = snapshot(dir.work());
  const std::vector<std::pair<std::vector<std::string>, std::vector<std::string>>> cases = {
      {{"list", "--help"}, {"usage: dabench list\n", "--help"}},
      {{"list", "-h"}, {"usage: dabench list\n"}},
      {{"solve", "--help"}, {"usage: dabench solve --algorithm SPEC", "--algorithm", "--weights", "--format", "--pd"}},
      {{"solve", "-h", "--algorithm", "bp"}, {"usage: dabench solve"}},
      {{"run", "--help"}, {"usage: dabench run EXPERIMENT.ini", "--trials", "--threads", "--resume", "--force"}},
      {{"run", "e.ini", "--trials", "2", "-h"}, {"usage: dabench run"}},
      {{"merge", "--help"}, {"usage: dabench merge OUT SHARD_DIR", "--force"}},
  };
  for (const auto& [args, mentions] : cases) {
    std::string shown;
    for (const auto& arg : args) shown += " " + arg;
    INFO("dabench" << shown);
    const CliResult result = run_ok(dir, args);
    CHECK(result.err.empty());
    CHECK(result.out.rfind("usage: dabench " + args[0], 0) == 0);
    for (const auto& part : mentions) {
      INFO("the usage should mention: " << part);
      CHECK(contains(result.out, part));
    }
  }
  CHECK_FALSE(contains(run_ok(dir, {"solve", "--help"}).out, "--resume"));  // its own options only
  CHECK(snapshot(dir.work()) == before);
}

TEST_CASE("cli --version: program name, project version and the build's git commit", "[cli]") {
  TempDir dir;
  const CliResult result = run_ok(dir, {"--version"});
  CHECK(result.err.empty());
  const dabench::BuildInfo& build = dabench::build_info();
  CHECK(build.version == DABENCH_PROJECT_VERSION);  // CMake's project(VERSION) reaches the program
  const std::string expected =
      build.git_commit == "unknown"
          ? fmt::format("dabench {}\n", DABENCH_PROJECT_VERSION)
          : fmt::format("dabench {} (git {}{})\n", DABENCH_PROJECT_VERSION, build.git_commit,
                        build.source == dabench::Provenance::modified ? ", modified source" : "");
  CHECK(result.out == expected);
  CHECK(snapshot(dir.work()).empty());
}

TEST_CASE("cli: extra words after list, --help or --version are one-line errors", "[cli]") {
  TempDir dir;
  expect_error(dir, {"list", "extra"}, {"list"});
  expect_error(dir, {"--version", "extra"}, {"--version", "extra"});
  expect_error(dir, {"--help", "extra"}, {"extra"});
}

}  // namespace DABENCH_TEST_FILE
