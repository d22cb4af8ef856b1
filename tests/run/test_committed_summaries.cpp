// Every committed run that keeps its trials.csv (results/**/trials.csv beside summary.csv and
// meta.json) has the summary.csv that the summariser writes from it, byte for byte: a hand-edited
// summary, or one left from another build's summariser, fails here, whatever the REPORTs print
// (results/SHA256SUMS guards the bytes; this, that they are what the trials give).
#include <catch2/catch.hpp>

#include <filesystem>
#include <set>
#include <string>

#include "harness/core/summary.hpp"
#include "harness/run/problem_kind.hpp"
#include "harness/run/run_meta.hpp"
#include "tests/support/cli_runner.hpp"

namespace DABENCH_TEST_FILE {

namespace fs = std::filesystem;
using dabench::test::cli::read_text;
using dabench::test::cli::TempDir;

std::set<fs::path> committed_runs_with_trials() {
  std::set<fs::path> folders;
  for (const auto& entry : fs::recursive_directory_iterator(fs::path(DABENCH_SOURCE_DIR) / "results")) {
    const fs::path folder = entry.path().parent_path();
    if (entry.path().filename() == "trials.csv" && fs::is_regular_file(folder / "summary.csv") &&
        fs::is_regular_file(folder / "meta.json")) {
      folders.insert(folder);
    }
  }
  return folders;
}

TEST_CASE("committed runs: summary.csv is what the summariser writes from trials.csv", "[run][summary]") {
  const std::set<fs::path> folders = committed_runs_with_trials();
  // results/multiscan (10 runs), results/jdtvb (8), results/cluster (3) keep their trials.
  CHECK(folders.size() >= 20);
  TempDir dir;
  for (const fs::path& folder : folders) {
    INFO(folder.string());
    const dabench::ProblemKind& kind = dabench::recorded_kind(folder.string(), "test");
    const fs::path summary = dir.io() / "summary.csv";
    dabench::write_summary((folder / "trials.csv").string(), summary.string(), kind.metric_columns());
    CHECK(read_text(summary) == read_text(folder / "summary.csv"));
  }
}

}  // namespace DABENCH_TEST_FILE
