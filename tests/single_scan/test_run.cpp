// End-to-end `dabench run` on tiny grid experiments (DESIGN.md, "Results (contract)"):
//  - trials.csv: the sweep parameters, trial, seed, algorithm (full SPEC, CSV-quoted when it
//    holds a comma), status and the metric columns; one row per (point, trial, algorithm) in
//    point-major, then trial, then algorithm order with the reference first; sane metrics;
//  - summary.csv: one row per (point, algorithm), consistent with a recomputation from
//    trials.csv;
//  - determinism: every column but time_us is identical for 1 and 2 threads, for the same seed
//    twice and after any resume history (SIGINT, a hard kill cut anywhere, --resume on a
//    finished run, --force), and differs for another seed;
//  - meta.json records status, seed, threads, git commit and compiler.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <numeric>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "harness/core/build_info.hpp"
#include "tests/support/cli_contract.hpp"
#include "tests/support/cli_runner.hpp"
#include "tests/support/run_files.hpp"
#include "tests/support/sanitized.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench::test::cli;
using dabench::test::sanitized_size;
namespace fs = std::filesystem;

namespace {

// 2×3 grid, 3 spacings, 40 trials, the exact reference and three bp variants (one SPEC with a
// comma, to exercise CSV quoting). Runs in a few tens of milliseconds.
const char* const kTiny =
    "name = tiny\n"
    "description = end-to-end test experiment\n"
    "scenario = grid\n"
    "trials = 40\n"
    "seed = 11\n"
    "reference = exact\n"
    "algorithm = bp\n"
    "algorithm = bp:delta=1e-6\n"
    "algorithm = bp:delta=1e-6,check_every=10\n"
    "\n"
    "[scenario]\n"
    "rows = 2\n"
    "cols = 3\n"
    "\n"
    "[sweep]\n"
    "spacing = 0.5:1.5:3.5\n";

const std::vector<std::string> kTinySpecs = {"exact", "bp", "bp:delta=1e-6", "bp:delta=1e-6,check_every=10"};
const std::vector<std::string> kTinySpacings = {"0.5", "2", "3.5"};
constexpr int kTinyTrials = 40;

// A slower experiment for the SIGINT tests: with --trials 1500 about a second on 2 cores (the
// exact reference dominates; denser clutter makes its clusters larger); a fifth of the trials
// under a sanitizer, which slows it about as much.
const char* const kLong =
    "scenario = grid\n"
    "trials = 10\n"
    "seed = 23\n"
    "reference = exact\n"
    "algorithm = bp\n"
    "algorithm = bp:delta=1e-6,check_every=10\n"
    "[scenario]\n"
    "rows = 2\n"
    "cols = 3\n"
    "lambda_fa = 0.02\n"
    "[sweep]\n"
    "spacing = 0.5, 1.5\n";

bool is_time_column(const std::string& name) { return name.rfind("time_us", 0) == 0; }

CsvTable read_csv(const TempDir& dir, const std::string& relative) {
  REQUIRE(dir.exists(relative));
  return parse_csv(dir.read(relative));
}
CsvTable trials_without_time(const TempDir& dir, const std::string& folder) {
  return read_csv(dir, folder + "/trials.csv").without(is_time_column);
}
CsvTable summary_without_time(const TempDir& dir, const std::string& folder) {
  return read_csv(dir, folder + "/summary.csv").without(is_time_column);
}

void check_same_table(const CsvTable& a, const CsvTable& b) {
  REQUIRE(a.header == b.header);
  REQUIRE(a.rows.size() == b.rows.size());
  std::size_t differing = 0;
  for (std::size_t r = 0; r < a.rows.size(); ++r) {
    if (a.rows[r] != b.rows[r]) {
      if (differing++ < 3) {
        INFO("first differing rows, row " << r + 2);
        CHECK(a.rows[r] == b.rows[r]);
      }
    }
  }
  CHECK(differing == 0);
}

// The metric columns of the single-scan runner, in order (DESIGN.md, "Results").
const std::vector<std::string> kMetrics = {"n_targets", "n_measurements", "max_error", "mean_error",
                                           "time_us",   "iterations",     "converged", "w_star"};

// The numbers of `column` in rows of `table` where column `key` equals `value` and `key2` equals
// `value2`; empty fields are missing and left out.
std::vector<double> values_of(const CsvTable& table, const std::string& column,
                              const std::vector<std::pair<std::string, std::string>>& where) {
  std::vector<double> values;
  const std::size_t c = table.column(column);
  for (const auto& row : table.rows) {
    bool match = true;
    for (const auto& [key, value] : where) match = match && row.at(table.column(key)) == value;
    if (match && !row[c].empty()) values.push_back(to_double(row[c]));
  }
  return values;
}

// Type-7 percentile, written out independently of harness/core/summary.cpp.
double percentile(std::vector<double> values, double fraction) {
  std::sort(values.begin(), values.end());
  const double h = (static_cast<double>(values.size()) - 1.0) * fraction;
  const std::size_t lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(lo + 1, values.size() - 1);
  return values[lo] + (h - std::floor(h)) * (values[hi] - values[lo]);
}

std::string json_field(const std::string& json, const std::string& key) {
  const std::string tag = "\"" + key + "\": ";
  const auto at = json.find(tag);
  if (at == std::string::npos) return "<absent>";
  const auto begin = at + tag.size();
  const auto end = json.find_first_of(",\n", begin);
  return json.substr(begin, end - begin);
}

std::size_t count_lines(const std::string& text) { return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')); }

}  // namespace

TEST_CASE("run: trials.csv has the documented columns and one row per point trial algorithm in order",
          "[run]") {
  TempDir dir;
  dir.write("tiny.ini", kTiny);
  const CliResult result = run_ok(dir, {"run", "tiny.ini", "--threads", "2"});
  CHECK(result.out.empty());
  // Default output folder: results/<name>.
  REQUIRE(dir.exists("results/tiny/trials.csv"));
  const std::string text = dir.read("results/tiny/trials.csv");
  const CsvTable trials = parse_csv(text);

  // Columns: point, every scenario parameter, trial, seed, algorithm, status, then the metrics.
  const auto& h = trials.header;
  CHECK(h.front() == "point");
  const std::size_t trial_column = trials.column("trial");
  for (const char* param : {"rows", "cols", "spacing", "pd", "lambda_fa", "r"}) {
    INFO("parameter column " << param);
    REQUIRE(trials.find_column(param));
    CHECK(*trials.find_column(param) < trial_column);
  }
  REQUIRE(trial_column + 4 + kMetrics.size() == h.size());
  CHECK(h[trial_column + 1] == "seed");
  CHECK(h[trial_column + 2] == "algorithm");
  CHECK(h[trial_column + 3] == "status");
  CHECK(std::vector<std::string>(h.begin() + static_cast<long>(trial_column) + 4, h.end()) == kMetrics);

  // One row per (point, trial, algorithm): point-major, then trial, then algorithm (reference first).
  const std::size_t n_specs = kTinySpecs.size();
  REQUIRE(trials.rows.size() == kTinySpacings.size() * kTinyTrials * n_specs);
  for (std::size_t r = 0; r < trials.rows.size(); ++r) {
    const std::size_t point = r / (kTinyTrials * n_specs);
    const std::size_t trial = (r / n_specs) % kTinyTrials;
    const std::string& spec = kTinySpecs[r % n_specs];
    INFO("row " << r + 2);
    CHECK(trials.at(r, "point") == std::to_string(point));
    CHECK(trials.at(r, "spacing") == kTinySpacings[point]);
    CHECK(trials.at(r, "rows") == "2");
    CHECK(trials.at(r, "cols") == "3");
    CHECK(trials.at(r, "trial") == std::to_string(trial));
    CHECK(trials.at(r, "seed") == "11");
    CHECK(trials.at(r, "algorithm") == spec);
    CHECK(trials.at(r, "status") == "ok");
    CHECK(trials.at(r, "n_targets") == "6");
    CHECK(to_double(trials.at(r, "time_us")) > 0.0);
    const double max_error = to_double(trials.at(r, "max_error"));
    const double mean_error = to_double(trials.at(r, "mean_error"));
    if (spec == "exact") {
      CHECK(trials.at(r, "max_error") == "0");
      CHECK(trials.at(r, "mean_error") == "0");
      CHECK(trials.at(r, "w_star").empty());
    } else {
      CHECK(max_error >= 0.0);
      CHECK(max_error < 0.2);
      CHECK(mean_error >= 0.0);
      CHECK(mean_error <= max_error);
      CHECK(to_double(trials.at(r, "iterations")) >= 1.0);
      CHECK(trials.at(r, "converged") == "1");
      CHECK(to_double(trials.at(r, "w_star")) >= 0.0);
    }
  }
  // Close targets share measurements, so bp is not exact there.
  for (const std::string& spec : {std::string("bp"), std::string("bp:delta=1e-6,check_every=10")}) {
    const auto errors = values_of(trials, "max_error", {{"point", "0"}, {"algorithm", spec}});
    REQUIRE(errors.size() == static_cast<std::size_t>(kTinyTrials));
    CHECK(*std::max_element(errors.begin(), errors.end()) > 0.0);
  }
  // The SPEC with a comma is one quoted CSV field.
  CHECK(text.find(",\"bp:delta=1e-6,check_every=10\",") != std::string::npos);
}

TEST_CASE("run: summary.csv matches a recomputation from trials.csv", "[run]") {
  TempDir dir;
  dir.write("tiny.ini", kTiny);
  run_ok(dir, {"run", "tiny.ini", "--threads", "2", "--out", "o"});
  const CsvTable trials = read_csv(dir, "o/trials.csv");
  const std::string summary_text = dir.read("o/summary.csv");
  const CsvTable summary = parse_csv(summary_text);

  // Columns: point + parameters, algorithm, trials/ok/skipped/failed, six statistics per metric.
  const std::size_t trial_column = trials.column("trial");
  std::vector<std::string> expected(trials.header.begin(), trials.header.begin() + static_cast<long>(trial_column));
  for (const char* name : {"algorithm", "trials", "ok", "skipped", "failed"}) expected.push_back(name);
  for (const auto& metric : kMetrics) {
    for (const char* stat : {"count", "mean", "se", "median", "p5", "p95"}) expected.push_back(metric + "_" + stat);
  }
  CHECK(summary.header == expected);
  CHECK(summary_text.find(",\"bp:delta=1e-6,check_every=10\",") != std::string::npos);

  // One row per (point, algorithm), point-major, algorithms in trials.csv order.
  REQUIRE(summary.rows.size() == kTinySpacings.size() * kTinySpecs.size());
  for (std::size_t r = 0; r < summary.rows.size(); ++r) {
    const std::string point = std::to_string(r / kTinySpecs.size());
    const std::string& spec = kTinySpecs[r % kTinySpecs.size()];
    INFO("summary row " << r + 2 << ": point " << point << ", " << spec);
    CHECK(summary.at(r, "point") == point);
    CHECK(summary.at(r, "spacing") == kTinySpacings[r / kTinySpecs.size()]);
    CHECK(summary.at(r, "algorithm") == spec);
    CHECK(summary.at(r, "trials") == "40");
    CHECK(summary.at(r, "ok") == "40");
    CHECK(summary.at(r, "skipped") == "0");
    CHECK(summary.at(r, "failed") == "0");
    for (const auto& metric : kMetrics) {
      INFO("metric " << metric);
      const auto values = values_of(trials, metric, {{"point", point}, {"algorithm", spec}});
      CHECK(summary.at(r, metric + "_count") == std::to_string(values.size()));
      if (values.empty()) {
        for (const char* stat : {"mean", "se", "median", "p5", "p95"}) CHECK(summary.at(r, metric + "_" + stat).empty());
        continue;
      }
      const double n = static_cast<double>(values.size());
      const double mean = std::accumulate(values.begin(), values.end(), 0.0) / n;
      double squares = 0.0;
      for (const double v : values) squares += (v - mean) * (v - mean);
      const double se = std::sqrt(squares / (n - 1.0) / n);
      const auto close = [](double expected_value) { return Approx(expected_value).epsilon(1e-12).margin(1e-300); };
      CHECK(to_double(summary.at(r, metric + "_mean")) == close(mean));
      CHECK(to_double(summary.at(r, metric + "_se")) == Approx(se).epsilon(1e-9).margin(1e-15 * std::fabs(mean)));
      CHECK(to_double(summary.at(r, metric + "_median")) == close(percentile(values, 0.5)));
      CHECK(to_double(summary.at(r, metric + "_p5")) == close(percentile(values, 0.05)));
      CHECK(to_double(summary.at(r, metric + "_p95")) == close(percentile(values, 0.95)));
    }
  }
  // The reference has no w_star and zero error; bp at the closest spacing has some error.
  CHECK(summary.at(0, "w_star_count") == "0");
  CHECK(summary.at(0, "max_error_mean") == "0");
  CHECK(to_double(summary.at(1, "max_error_mean")) > 0.0);

  // An explicit median check on one group, by hand: 40 values → mean of the 20th and 21st.
  auto errors = values_of(trials, "max_error", {{"point", "0"}, {"algorithm", "bp"}});
  std::sort(errors.begin(), errors.end());
  CHECK(to_double(summary.at(1, "max_error_median")) == Approx((errors[19] + errors[20]) / 2).epsilon(1e-14));
}

TEST_CASE("run: meta.json records the run", "[run]") {
  TempDir dir;
  dir.write("tiny.ini", kTiny);
  run_ok(dir, {"run", "tiny.ini", "--threads", "2", "--out", "o", "--seed", "99", "--trials", "3"});
  const std::string meta = dir.read("o/meta.json");
  INFO(meta);
  CHECK(json_field(meta, "status") == "\"complete\"");
  CHECK(json_field(meta, "seed") == "99");
  CHECK(json_field(meta, "threads") == "2");
  CHECK(json_field(meta, "trials_per_point") == "3");
  CHECK(json_field(meta, "git_commit").size() > 2);
  CHECK(json_field(meta, "git_commit") != "<absent>");
  const dabench::BuildInfo& build = dabench::build_info();
  CHECK(json_field(meta, "source_modified") == (build.source == dabench::Provenance::unknown    ? "null"
                                                : build.source == dabench::Provenance::modified ? "true"
                                                                                                : "false"));
  CHECK(json_field(meta, "compiler").size() > 2);
  CHECK(json_field(meta, "compiler") != "<absent>");
  CHECK(json_field(meta, "command_line") != "<absent>");
  CHECK(json_field(meta, "start_time") != "<absent>");
  CHECK(json_field(meta, "end_time") != "<absent>");
  CHECK(json_field(meta, "host") != "<absent>");
  CHECK(contains(meta, "check_every=10"));  // the experiment text or the algorithm list
  // trials.csv's seed column follows --seed.
  const CsvTable trials = read_csv(dir, "o/trials.csv");
  CHECK(trials.rows.size() == 3u * 3u * kTinySpecs.size());
  for (std::size_t r = 0; r < trials.rows.size(); ++r) CHECK(trials.at(r, "seed") == "99");
}

TEST_CASE("run: results do not depend on the thread count and follow the seed", "[run][determinism]") {
  TempDir dir;
  dir.write("tiny.ini", kTiny);
  run_ok(dir, {"run", "tiny.ini", "--threads", "1", "--out", "t1"});
  run_ok(dir, {"run", "tiny.ini", "--threads", "2", "--out", "t2"});
  run_ok(dir, {"run", "tiny.ini", "--threads", "2", "--out", "t2again"});
  run_ok(dir, {"run", "tiny.ini", "--threads", "2", "--out", "s12", "--seed", "12"});
  CHECK(json_field(dir.read("t1/meta.json"), "threads") == "1");
  CHECK(json_field(dir.read("t2/meta.json"), "threads") == "2");

  const CsvTable t1 = trials_without_time(dir, "t1");
  SECTION("1 vs 2 threads") {
    check_same_table(t1, trials_without_time(dir, "t2"));
    check_same_table(summary_without_time(dir, "t1"), summary_without_time(dir, "t2"));
  }
  SECTION("same seed twice") {
    check_same_table(trials_without_time(dir, "t2"), trials_without_time(dir, "t2again"));
    check_same_table(summary_without_time(dir, "t2"), summary_without_time(dir, "t2again"));
  }
  SECTION("another seed gives other trials") {
    const CsvTable s12 = trials_without_time(dir, "s12");
    REQUIRE(s12.rows.size() == t1.rows.size());
    std::size_t same_measurement_counts = 0, same_errors = 0, nonzero_errors = 0;
    for (std::size_t r = 0; r < t1.rows.size(); ++r) {
      CHECK(s12.at(r, "seed") == "12");
      same_measurement_counts += s12.at(r, "n_measurements") == t1.at(r, "n_measurements");
      if (t1.at(r, "max_error") != "0") {
        ++nonzero_errors;
        same_errors += s12.at(r, "max_error") == t1.at(r, "max_error");
      }
    }
    CHECK(same_measurement_counts < t1.rows.size());
    CHECK(nonzero_errors > 20);
    CHECK(same_errors == 0);
  }
}

TEST_CASE("run: SIGINT stops with status 130 and --resume finishes identically", "[run][resume]") {
  TempDir dir;
  dir.write("long.ini", kLong);
  const int trials = sanitized_size(1500, 5);
  const std::vector<std::string> common = {"run", "long.ini", "--trials", std::to_string(trials)};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = common;
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  };
  run_ok(dir, with({"--threads", "2", "--out", "A"}));
  const std::size_t rows_per_item = 3;
  const std::size_t total_rows = 2 * static_cast<std::size_t>(trials) * rows_per_item;

