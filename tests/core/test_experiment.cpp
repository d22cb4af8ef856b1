// harness/core/experiment.hpp: experiment files and sweep values, called directly.
//  - expand_sweep_values: inclusive start:step:stop ranges printed without binary noise
//    (0:0.1:1 gives "0.3", not "0.30000000000000004"), comma lists, whitespace;
//  - load_experiment: every top-level key, defaults (name = file stem, output = results/<name>),
//    [scenario] fixed values overridden by sweeps, full-factorial order inside a block (first
//    key slowest), [sweep.X] blocks concatenated in file order, `key = @other` ties;
//  - every error is a dabench::InputError whose message names the file.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "harness/core/errors.hpp"
#include "harness/core/experiment.hpp"
#include "tests/support/cli_runner.hpp"
#include "tests/support/input_error.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench;
using namespace dabench::test::cli;
using dabench::test::input_error_message;
namespace fs = std::filesystem;

namespace {

using Strings = std::vector<std::string>;

// The value of `key` in a point's settings, or "<unset>".
std::string value(const std::vector<KeyValue>& settings, const std::string& key) {
  for (const KeyValue& kv : settings) {
    if (kv.key == key) return kv.value;
  }
  return "<unset>";
}

// (key → value) pairs of each point, for the keys asked.
std::vector<Strings> table(const Experiment& experiment, const Strings& keys) {
  std::vector<Strings> rows;
  for (const auto& point : experiment.points) {
    Strings row;
    for (const auto& key : keys) row.push_back(value(point, key));
    rows.push_back(row);
  }
  return rows;
}

const char* const kHeader =
    "scenario = grid\n"
    "trials = 4\n"
    "algorithm = bp\n";

}  // namespace

TEST_CASE("experiment: ranges are inclusive and free of binary noise", "[experiment]") {
  CHECK(expand_sweep_values("0:0.5:2") == Strings{"0", "0.5", "1", "1.5", "2"});
  CHECK(expand_sweep_values("0:0.1:1") == Strings{"0", "0.1", "0.2", "0.3", "0.4", "0.5", "0.6", "0.7", "0.8", "0.9", "1"});
  CHECK(expand_sweep_values("0:0.1:0.3") == Strings{"0", "0.1", "0.2", "0.3"});  // (0.3-0)/0.1 = 2.9999999999999996
  CHECK(expand_sweep_values("0:0.3:1") == Strings{"0", "0.3", "0.6", "0.9"});     // stop not hit exactly
  CHECK(expand_sweep_values("2:1:2") == Strings{"2"});
  CHECK(expand_sweep_values("-1:0.5:0") == Strings{"-1", "-0.5", "0"});
  CHECK(expand_sweep_values("1e-3:1e-3:3e-3") == Strings{"0.001", "0.002", "0.003"});
  CHECK(expand_sweep_values("  0 : 2 :  4 ") == Strings{"0", "2", "4"});
  const Strings quarter = expand_sweep_values("0:0.25:10");
  REQUIRE(quarter.size() == 41);
  CHECK(quarter[1] == "0.25");
  CHECK(quarter[39] == "9.75");
  CHECK(quarter.back() == "10");
  const Strings tenth = expand_sweep_values("0:0.1:10");
  REQUIRE(tenth.size() == 101);
  for (const std::string& text : tenth) {
    INFO(text);
    CHECK(text.size() <= 4);  // "9.9", "10": no 0.30000000000000004
  }
}

TEST_CASE("experiment: lists keep their text and trim whitespace", "[experiment]") {
  CHECK(expand_sweep_values("1, 2,3") == Strings{"1", "2", "3"});
  CHECK(expand_sweep_values("  0.3 ,\t0.6 , 0.9  ") == Strings{"0.3", "0.6", "0.9"});
  CHECK(expand_sweep_values("5") == Strings{"5"});
  CHECK(expand_sweep_values("1e-5, 0.10") == Strings{"1e-5", "0.10"});
}

