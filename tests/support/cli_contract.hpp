#pragma once
// The command-line error contract of DESIGN.md ("Command line") as helpers of the CLI tests
// (tests/apps/test_cli*.cpp) and the run tests: an error exits != 0 with exactly one stderr line
// naming the problem, nothing on stdout and no file left behind; a success exits 0; and the small
// experiment the CLI's error cases break one thing of.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "tests/support/cli_runner.hpp"

namespace dabench::test::cli {

inline int count_newlines(const std::string& text) {
  int count = 0;
  for (const char c : text) count += c == '\n';
  return count;
}

// Runs dabench with `args` in dir.work(); requires the error contract and that every string of
// `mentions` occurs in the message. Returns the stderr line.
inline std::string expect_error(const TempDir& dir, const std::vector<std::string>& args,
                                const std::vector<std::string>& mentions) {
  const auto before = snapshot(dir.work());
  const CliResult result = run_dabench(dir, args);
  std::string shown;
  for (const auto& arg : args) shown += " " + arg;
  INFO("dabench" << shown);
  INFO("stderr: " << result.err);
  CHECK_FALSE(result.signaled);
  CHECK(result.status != 0);
  CHECK(result.out.empty());
  CHECK(count_newlines(result.err) == 1);
  CHECK((!result.err.empty() && result.err.back() == '\n'));
  for (const auto& part : mentions) {
    INFO("the message should mention: " << part);
    CHECK(contains(result.err, part));
  }
  CHECK(snapshot(dir.work()) == before);
  return result.err;
}

// Runs dabench with `args` in dir.work() and requires status 0 (the command line and stderr shown
// if not).
inline CliResult run_ok(const TempDir& dir, const std::vector<std::string>& args) {
  const CliResult result = run_dabench(dir, args);
  std::string shown;
  for (const auto& arg : args) shown += " " + arg;
  INFO("dabench" << shown);
  INFO("stderr: " << result.err);
  REQUIRE(result.status == 0);
  return result;
}

inline constexpr const char* kGoodExperiment =
    "scenario = grid\n"
    "trials = 3\n"
    "seed = 5\n"
    "output = out\n"
    "reference = exact\n"
    "algorithm = bp\n"
    "[scenario]\n"
    "rows = 1\n"
    "cols = 2\n"
    "[sweep]\n"
    "spacing = 1, 2\n";

// kGoodExperiment with `line` inserted after the top-level keys (before [scenario]) or appended.
inline std::string experiment_with(const std::string& top, const std::string& tail = "") {
  std::string text = kGoodExperiment;
  text.insert(text.find("[scenario]"), top);
  return text + tail;
}

// kGoodExperiment with `lines` added at the start of its [scenario] or [sweep] section (a section
// opened twice is an error of its own).
inline std::string experiment_in(const std::string& section, const std::string& lines) {
  std::string text = kGoodExperiment;
  const std::string header = "[" + section + "]\n";
  text.insert(text.find(header) + header.size(), lines);
  return text;
}

}  // namespace dabench::test::cli
