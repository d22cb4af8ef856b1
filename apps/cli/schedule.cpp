// dabench schedule: a finished run's predicted wall time on W workers, simulated over its own
// per-unit times (harness/run/schedule_simulation.hpp).
#include <algorithm>
#include <cstdlib>
#include <numeric>

#include <fmt/format.h>

#include "apps/cli/command.hpp"
#include "harness/core/errors.hpp"
#include "harness/run/run_meta.hpp"
#include "harness/run/schedule_simulation.hpp"

namespace dabench::cli {

namespace {

std::vector<long long> parse_workers(const std::string& text) {
  std::vector<long long> workers;
  for (const std::string& word : comma_list(text, "schedule", "--workers")) {
    char* stop = nullptr;
    const long long value = std::strtoll(word.c_str(), &stop, 10);
    if (*stop != '\0' || value < 1 || value > 1000000) {
      throw InputError(fmt::format("schedule: --workers '{}' must be a list of counts from 1 to 1000000, e.g. 16,64,256", text));
    }
    workers.push_back(value);
  }
  return workers;
}

int run_schedule(const Invocation& invocation) {
  po::options_description options("schedule options");
  std::string folder, workers_text, format;
  long long trials = -1;
  options.add_options()
      ("run", po::value(&folder)->required(), "folder of a finished run")
      ("trials", po::value(&trials), "only the first N trials of each point")
      ("workers", po::value(&workers_text)->default_value("1,2,16,64,256"), "worker counts, comma-separated")
      ("format", po::value(&format)->default_value("table"), "table or csv");
  po::positional_options_description positional;
  positional.add("run", 1);
  const auto parsed = parse_command(kScheduleCommand, options, positional, invocation);
  if (!parsed) return 0;
  if (format != "table" && format != "csv") throw InputError(fmt::format("schedule: --format must be table or csv, not '{}'", format));
  const std::vector<long long> workers = parse_workers(workers_text);
  if (parsed->count("trials") && trials < 1) throw InputError(fmt::format("schedule: --trials {} must be >= 1", trials));
  require_complete_run(folder, "schedule");
  const RunCosts costs = read_run_costs(folder, "schedule", trials);
  const double total = std::accumulate(costs.unit_seconds.begin(), costs.unit_seconds.end(), 0.0);
  const double longest = *std::max_element(costs.unit_seconds.begin(), costs.unit_seconds.end());
  std::string out;
  if (format == "csv") {
    out = "workers,units,total_s,longest_unit_s,bound_s,wall_s,work_fraction,blocks_wall_s,blocks_work_fraction,"
          "known_wall_s,known_work_fraction\n";
  } else {
    out = fmt::format("{}{}: {} units ({} items x {}), {:.4g} s of algorithm time, longest unit {:.4g} s\n"
                      "{:>8} {:>11} {:>11} {:>9} {:>10} {:>15} {:>10} {:>14}\n",
                      costs.source, costs.from_means ? " (means per point and algorithm)" : "", costs.unit_seconds.size(),
                      costs.items(), costs.parts, total, longest, "workers",
                      "bound_s", "wall_s", "fraction", "wall/bound", "8-item blocks_s", "fraction", "costs known_s");
  }
  for (const long long w : workers) {
    const double bound = schedule_lower_bound(costs, w);
    const SchedulePrediction now = simulate_work_queue(costs, w);
    const SchedulePrediction blocks = simulate_item_blocks(costs, w);
    const SchedulePrediction known = simulate_work_queue(costs, w, true);
    if (format == "csv") {
      out += fmt::format("{},{},{},{},{},{},{},{},{},{},{}\n", w, costs.unit_seconds.size(), total, longest, bound,
                         now.wall_seconds, now.work_fraction, blocks.wall_seconds, blocks.work_fraction, known.wall_seconds,
                         known.work_fraction);
    } else {
      out += fmt::format("{:>8} {:>11.4g} {:>11.4g} {:>9.3f} {:>10.3f} {:>15.4g} {:>10.3f} {:>14.4g}\n", w, bound,
                         now.wall_seconds, now.work_fraction, now.wall_seconds / bound, blocks.wall_seconds,
                         blocks.work_fraction, known.wall_seconds);
    }
  }
  print_stdout(out);
  return 0;
}

}  // namespace

const Command kScheduleCommand{
    "schedule", "dabench schedule RUN_DIR [--workers 1,2,16,64,256] [--trials N] [--format table|csv]",
    "Predicts the wall time of a finished run's work on W workers (threads of all ranks), simulated\n"
    "over the run's own per-unit times: the runner's work queue, the 8-item blocks it replaced, and\n"
    "the queue of a rerun with --costs-from. The times are those of the time column of the run's kind\n"
    "(meta.json's scenario says which) in trials.csv (or a track-before-detect report's runs.csv, or\n"
    "summary.csv's means per point and algorithm), the algorithms' alone: drawing, metrics and\n"
    "writing come on top. With --trials N: the first N trials of each point.\n",
    run_schedule};

}  // namespace dabench::cli