  {
    CliProcess process(with({"--threads", "2", "--out", "B"}), dir.work(), dir.io());
    // Interrupt once rows are being written (the handler is installed by then).
    const fs::path trials_file = dir.work() / "B" / "trials.csv";
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (std::chrono::steady_clock::now() < deadline) {
      if (fs::exists(trials_file) && count_lines(read_text(trials_file)) >= 1 + rows_per_item) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(30));
    process.signal_process(SIGINT);
    const CliResult interrupted = process.wait();
    INFO("stderr: " << interrupted.err);
    REQUIRE_FALSE(interrupted.signaled);
    REQUIRE(interrupted.status == 130);
    CHECK(interrupted.out.empty());
    CHECK(contains(interrupted.err, "--resume"));
  }
  // A prefix of whole items of the uninterrupted run; no summary yet; meta.json says so.
  const std::string partial_text = dir.read("B/trials.csv");
  CHECK((!partial_text.empty() && partial_text.back() == '\n'));
  const CsvTable partial = parse_csv(partial_text).without(is_time_column);
  const CsvTable full = trials_without_time(dir, "A");
  REQUIRE(full.rows.size() == total_rows);
  REQUIRE(partial.header == full.header);
  REQUIRE(partial.rows.size() < full.rows.size());
  CHECK(partial.rows.size() % rows_per_item == 0);
  for (std::size_t r = 0; r < partial.rows.size(); ++r) {
    if (partial.rows[r] != full.rows[r]) {
      INFO("row " << r + 2);
      REQUIRE(partial.rows[r] == full.rows[r]);
    }
  }
  CHECK_FALSE(dir.exists("B/summary.csv"));
  CHECK(json_field(dir.read("B/meta.json"), "status") == "\"interrupted\"");

