// dabench compare: a paired comparison of two algorithms on the same trials (one run), or of
// one algorithm in two runs of the same plan (harness/run/paired_comparison.hpp).
#include <fmt/format.h>

#include "apps/cli/command.hpp"
#include "harness/core/errors.hpp"
#include "harness/run/paired_comparison.hpp"

namespace dabench::cli {

namespace {

int run_compare(const Invocation& invocation) {
  po::options_description options("compare options");
  std::vector<std::string> runs;
  std::string algorithms, metrics, format;
  options.add_options()
      ("runs", po::value(&runs)->multitoken(), "one run folder, or two of the same plan")
      ("algorithms", po::value(&algorithms)->required(), "A,B (one run) or A (two runs): SPECs as in trials.csv (bp:delta=1e-9,check_every=10,exact is two)")
      ("metric", po::value(&metrics), "metric columns, comma-separated (default: the kind's error and time)")
      ("format", po::value(&format)->default_value("table"), "table or csv");
  po::positional_options_description positional;
  positional.add("runs", -1);
  const auto parsed = parse_command(kCompareCommand, options, positional, invocation);
  if (!parsed) return 0;
  if (runs.empty() || runs.size() > 2) throw InputError("compare: give one run folder, or two runs of the same plan");
  if (format != "table" && format != "csv") throw InputError(fmt::format("compare: --format must be table or csv, not '{}'", format));
  CompareOptions compare;
  compare.run_a = runs[0];
  if (runs.size() == 2) compare.run_b = runs[1];
  // SPECs hold commas too ("bp:delta=1e-9,check_every=10"): an item with '=' and no ':' goes on
  // the SPEC before it.
  for (const std::string& item : comma_list(algorithms, "compare", "--algorithms")) {
    const bool continues = item.find('=') != std::string::npos && item.find(':') == std::string::npos;
    if (continues && !compare.algorithms.empty()) {
      compare.algorithms.back() += "," + item;
    } else {
      compare.algorithms.push_back(item);
    }
  }
  if (parsed->count("metric")) compare.metrics = comma_list(metrics, "compare", "--metric");
  const Comparison comparison = compare_runs(compare);
  print_stdout((format == "csv" ? comparison_csv(comparison) : comparison_table(comparison)));
  return 0;
}

}  // namespace

const Command kCompareCommand{
    "compare", "dabench compare RUN_DIR [RUN_DIR_B] --algorithms A[,B] [--metric M,...] [--format table|csv]",
    "Paired comparison on the same trials: two algorithms of one run, or one algorithm in two runs of\n"
    "the same plan (same fingerprint and seed). Per sweep point and metric (default: the kind's error\n"
    "and time): the mean paired difference A - B with its 95% t interval, the two-sided Wilcoxon\n"
    "signed-rank p-value (zeros dropped; exact up to 50 untied differences, else normal with the tie\n"
    "correction), Holm-adjusted over the points, and the share of trials where A is lower.\n",
    run_compare};

}  // namespace dabench::cli
