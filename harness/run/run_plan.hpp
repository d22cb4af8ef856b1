#pragma once
// A fully checked experiment: the resolved parameters of every sweep point and the algorithm
// SPECs to run, built before any output is written. The scenario's kind decides the kind of
// run: a single-scan scenario runs single-scan algorithms against a reference; a multi-scan
// scenario runs multi-scan algorithms, measured against the scenario's truth (no reference),
// and also writes targets.csv (one row per target); a tracking scenario runs trackers against
// the truth and also writes tracks.csv and measurements.csv (harness/run/tracking_execution.hpp),
// and iterations.csv when the experiment says `iterations = true` (an error for other kinds);
// a track-before-detect scenario runs TBD trackers frame by frame and also writes steps.csv,
// estimates.csv and frames.csv (harness/run/tbd_execution.hpp). The experiment's [metrics]
// lines set the kind's metric options (track-before-detect and tracking; an error for other kinds).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "harness/core/experiment.hpp"
#include "harness/run/runner.hpp"

namespace dabench {

enum class RunKind { single_scan, multi_scan, tracking, tbd };

// A per-item file beside trials.csv: its rows start with the point's prefix then `trial`, in
// item order, so --resume can trim it to the items trials.csv holds.
struct ItemFile {
  std::string name;    // e.g. "targets.csv"
  std::string header;  // with its newline
};

// Shards are made of blocks of items: shard K of N runs blocks K − 1, K − 1 + N, K − 1 + 2N, ...
// (round robin, so every shard gets a share of each sweep point's cost). Inside a process, the
// order units run in is harness/run/work_queue.hpp's.
constexpr long long kItemsPerBlock = 8;

struct RunPlan {
  Experiment experiment;
  std::vector<std::vector<KeyValue>> point_settings;  // as written (fixed + swept)
  std::vector<std::vector<KeyValue>> point_params;    // every scenario parameter, effective value
  std::vector<std::string> specs;                     // references first, then algorithms
  int references = 0;                                 // how many leading specs are references
  RunKind kind = RunKind::single_scan;                // from the scenario's registry
  std::int64_t trials = 0;
  std::uint64_t seed = 0;
  int threads = 1;
  std::string output;
  std::optional<Shard> shard;  // run only this shard's items

  long long items() const { return static_cast<long long>(point_params.size()) * trials; }
  // Work units per item (harness/run/work_queue.hpp): 1 for single scan, whose algorithms share the
  // reference's marginals; one per algorithm for the other kinds, whose algorithms are independent.
  int parts() const { return kind == RunKind::single_scan ? 1 : static_cast<int>(specs.size()); }
  // The items this process runs, in item order: all of them, or its shard's. Its item `local`
  // (0-based, < shard_items()) is the plan's item global_item(local).
  long long shard_items() const;
  long long global_item(long long local) const;
  long long local_item(long long global) const;  // its inverse; -1 for another shard's item or none
  std::string shard_label() const;  // "K/N", or "" when not sharded
  const std::vector<std::string>& metric_columns() const;  // of trials.csv, by kind
  std::string trials_header() const;
  // The per-item files of this kind, in the order the writer fills them (before trials.csv):
  // multi-scan: targets.csv; tracking: tracks.csv, measurements.csv and, with
  // `iterations = true`, iterations.csv; track-before-detect: steps.csv, estimates.csv, frames.csv.
  std::vector<ItemFile> item_files() const;
  // The files a run of this plan writes: trials.csv, summary.csv, meta.json and item_files().
  std::vector<std::string> output_files() const;
  std::string fingerprint() const;  // identifies the run for --resume
  // The leading fields of every row, precomputed once per run: "point,param values" per point,
  // and the CSV-quoted SPEC per algorithm.
  std::vector<std::string> point_row_prefixes() const;
  std::vector<std::string> spec_fields() const;
};

RunPlan make_run_plan(const RunOptions& options);  // throws InputError
// The same for an experiment already read (options.experiment_path is not used).
RunPlan make_run_plan(Experiment experiment, const RunOptions& options);

}  // namespace dabench
