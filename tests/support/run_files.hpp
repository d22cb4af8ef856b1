#pragma once
// Helpers of the run tests (test_run_multi_scan, test_run_tracking, test_run_tracking_iterations):
// run an experiment through the C++ API, check that a bad one is refused in one line, compare CSV
// tables, find the byte where a work item's rows start (for resume tests that cut files there).
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "harness/core/errors.hpp"
#include "harness/run/runner.hpp"
#include "tests/support/cli_runner.hpp"

namespace dabench::test::cli {

inline dabench::RunOutcome run_in(const TempDir& dir, const std::string& ini, const std::string& out, int threads,
                                  bool resume = false, bool force = false) {
  dabench::RunOptions options;
  options.experiment_path = (dir.work() / ini).string();
  options.output = (dir.work() / out).string();
  options.threads = threads;
  options.resume = resume;
  options.force = force;
  return dabench::run_experiment(options);
}

// Writes `text` as dir/bad.ini and checks that running it throws InputError with one line naming
// every part, and that it writes no output folder B.
inline void check_refused_experiment(TempDir& dir, const std::string& text, const std::vector<std::string>& parts) {
  dir.write("bad.ini", text);
  try {
    run_in(dir, "bad.ini", "B", 1);
    FAIL("accepted: " << text);
  } catch (const dabench::InputError& error) {
    const std::string message = error.what();
    for (const auto& part : parts) {
      INFO("message: " << message);
      CHECK(contains(message, part));
    }
    CHECK(message.find('\n') == std::string::npos);
  }
  CHECK_FALSE(dir.exists("B"));
}

// Same header and rows; the count of differing rows is reported, not every cell.
inline void check_same(const CsvTable& a, const CsvTable& b) {
  REQUIRE(a.header == b.header);
  REQUIRE(a.rows.size() == b.rows.size());
  std::size_t differing = 0;
  for (std::size_t r = 0; r < a.rows.size(); ++r) differing += a.rows[r] != b.rows[r];
  CHECK(differing == 0);
}

inline double number(const CsvTable& table, std::size_t row, const std::string& column) {
  return to_double(table.at(row, column));
}

// Byte offset of the first row (after the header) whose item, point · trials + trial, is >= item.
inline std::size_t offset_of_item(const std::string& text, long long item, int trials_per_point) {
  const auto lines = split_lines(text);
  const CsvTable table = parse_csv(text);
  const std::size_t point = table.column("point"), trial = table.column("trial");
  std::size_t offset = lines[0].size() + 1;
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    if (std::stoll(table.rows[r][point]) * trials_per_point + std::stoll(table.rows[r][trial]) >= item) return offset;
    offset += lines[r + 1].size() + 1;
  }
  return offset;
}

}  // namespace dabench::test::cli