TEST_CASE("experiment: malformed sweep values throw InputError", "[experiment]") {
  for (const char* text : {"0:0:10", "0:1", "0:1:2:3", "a:1:2", "0:b:2", "0:1:", ":1:2", "2:1:0", "0:-1:5", "1,,2",
                           "1,2,", ",1", "", "   ", "0:1e-7:1"}) {
    INFO("value '" << text << "'");
    const std::string message = input_error_message([&] { expand_sweep_values(text); });
    CHECK(!message.empty());
  }
}

TEST_CASE("experiment: a complete file is read key by key", "[experiment]") {
  const fs::path path = fs::path(DABENCH_SOURCE_DIR) / "tests" / "data" / "experiment_full.ini";
  const Experiment e = load_experiment(path.string());
  CHECK(e.path == path.string());
  CHECK(e.text == read_text(path));
  CHECK(e.name == "full_example");
  CHECK(e.description == "every key, two sweep blocks");
  CHECK(e.scenario == "grid");
  CHECK(e.trials == 25);
  CHECK(e.seed == 1234);
  CHECK(e.output == "somewhere/else");
  CHECK(e.references == std::vector<std::string>{"exact"});
  CHECK(e.algorithms == Strings{"bp", "bp:delta=1e-6,check_every=10", "bp:delta=1e-6"});
  CHECK(e.swept_keys == Strings{"rows", "spacing", "pd"});

  // [sweep]: rows × spacing (rows slowest), cols tied to rows, spacing 9 overridden, pd fixed;
  // then [sweep.pd_panel]: pd over the fixed values (rows 2, cols 3, spacing 9).
  const std::vector<Strings> expected = {
      {"1", "1", "0", "0.6"},   {"1", "1", "0.5", "0.6"}, {"1", "1", "1", "0.6"},
      {"2", "2", "0", "0.6"},   {"2", "2", "0.5", "0.6"}, {"2", "2", "1", "0.6"},
      {"2", "3", "9", "0.3"},   {"2", "3", "9", "0.9"},
  };
  CHECK(table(e, {"rows", "cols", "spacing", "pd"}) == expected);
}

TEST_CASE("experiment: defaults for name output seed and points", "[experiment]") {
  TempDir dir;
  SECTION("name from the file stem, output results/<stem>, one point of fixed values") {
    const fs::path path = dir.work() / "my_study.v2.ini";
    write_text(path, std::string(kHeader) + "[scenario]\nrows = 3\n");
    const Experiment e = load_experiment(path.string());
    CHECK(e.name == "my_study.v2");
    CHECK(e.output == "results/my_study.v2");
    CHECK(e.description.empty());
    CHECK(e.seed == 1);
    CHECK(e.references.empty());
    CHECK(e.swept_keys.empty());
    REQUIRE(e.points.size() == 1);
    CHECK(e.points[0].size() == 1);
    CHECK(value(e.points[0], "rows") == "3");
  }
  SECTION("no [scenario] and no sweep: one point with no settings") {
    const fs::path path = dir.work() / "bare.ini";
    write_text(path, kHeader);
    const Experiment e = load_experiment(path.string());
    REQUIRE(e.points.size() == 1);
    CHECK(e.points[0].empty());
  }
  SECTION("output follows an explicit name") {
    const fs::path path = dir.work() / "file.ini";
    write_text(path, std::string("name = study\n") + kHeader);
    const Experiment e = load_experiment(path.string());
    CHECK(e.name == "study");
    CHECK(e.output == "results/study");
  }
  SECTION("a reference alone is enough") {
    const fs::path path = dir.work() / "ref.ini";
    write_text(path, "scenario = grid\ntrials = 1\nreference = exact\n");
    const Experiment e = load_experiment(path.string());
    CHECK(e.algorithms.empty());
    CHECK(e.references == std::vector<std::string>{"exact"});
  }
}

TEST_CASE("experiment: full-factorial order with the first key slowest", "[experiment]") {
  TempDir dir;
  const fs::path path = dir.work() / "f.ini";
  write_text(path, std::string(kHeader) + "[sweep]\npd = 0.3, 0.6\nrows = 1:1:3\nspacing = 0, 5\n");
  const Experiment e = load_experiment(path.string());
  std::vector<Strings> expected;
  for (const char* pd : {"0.3", "0.6"}) {
    for (const char* rows : {"1", "2", "3"}) {
      for (const char* spacing : {"0", "5"}) expected.push_back({pd, rows, spacing});
    }
  }
  CHECK(table(e, {"pd", "rows", "spacing"}) == expected);
  CHECK(e.swept_keys == Strings{"pd", "rows", "spacing"});
}