  // Resume with another thread count: identical rows and summary (time aside).
  const CliResult resumed = run_ok(dir, with({"--threads", "1", "--out", "B", "--resume"}));
  CHECK(resumed.out.empty());
  check_same_table(full, trials_without_time(dir, "B"));
  check_same_table(summary_without_time(dir, "A"), summary_without_time(dir, "B"));
  const std::string meta = dir.read("B/meta.json");
  CHECK(json_field(meta, "status") == "\"complete\"");
  CHECK(json_field(meta, "resumed") == "true");
}

TEST_CASE("run: --resume after a hard kill at any byte offset finishes identically", "[run][resume]") {
  TempDir dir;
  dir.write("tiny.ini", kTiny);
  run_ok(dir, {"run", "tiny.ini", "--threads", "2", "--out", "A"});
  const std::string complete = dir.read("A/trials.csv");
  const CsvTable reference = trials_without_time(dir, "A");
  const CsvTable reference_summary = summary_without_time(dir, "A");
  const std::string meta = dir.read("A/meta.json");
  const auto lines = split_lines(complete);
  const std::size_t header_size = lines[0].size() + 1;
  // Byte offset where row `row` (0-based, after the header) starts.
  const auto row_start = [&](std::size_t row) {
    std::size_t offset = header_size;
    for (std::size_t k = 1; k <= row; ++k) offset += lines[k].size() + 1;
    return offset;
  };
  const std::size_t specs = kTinySpecs.size();

  std::vector<std::pair<std::string, std::size_t>> cuts = {
      {"right after the header", header_size},
      {"inside the first row", header_size + 10},
      {"after the first (reference) row of an item", row_start(1)},
      {"mid-item inside a bp row", row_start(specs * 17 + 2) + 25},
      {"in the middle of the file, mid-line", complete.size() / 2},
      {"at an item boundary inside a block", row_start(specs * 5)},
      {"at a block boundary", row_start(specs * 8)},
      {"on a quoted comma SPEC", row_start(specs * 30 + 3) + complete.substr(row_start(specs * 30 + 3)).find("check_every")},
      {"just before the final newline", complete.size() - 1},
      {"empty file", 0},
  };
  // One folder per cut, all beside the one reference run (sections would rerun it per cut).
  for (std::size_t c = 0; c < cuts.size(); ++c) {
    const auto& [what, offset] = cuts[c];
    INFO("cut " << what << " (byte " << offset << ")");
    // A hard kill leaves trials.csv cut anywhere and meta.json saying "running"; no summary.
    const std::string folder = "K" + std::to_string(c);
    fs::create_directories(dir.work() / folder);
    write_run_files(dir, folder, {{"trials.csv", complete.substr(0, offset)}, {"meta.json", meta}});
    run_ok(dir, {"run", "tiny.ini", "--threads", "2", "--out", folder, "--resume"});
    check_same_table(reference, trials_without_time(dir, folder));
    check_same_table(reference_summary, summary_without_time(dir, folder));
    CHECK(json_field(dir.read(folder + "/meta.json"), "status") == "\"complete\"");
  }
}

