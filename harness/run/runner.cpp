#include "harness/run/runner.hpp"

#include <omp.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cmath>
#include <filesystem>
#include <memory>

#include <fmt/format.h>

#include "harness/core/atomic_file.hpp"
#include "harness/core/csv.hpp"
#include "harness/core/errors.hpp"
#include "harness/core/ordered_writer.hpp"
#include "harness/core/progress.hpp"
#include "harness/core/row_fields.hpp"
#include "harness/core/summary.hpp"
#include "harness/multi_scan/registry.hpp"
#include "harness/run/multi_scan_execution.hpp"
#include "harness/run/run_folder.hpp"
#include "harness/run/run_meta.hpp"
#include "harness/run/run_plan.hpp"
#include "harness/run/single_scan_execution.hpp"
#include "harness/run/tbd_execution.hpp"
#include "harness/run/tracking_execution.hpp"
#include "harness/single_scan/marginal_errors.hpp"
#include "harness/single_scan/registry.hpp"
#include "harness/tbd/registry.hpp"
#include "harness/tracking/registry.hpp"

namespace dabench {

const std::vector<std::string>& single_scan_metric_columns() {
  static const std::vector<std::string> columns = {"n_targets", "n_measurements", "max_error", "mean_error",
                                                   "time_us",   "iterations",     "converged", "w_star"};
  return columns;
}

const std::vector<std::string>& multi_scan_metric_columns() {
  static const std::vector<std::string> columns = {
      "n_targets", "n_scans",    "n_measurements",    "mean_hpd", "max_hpd",       "mean_entropy",
      "time_us",   "iterations", "converged",         "line_search_steps", "residual", "inner_residual"};
  return columns;
}

const std::vector<std::string>& tracking_metric_columns() {
  static const std::vector<std::string> columns = {
      "nvt",          "tpd",          "nft",      "false_tracks", "ghost_tracks", "broken_targets", "ttl_scans",
      "aee_range_km", "aee_bearing_mrad", "mospa_km", "tet_s",        "iterations",   "converged",      "free_energy"};
  return columns;
}

const std::vector<std::string>& tracking_iteration_metric_columns() {
  static const std::vector<std::string> columns = {"nvt",          "tpd",          "nft",          "false_tracks",
                                                   "ghost_tracks", "broken_targets", "ttl_scans", "aee_range_km",
                                                   "aee_bearing_mrad", "mospa_km", "free_energy"};
  return columns;
}

const std::vector<std::string>& tbd_metric_columns() {
  static const std::vector<std::string> columns = {"n_steps",   "gospa",     "gospa_p2",     "localisation",
                                                   "missed",    "false",     "n_objects",    "n_estimates",
                                                   "step_time_us", "iterations", "converged"};
  return columns;
}

namespace {

using Clock = std::chrono::steady_clock;

volatile std::sig_atomic_t g_interrupted = 0;
extern "C" void on_interrupt(int) { g_interrupted = 1; }

// Runs blocks first_block..total_blocks−1 of this process's items (RunPlan::shard_items, in
// blocks of kItemsPerBlock) on OpenMP threads (each thread with its own worker) and hands each
// block's texts to the ordered writer; returns the threads' busy seconds.
template <class Execution>
double run_blocks(const Execution& execution, const RunPlan& plan, OrderedWriter& writer, ProgressLine& progress,
                  long long first_block, long long skip_in_first, std::atomic<long long>& items_finished) {
  const long long total_items = plan.shard_items();
  const int threads = plan.threads;
  const long long total_blocks = (total_items + kItemsPerBlock - 1) / kItemsPerBlock;
  double busy_seconds = 0.0;
#pragma omp parallel num_threads(threads) reduction(+ : busy_seconds)
  {
    auto worker = execution.make_worker();
    const std::size_t files = worker.texts.size();
#pragma omp for schedule(dynamic, 1)
    for (long long block = first_block; block < total_blocks; ++block) {
      if (g_interrupted) continue;
      const long long begin = block * kItemsPerBlock + (block == first_block ? skip_in_first : 0);
      const long long end = std::min(total_items, (block + 1) * kItemsPerBlock);
      for (std::string& text : worker.texts) text.clear();
      for (long long item = begin; item < end; ++item) execution.run_item(worker, plan.global_item(item));
      const long long blocks_written = writer.submit(block, std::move(worker.texts));
      worker.texts = std::vector<std::string>(files);
      items_finished += end - begin;
      if (omp_get_thread_num() == 0 || blocks_written == total_blocks) progress.update(items_finished.load());
    }
    busy_seconds += worker.busy_seconds;
  }
  return busy_seconds;
}

}  // namespace

RunOutcome run_experiment(const RunOptions& options) {
  const RunPlan plan = make_run_plan(options);
  RunRecord record;
  record.command_line = options.command_line;
  record.status = "running";
  record.start_time = utc_now();
  record.hosts = host_name();
  OpenedTrials opened = open_trials_file(plan, options.resume, options.force, run_meta_json(plan, record));
  if (!opened.resumed && !plan.experiment.record_iterations) {
    // A fresh run without `iterations = true` leaves no iterations.csv of an earlier run.
    std::error_code ignored;
    std::filesystem::remove(std::filesystem::path(plan.output) / "iterations.csv", ignored);
  }
  if (!opened.resumed && !plan.experiment.record_beliefs) {
    std::error_code ignored;
    std::filesystem::remove(std::filesystem::path(plan.output) / "beliefs.csv", ignored);
  }
  std::vector<std::FILE*> files;
  for (const ItemFile& file : plan.item_files()) files.push_back(open_item_file(plan, file, opened.items_done, opened.resumed));
  files.push_back(opened.file);  // trials.csv last: the item files never hold fewer items
  record.items_done = opened.items_done;
  record.resumed = opened.resumed;
  write_file_atomically(meta_path(plan), run_meta_json(plan, record));

  const long long total_items = plan.shard_items();
  const long long first_block = opened.items_done / kItemsPerBlock;
  // Resume points are whole items; realign so block boundaries stay item multiples.
  const long long skip_in_first = opened.items_done - first_block * kItemsPerBlock;
  OrderedWriter writer(files, first_block);
  ProgressLine progress(total_items, opened.items_done, stderr_is_terminal());

  g_interrupted = 0;
  auto previous_int = std::signal(SIGINT, on_interrupt);
  auto previous_term = std::signal(SIGTERM, on_interrupt);
  const auto wall_start = Clock::now();
  std::atomic<long long> items_finished{opened.items_done};
  double busy_seconds = 0.0;
  if (plan.kind == RunKind::tracking) {
    std::vector<std::unique_ptr<TrackingScenario>> scenarios;
    const auto* entry = tracking_scenario_registry().find(plan.experiment.scenario);
    for (const auto& settings : plan.point_settings) scenarios.push_back(entry->create(settings));
    const TrackingExecution execution(plan, std::move(scenarios),
                                      make_options<TrackingMetricsOptions>(plan.experiment.metric_settings, "[metrics]"));
    busy_seconds = run_blocks(execution, plan, writer, progress, first_block, skip_in_first, items_finished);
  } else if (plan.kind == RunKind::tbd) {
    std::vector<std::unique_ptr<TbdScenario>> scenarios;
    const auto* entry = tbd_scenario_registry().find(plan.experiment.scenario);
    for (const auto& settings : plan.point_settings) scenarios.push_back(entry->create(settings));
    const TbdExecution execution(plan, std::move(scenarios),
                                 make_options<TbdMetricsOptions>(plan.experiment.metric_settings, "[metrics]"));
    busy_seconds = run_blocks(execution, plan, writer, progress, first_block, skip_in_first, items_finished);
  } else if (plan.kind == RunKind::multi_scan) {
    std::vector<std::unique_ptr<MultiScanScenario>> scenarios;
    const auto* entry = multi_scan_scenario_registry().find(plan.experiment.scenario);
    for (const auto& settings : plan.point_settings) scenarios.push_back(entry->create(settings));
    const MultiScanExecution execution(plan, std::move(scenarios));
    busy_seconds = run_blocks(execution, plan, writer, progress, first_block, skip_in_first, items_finished);
  } else {
    std::vector<std::unique_ptr<SingleScanScenario>> scenarios;
    const auto* entry = scenario_registry().find(plan.experiment.scenario);
    for (const auto& settings : plan.point_settings) scenarios.push_back(entry->create(settings));
    const SingleScanExecution execution(plan, std::move(scenarios));
    busy_seconds = run_blocks(execution, plan, writer, progress, first_block, skip_in_first, items_finished);
  }
  std::signal(SIGINT, previous_int);
  std::signal(SIGTERM, previous_term);
  progress.finish();
  const double wall_seconds = std::chrono::duration<double>(Clock::now() - wall_start).count();
  for (std::FILE* file : files) std::fclose(file);
  if (writer.failed()) throw InputError(fmt::format("{}: write failed (disk full?)", plan.output));

  RunOutcome outcome;
  outcome.items_total = total_items;
  outcome.items_written = std::min(total_items, writer.next_block() * kItemsPerBlock);
  outcome.interrupted = outcome.items_written < total_items;
  outcome.output = plan.output;
  for (const ItemFile& file : plan.item_files()) outcome.item_files.push_back(file.name);
  if (!outcome.interrupted) write_summary(trials_path(plan), summary_path(plan), plan.metric_columns());
  record.status = outcome.interrupted ? "interrupted" : "complete";
  record.items_done = outcome.items_written;
  record.end_time = utc_now();
  record.wall_seconds = wall_seconds;
  record.work_fraction = wall_seconds > 0.0 ? busy_seconds / (wall_seconds * plan.threads) : std::nan("");
  write_file_atomically(meta_path(plan), run_meta_json(plan, record));
  return outcome;
}

}  // namespace dabench