TEST_CASE("experiment: sweep blocks concatenate in file order", "[experiment]") {
  TempDir dir;
  const fs::path path = dir.work() / "b.ini";
  write_text(path, std::string(kHeader) +
                       "[scenario]\nspacing = 4\n"
                       "[sweep.zeta]\nrows = 1, 2\n"
                       "[sweep.alpha]\npd = 0.5\nspacing = 1, 2, 3\n"
                       "[sweep]\ncols = 7\n");
  const Experiment e = load_experiment(path.string());
  const std::vector<Strings> expected = {
      {"1", "4", "<unset>", "<unset>"}, {"2", "4", "<unset>", "<unset>"},                                 // zeta
      {"<unset>", "1", "0.5", "<unset>"}, {"<unset>", "2", "0.5", "<unset>"}, {"<unset>", "3", "0.5", "<unset>"},  // alpha
      {"<unset>", "4", "<unset>", "7"},                                                                 // [sweep]
  };
  CHECK(table(e, {"rows", "spacing", "pd", "cols"}) == expected);
  CHECK(e.swept_keys == Strings{"rows", "pd", "spacing", "cols"});
}

TEST_CASE("experiment: ties copy the swept value point by point", "[experiment]") {
  TempDir dir;
  const fs::path path = dir.work() / "t.ini";
  write_text(path, std::string(kHeader) + "[scenario]\ncols = 9\n[sweep]\nrows = 2:1:4\ncols = @rows\nspacing = 0.5, 1\n");
  const Experiment e = load_experiment(path.string());
  const std::vector<Strings> expected = {{"2", "2", "0.5"}, {"2", "2", "1"}, {"3", "3", "0.5"},
                                         {"3", "3", "1"},   {"4", "4", "0.5"}, {"4", "4", "1"}};
  CHECK(table(e, {"rows", "cols", "spacing"}) == expected);
  CHECK(e.swept_keys == Strings{"rows", "spacing"});  // a tie is not a sweep axis
}

TEST_CASE("experiment: a repeated key, section or sweep value is one error with its line numbers", "[experiment]") {
  // Boost's parser keeps the last of each without a word (issue 47): 82 points instead of 41.
  const auto message = [](const std::string& text) {
    return input_error_message([&] { parse_experiment("dup.ini", text); });
  };
  CHECK(message("scenario = grid\ntrials = 4\nalgorithm = bp\ntrials = 5\n") ==
        "dup.ini:4: 'trials' is set again (first at line 2)");
  CHECK(message("scenario = grid\ntrials = 4\nalgorithm = bp\n[scenario]\npd = 0.5\n\npd = 0.6\n") ==
        "dup.ini:7: 'scenario.pd' is set again (first at line 5)");
  CHECK(message("scenario = grid\ntrials = 4\nalgorithm = bp\n[scenario]\npd = 0.5\n[sweep]\nspacing = 1\n[scenario]\n") ==
        "dup.ini:8: section [scenario] is opened again (first at line 4)");
  CHECK(message("scenario = grid\ntrials = 4\nalgorithm = bp\n[sweep]\nspacing = 1:1:2\nspacing = 1:1:2\n") ==
        "dup.ini:6: 'sweep.spacing' is set again (first at line 5)");
  CHECK(message("scenario = grid\ntrials = 4\nalgorithm = bp\n[sweep]\nspacing = 0, 0.5, 1, 0.5\n") ==
        "dup.ini:5: 'sweep.spacing' sweeps the value 0.5 twice (its values 2 and 4)");
  // algorithm and reference take one SPEC per line; the same value in two blocks is two points.
  const Experiment e = parse_experiment("ok.ini", "scenario = grid\ntrials = 4\nalgorithm = bp\nalgorithm = exact\n"
                                                  "[sweep]\nspacing = 1, 2\n[sweep.more]\nspacing = 1, 2\n");
  CHECK(e.algorithms == Strings{"bp", "exact"});
  CHECK(e.points.size() == 4);
}