// --resume keeps rows only when they are, row by row, the plan's items in order with one row
// per SPEC; anything else (rows reordered, another run's rows pasted in, more items than the
// run has) is refused with one line, and the folder is left as it was.
TEST_CASE("run: --resume refuses kept rows that are not the plan's items", "[run][resume]") {
  TempDir dir;
  dir.write("tiny.ini", kTiny);
  run_ok(dir, {"run", "tiny.ini", "--threads", "2", "--out", "A"});
  const auto lines = split_lines(dir.read("A/trials.csv"));
  const std::string meta = dir.read("A/meta.json");
  const std::size_t specs = kTinySpecs.size();
  // The header and rows [0, rows) of the run, row a read from row b and row b from row a.
  const auto text = [&](std::size_t rows, std::size_t a, std::size_t b) {
    std::string joined = lines[0] + "\n";
    for (std::size_t r = 0; r < rows; ++r) joined += lines[1 + (r == a ? b : r == b ? a : r)] + "\n";
    return joined;
  };
  const std::string first_item_again = text(specs, 0, 0).substr(lines[0].size() + 1);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"two items exchanged", text(10 * specs, 1, specs + 1)},
      {"two algorithms of an item exchanged", text(10 * specs, 2, 3)},
      {"a row of the second point in place of the third item's first", text(10 * specs, 2 * specs, 45 * specs)},
      {"more items than the run has", text(lines.size() - 1, 0, 0) + first_item_again},
  };
  for (const auto& [what, trials] : cases) {
    DYNAMIC_SECTION(what) {
      write_run_files(dir, "K", {{"trials.csv", trials}, {"meta.json", meta}});
      const CliResult result = run_dabench(dir, {"run", "tiny.ini", "--threads", "2", "--out", "K", "--resume"});
      INFO(result.err);
      CHECK(result.status == 2);
      CHECK(contains(result.err, "cannot resume (use --force to start over)"));
      CHECK(std::count(result.err.begin(), result.err.end(), '\n') == 1);
      CHECK(dir.read("K/trials.csv") == trials);
      CHECK_FALSE(dir.exists("K/summary.csv"));
    }
  }
}

