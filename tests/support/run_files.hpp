#pragma once
// Helpers of the run tests (test_run_multi_scan, test_run_tracking, test_run_tracking_iterations):
// run an experiment through the C++ API, check that a bad one is refused in one line (through the
// API or the command line), compare CSV tables without their timing columns, find the byte where
// a work item's rows start, write the files a hard kill leaves and check those of a resumed run.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>
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

// Writes `text` as dir/bad.ini and checks that `dabench run bad.ini --out B` exits with status 2
// and one stderr line naming every part, and writes no output folder B.
inline void check_refused_on_command_line(TempDir& dir, const std::string& text, const std::vector<std::string>& parts) {
  dir.write("bad.ini", text);
  const CliResult result = run_dabench(dir, {"run", "bad.ini", "--out", "B"});
  CHECK(result.status == 2);
  for (const auto& part : parts) {
    INFO("stderr: " << result.err);
    CHECK(contains(result.err, part));
  }
  CHECK(std::count(result.err.begin(), result.err.end(), '\n') == 1);
  CHECK_FALSE(dir.exists("B"));
}

// The columns that differ between two runs of one experiment: the timings (time_us of the
// single- and multi-scan runs, tet_s of the tracking runs).
inline bool is_timing_column(const std::string& name) {
  return name.rfind("time_us", 0) == 0 || name.rfind("tet_s", 0) == 0;
}

// The CSV file `relative` (to dir.work()), which must exist, without its timing columns.
inline CsvTable without_timing(const TempDir& dir, const std::string& relative) {
  REQUIRE(dir.exists(relative));
  return parse_csv(dir.read(relative)).without(is_timing_column);
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

// A run file's name (in its output folder) and its text.
using RunFile = std::pair<std::string, std::string>;

// checksums.csv recording every whole row (after the header line) of each CSV file of `files`,
// as the runner writes it once those rows are flushed: `FILE,C1 C2 ...` with C the 32-bit FNV-1a
// of the row, computed here independently of harness/run/row_checksums.cpp.
inline std::string checksums_recording(const std::vector<RunFile>& files) {
  std::string text = "file,row_checksums\n";
  for (const auto& [name, contents] : files) {
    if (name.size() < 4 || name.compare(name.size() - 4, 4, ".csv") != 0) continue;
    std::string line;
    const std::size_t header_end = contents.find('\n');
    for (std::size_t at = header_end == std::string::npos ? contents.size() : header_end + 1; at < contents.size();) {
      const std::size_t end = contents.find('\n', at);
      if (end == std::string::npos) break;  // a row cut short was never recorded
      std::uint32_t hash = 2166136261u;
      for (std::size_t k = at; k < end; ++k) hash = (hash ^ static_cast<unsigned char>(contents[k])) * 16777619u;
      char hex[9];
      std::snprintf(hex, sizeof hex, "%08x", hash);
      line += (line.empty() ? name + "," : std::string(" ")) + hex;
      at = end + 1;
    }
    if (!line.empty()) text += line + "\n";
  }
  return text;
}

// Writes `files` into dir/folder, as a hard kill of a run into that folder could leave them: with
// a checksums.csv recording their whole rows.
inline void write_run_files(const TempDir& dir, const std::string& folder, const std::vector<RunFile>& files) {
  for (const auto& [name, text] : files) write_text(dir.work() / folder / name, text);
  write_text(dir.work() / folder / "checksums.csv", checksums_recording(files));
}

// The tracking run in dir/folder finished with the files of an uninterrupted one: trials.csv and
// summary.csv are `trials` and `summary` but for their timing columns, and every item file is
// its text in `item_files` to the byte.
inline void check_finished_tracking_run(const TempDir& dir, const std::string& folder, const CsvTable& trials,
                                        const CsvTable& summary, const std::vector<RunFile>& item_files) {
  check_same(trials, without_timing(dir, folder + "/trials.csv"));
  for (const auto& [name, text] : item_files) CHECK(dir.read(folder + "/" + name) == text);
  check_same(summary, without_timing(dir, folder + "/summary.csv"));
}

}  // namespace dabench::test::cli
