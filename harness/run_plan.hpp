#pragma once
// A fully checked experiment: the resolved parameters of every sweep point and the algorithm
// SPECs to run, built before any output is written. The scenario's kind decides the kind of
// run: a single-scan scenario runs single-scan algorithms against a reference; a multi-scan
// scenario runs multi-scan algorithms, measured against the scenario's truth (no reference),
// and also writes targets.csv (one row per target).
#include <cstdint>
#include <string>
#include <vector>

#include "harness/experiment.hpp"
#include "harness/runner.hpp"

namespace dabench {

struct RunPlan {
  Experiment experiment;
  std::vector<std::vector<KeyValue>> point_settings;  // as written (fixed + swept)
  std::vector<std::vector<KeyValue>> point_params;    // every scenario parameter, effective value
  std::vector<std::string> specs;                     // references first, then algorithms
  int references = 0;                                 // how many leading specs are references
  bool multi_scan = false;                            // the scenario is a multi-scan scenario
  std::int64_t trials = 0;
  std::uint64_t seed = 0;
  int threads = 1;
  std::string output;

  long long items() const { return static_cast<long long>(point_params.size()) * trials; }
  const std::vector<std::string>& metric_columns() const;  // of trials.csv, by kind
  std::string trials_header() const;
  std::string targets_header() const;  // multi-scan runs: point, parameters, trial, seed, algorithm, target, hpd, entropy
  std::string fingerprint() const;  // identifies the run for --resume
  // The leading fields of every row, precomputed once per run: "point,param values" per point,
  // and the CSV-quoted SPEC per algorithm.
  std::vector<std::string> point_row_prefixes() const;
  std::vector<std::string> spec_fields() const;
};

RunPlan make_run_plan(const RunOptions& options);  // throws InputError

}  // namespace dabench