// A cut inside the header line (the header is written before the first row, so only a crash in
// the first moments of a run can leave one) makes --resume refuse instead of starting over.
TEST_CASE("run: --resume after a hard kill inside the header line", "[run][resume]") {
  TempDir dir;
  dir.write("tiny.ini", kTiny);
  run_ok(dir, {"run", "tiny.ini", "--threads", "2", "--out", "A", "--trials", "5"});
  const std::string complete = dir.read("A/trials.csv");
  write_run_files(dir, "K", {{"trials.csv", complete.substr(0, 20)}});
  write_text(dir.work() / "K" / "meta.json", dir.read("A/meta.json"));
  run_ok(dir, {"run", "tiny.ini", "--threads", "2", "--out", "K", "--resume", "--trials", "5"});
  check_same_table(trials_without_time(dir, "A"), trials_without_time(dir, "K"));
}

TEST_CASE("run: --resume on a finished run is a no-op and --force restarts", "[run][resume]") {
  TempDir dir;
  dir.write("tiny.ini", kTiny);
  run_ok(dir, {"run", "tiny.ini", "--threads", "2", "--out", "A"});
  const std::string trials_a = dir.read("A/trials.csv");
  const CsvTable reference = trials_without_time(dir, "A");

  SECTION("--resume keeps every row byte-identical") {
    const std::string summary_a = dir.read("A/summary.csv");
    run_ok(dir, {"run", "tiny.ini", "--threads", "1", "--out", "A", "--resume"});
    CHECK(dir.read("A/trials.csv") == trials_a);  // nothing re-run, so even time_us is kept
    CHECK(dir.read("A/summary.csv") == summary_a);
    CHECK(json_field(dir.read("A/meta.json"), "status") == "\"complete\"");
  }
  SECTION("--force starts over and gives the same rows") {
    const std::string summary_before = dir.read("A/summary.csv");
    run_ok(dir, {"run", "tiny.ini", "--threads", "1", "--out", "A", "--force"});
    check_same_table(reference, trials_without_time(dir, "A"));
    CHECK(dir.read("A/trials.csv") != trials_a);  // re-run: new timings
    check_same_table(parse_csv(summary_before).without(is_time_column), summary_without_time(dir, "A"));
    CHECK(json_field(dir.read("A/meta.json"), "resumed") == "false");
  }
  SECTION("--force with another seed replaces the run") {
    run_ok(dir, {"run", "tiny.ini", "--threads", "2", "--out", "A", "--force", "--seed", "4"});
    const CsvTable trials = trials_without_time(dir, "A");
    REQUIRE(trials.rows.size() == reference.rows.size());
    CHECK(trials.at(0, "seed") == "4");
    CHECK(json_field(dir.read("A/meta.json"), "seed") == "4");
  }
  SECTION("--resume on an empty folder starts a fresh run") {
    fs::create_directories(dir.work() / "E");
    run_ok(dir, {"run", "tiny.ini", "--threads", "2", "--out", "E", "--resume"});
    check_same_table(reference, trials_without_time(dir, "E"));
  }
}

