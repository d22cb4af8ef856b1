// dabench list: the registered algorithms, trackers and scenarios with their parameters and
// defaults, and the experiment files.
#include <algorithm>
#include <filesystem>
#include <set>

#include <fmt/format.h>

#include "apps/cli/command.hpp"
#include "harness/core/errors.hpp"
#include "harness/core/experiment.hpp"
#include "harness/core/input_file.hpp"
#include "harness/core/params.hpp"
#include "harness/multi_scan/registry.hpp"
#include "harness/single_scan/registry.hpp"
#include "harness/tbd/registry.hpp"
#include "harness/tracking/metrics.hpp"
#include "harness/tracking/registry.hpp"

namespace dabench::cli {

namespace {

namespace fs = std::filesystem;

fs::path experiments_folder() {
  if (fs::is_directory("experiments")) return "experiments";
  return fs::path(DABENCH_SOURCE_DIR) / "experiments";
}

// A registry's entries: each section's columns are as wide as its longest name and key, so no
// entry pushes its value.
template <class Registry>
void describe(std::string& out, const Registry& registry) {
  if (registry.entries().empty()) out += "  (none registered)\n";
  std::size_t name_width = 10, key_width = 16;
  for (const auto& [name, entry] : registry.entries()) {
    name_width = std::max(name_width, name.size());
    for (const auto& param : entry.defaults) key_width = std::max(key_width, param.key.size());
  }
  for (const auto& [name, entry] : registry.entries()) {
    out += fmt::format("  {:<{}} {}\n", name, name_width, entry.summary);
    for (const auto& param : entry.defaults) {
      out += fmt::format("      {:<{}} = {:<10} {}\n", param.key, key_width, ParamList::format(param), param.doc);
    }
  }
}

int run_list(const Invocation& invocation) {
  if (!parse_command(kListCommand, po::options_description("list options"), po::positional_options_description(),
                     invocation)) {
    return 0;
  }
  std::string out;
  out += "Algorithms (SPEC = name or name:key=value,...):\n";
  describe(out, single_scan_algorithm_registry());
  out += "\nMulti-scan algorithms (for multi-scan scenarios):\n";
  describe(out, multi_scan_algorithm_registry());
  out += "\nTrackers (for tracking scenarios):\n";
  describe(out, tracking_tracker_registry());
  out += "\nTrack-before-detect trackers (for track-before-detect scenarios; frame by frame):\n";
  describe(out, tbd_tracker_registry());
  out += "\nScenarios (parameters settable in an experiment's [scenario] and [sweep] sections):\n";
  describe(out, single_scan_scenario_registry());
  out += "\nMulti-scan scenarios (run multi-scan algorithms; metrics against the truth):\n";
  describe(out, multi_scan_scenario_registry());
  out += "\nTracking scenarios (whole runs of K scans, for trackers):\n";
  describe(out, tracking_scenario_registry());
  out += "  experiment [metrics] of tracking scenarios (harness/tracking/metrics.hpp):\n";
  TrackingMetricsOptions tracking_metrics;
  ParamList tracking_metric_params;
  tracking_metrics.bind(tracking_metric_params);
  for (const auto& param : tracking_metric_params.entries())
    out += fmt::format("      {:<16} = {:<10} {}\n", param.key, ParamList::format(param), param.doc);
  out += "\nTrack-before-detect scenarios (K image frames of J data cells; experiment [metrics]: GOSPA c, p, alpha):\n";
  describe(out, tbd_scenario_registry());
  const fs::path folder = experiments_folder();
  out += fmt::format("\nExperiments (in {}):\n", folder.string());
  std::set<fs::path> files;
  std::error_code error;
  for (const auto& file : fs::directory_iterator(folder, error)) {
    if (file.path().extension() == ".ini") files.insert(file.path());
  }
  for (const auto& file : files) {
    std::string description;
    try {
      description = load_experiment(file.string()).description;
    } catch (const InputError& problem) {
      description = fmt::format("(unreadable: {})", printable(problem.what()));
    }
    out += fmt::format("  {:<28} {}\n", file.filename().string(), description);
  }
  print_stdout(out);
  return 0;
}

}  // namespace

const Command kListCommand{
    "list", "dabench list",
    "Prints the algorithms and trackers with their parameters and defaults, the scenarios and the\n"
    "experiment files.\n",
    run_list};

}  // namespace dabench::cli