TEST_CASE("experiment: errors throw InputError naming the file", "[experiment]") {
  TempDir dir;
  const fs::path path = dir.work() / "bad_experiment.ini";
  const auto error_for = [&](const std::string& text) {
    write_text(path, text);
    const std::string message = input_error_message([&] { load_experiment(path.string()); });
    CHECK(contains(message, path.string()));
    return message;
  };
  SECTION("missing file") {
    const std::string missing = (dir.work() / "absent.ini").string();
    CHECK(contains(input_error_message([&] { load_experiment(missing); }), missing));
  }
  SECTION("a line without '='") {
    CHECK(contains(error_for(std::string(kHeader) + "just words\n"), "just words"));
  }
  SECTION("unknown top-level key") {
    CHECK(contains(error_for(std::string(kHeader) + "threads = 4\n"), "threads"));
  }
  SECTION("unknown section") {
    CHECK(contains(error_for(std::string(kHeader) + "[output]\nfolder = x\n"), "output.folder"));
  }
  SECTION("missing scenario") {
    CHECK(contains(error_for("trials = 4\nalgorithm = bp\n"), "scenario"));
  }
  SECTION("missing trials") {
    CHECK(contains(error_for("scenario = grid\nalgorithm = bp\n"), "trials"));
  }
  SECTION("no algorithm and no reference") {
    CHECK(contains(error_for("scenario = grid\ntrials = 4\n"), "algorithm"));
  }
  SECTION("trials = 0") {
    CHECK(contains(error_for("scenario = grid\ntrials = 0\nalgorithm = bp\n"), "trials"));
  }
  SECTION("trials not an integer") {
    CHECK(contains(error_for("scenario = grid\ntrials = 2.5\nalgorithm = bp\n"), "trials"));
  }
  SECTION("negative seed") {
    CHECK(contains(error_for(std::string(kHeader) + "seed = -1\n"), "seed"));
  }
  SECTION("seed not a number") {
    CHECK(contains(error_for(std::string(kHeader) + "seed = abc\n"), "seed"));
  }
  SECTION("range with zero step") {
    CHECK(contains(error_for(std::string(kHeader) + "[sweep]\nspacing = 0:0:10\n"), "0:0:10"));
  }
  SECTION("range with two parts") {
    CHECK(contains(error_for(std::string(kHeader) + "[sweep]\nspacing = 0:1\n"), "0:1"));
  }
  SECTION("empty sweep value") {
    CHECK(contains(error_for(std::string(kHeader) + "[sweep]\nspacing =\n"), "spacing"));
  }
  SECTION("tie to a parameter no block sweeps") {
    CHECK(contains(error_for(std::string(kHeader) + "[scenario]\nrows = 2\n[sweep]\nspacing = 1, 2\ncols = @rows\n"),
                   "@rows"));
  }
  SECTION("tie to a parameter another block sweeps") {
    CHECK(contains(error_for(std::string(kHeader) + "[sweep.a]\nrows = 1, 2\n[sweep.b]\nspacing = 1\ncols = @rows\n"),
                   "@rows"));
  }
  SECTION("a block of ties only") {
    CHECK(contains(error_for(std::string(kHeader) + "[sweep]\ncols = @rows\n"), "@rows"));
  }
  SECTION("a sweep of more than 10^5 points, counted before any is made") {
    // 10^12 points in one block (two ranges of 10^6), and 2 · 60 000 over two blocks.
    CHECK(contains(error_for(std::string(kHeader) + "[sweep]\nrows = 1:1:1000000\ncols = 1:1:1000000\n"),
                   "the sweep has 1e+12 points, more than 100000"));
    CHECK(contains(error_for(std::string(kHeader) + "[sweep.a]\nrows = 1:1:60000\n[sweep.b]\ncols = 1:1:60000\n"),
                   "the sweep has 1.2e+05 points"));
  }
}

}  // namespace DABENCH_TEST_FILE