// The interrupted-run message says "finish with: <the command line> --resume". When the
// interrupted command already held --force (or --resume), that suggestion is rejected
// ("--resume and --force exclude each other" / "'--resume' cannot be specified more than once").
TEST_CASE("run: the command suggested after an interrupted --force run finishes it", "[run][resume]") {
  TempDir dir;
  dir.write("long.ini", kLong);
  run_ok(dir, {"run", "long.ini", "--trials", "3", "--out", "F"});  // a finished run to --force over
  fs::remove(dir.work() / "F" / "trials.csv");                      // (so the poll below sees the new one)
  CliProcess process({"run", "long.ini", "--trials", std::to_string(sanitized_size(600, 5)), "--threads", "2", "--out", "F",
                      "--force"},
                     dir.work(), dir.io());
  const fs::path trials = dir.work() / "F" / "trials.csv";
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (std::chrono::steady_clock::now() < deadline) {
    if (count_lines(read_text(trials)) >= 4) break;  // the new run's header and a first item
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  process.signal_process(SIGINT);
  const CliResult interrupted = process.wait();
  INFO("stderr: " << interrupted.err);
  REQUIRE(interrupted.status == 130);
  const std::string tag = "finish with: ";
  const auto at = interrupted.err.find(tag);
  REQUIRE(at != std::string::npos);
  std::vector<std::string> words;
  std::istringstream suggestion(interrupted.err.substr(at + tag.size(), interrupted.err.find('\n', at) - at - tag.size()));
  for (std::string word; suggestion >> word;) words.push_back(word);
  REQUIRE(words.size() > 2);
  CHECK(words[0] == DABENCH_BINARY);
  run_ok(dir, std::vector<std::string>(words.begin() + 1, words.end()));
}

TEST_CASE("run: fallback references run only when the ones before them are skipped", "[run]") {
  // The first reference refuses every problem with more than a handful of events; the second
  // (plain exact) takes over exactly then. Errors are always measured against the one used.
  TempDir dir;
  dir.write("fallback.ini",
            "scenario = grid\n"
            "trials = 30\n"
            "seed = 5\n"
            "reference = exact:max_events=20\n"
            "reference = exact\n"
            "algorithm = bp\n"
            "[sweep]\n"
            "spacing = 0, 10\n");
  run_ok(dir, {"run", "fallback.ini", "--out", "o"});
  const CsvTable trials = read_csv(dir, "o/trials.csv");
  REQUIRE(trials.rows.size() == 2u * 30u * 3u);
  int primary_used = 0, fallback_used = 0;
  for (std::size_t r = 0; r < trials.rows.size(); r += 3) {
    const std::string primary = trials.at(r, "status");
    const std::string fallback = trials.at(r + 1, "status");
    REQUIRE(trials.at(r, "algorithm") == "exact:max_events=20");
    REQUIRE(trials.at(r + 1, "algorithm") == "exact");
    REQUIRE(trials.at(r + 2, "algorithm") == "bp");
    if (primary == "ok") {
      ++primary_used;
      CHECK(fallback == "skipped:not_needed");
      CHECK(trials.at(r + 1, "max_error").empty());
      CHECK(trials.at(r, "max_error") == "0");
    } else {
      ++fallback_used;
      CHECK(primary == "skipped:work_limit");
      CHECK(fallback == "ok");
      CHECK(trials.at(r + 1, "max_error") == "0");
    }
    CHECK(!trials.at(r + 2, "max_error").empty());  // bp always has a reference to compare with
  }
  CHECK(primary_used > 10);   // wide spacing: tiny clusters
  CHECK(fallback_used > 10);  // spacing 0: six targets in one cluster
}

}  // namespace DABENCH_TEST_FILE
