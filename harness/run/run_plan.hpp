#pragma once
// A fully checked experiment: the resolved parameters of every sweep point and the algorithm
// SPECs to run, built before any output is written. The scenario's kind (harness/run/problem_kind.hpp,
// one descriptor per kind in harness/run/kinds/) decides the rest: which algorithms the
// experiment may name, whether it has references (single scan: algorithms against a reference)
// or is measured against the scenario's truth, which of `iterations = true`, `beliefs = true`
// and a [metrics] section it may hold, trials.csv's metric columns and the per-item files.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "harness/core/experiment.hpp"
#include "harness/run/problem_kind.hpp"
#include "harness/run/runner.hpp"

namespace dabench {

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
  const ProblemKind* kind = nullptr;                  // the scenario's (harness/run/problem_kind.hpp)
  std::int64_t trials = 0;
  std::uint64_t seed = 0;
  int threads = 1;
  std::string output;
  std::optional<Shard> shard;  // run only this shard's items

  long long items() const { return static_cast<long long>(point_params.size()) * trials; }
  // Work units per item (harness/run/work_queue.hpp): 1 for single scan, whose algorithms share the
  // reference's marginals; one per algorithm for the other kinds, whose algorithms are independent.
  int parts() const { return kind->shares_items() ? 1 : static_cast<int>(specs.size()); }
  // The items this process runs, in item order: all of them, or its shard's. Its item `local`
  // (0-based, < shard_items()) is the plan's item global_item(local).
  long long shard_items() const;
  long long global_item(long long local) const;
  long long local_item(long long global) const;  // its inverse; -1 for another shard's item or none
  std::string shard_label() const;  // "K/N", or "" when not sharded
  const std::vector<std::string>& metric_columns() const;  // of trials.csv, by kind
  std::string trials_header() const;
  // The per-item files of this kind, in the order the writer fills them (before trials.csv).
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
