#pragma once
// Experiment files: INI text in Boost.Program_options' config-file syntax.
//
//   name = quickstart                 # optional; defaults to the file's stem
//   description = one line for `dabench list`
//   scenario = grid
//   trials = 200                      # Monte Carlo trials per sweep point
//   seed = 1                          # master seed (uint64)
//   output = out/quickstart           # output folder (relative to the working directory)
//   reference = exact                 # SPEC the errors are measured against; more reference
//   reference = mcmcda:samples=1e7    #   lines are fallbacks, run only when the ones before
//                                     #   were skipped (e.g. a work limit)
//   algorithm = bp                    # one line per algorithm SPEC (variants allowed)
//   algorithm = bp:delta=1e-6
//   iterations = true                 # tracking only: also write iterations.csv, the metrics
//                                     #   of each recorded tracker iteration (default false)
//   beliefs = true                    # track-before-detect only: also write beliefs.csv, the
//                                     #   trackers' beliefs after trial 0's last step
//
//   [scenario]                        # fixed scenario parameters (others keep defaults)
//   rows = 2
//
//   [metrics]                         # options of the kind's metrics (track-before-detect:
//   gospa_cutoff = 2                  #   GOSPA c, p, α; tracking: gate_km, ospa_cutoff_km, ...);
//                                     #   recorded in meta.json
//
//   [sweep]                           # a full-factorial block; [sweep.NAME] adds more blocks,
//   spacing = 0:0.5:10                # whose points are concatenated in file order.
//   pd = 0.3, 0.6, 0.9                # values: a comma list or start:step:stop (inclusive);
//   cols = @rows                      # "@key" ties a parameter to another swept one.
//
// Points enumerate blocks in file order, and inside a block the first key varies slowest.
#include <cstdint>
#include <string>
#include <vector>

#include "harness/core/params.hpp"

namespace dabench {

// Sweep points, all blocks together (a range holds at most as many values). Each point is a list
// of settings checked in turn before a run starts, ~7 µs each in a Release build; at the bound
// before, 10^6, one fuzz input held ~1 GB and ran past 10 s under ASan. 10^5 is far beyond any
// committed study.
constexpr double kMaxSweepPoints = 1e5;

struct Experiment {
  std::string path;         // as given
  std::string text;         // file contents (recorded in meta.json)
  std::string name;
  std::string description;
  std::string scenario;
  std::int64_t trials = 0;
  std::uint64_t seed = 1;
  std::string output;
  std::vector<std::string> references;  // first that succeeds in a trial is the reference
  std::vector<std::string> algorithms;
  bool record_iterations = false;       // `iterations = true`: per-iteration metrics (tracking)
  bool record_beliefs = false;          // `beliefs = true`: trial 0's final beliefs (track-before-detect)
  std::vector<KeyValue> metric_settings;  // [metrics]: checked against the kind's metric options
  std::vector<std::string> swept_keys;         // parameters that some block sweeps
  std::vector<std::vector<KeyValue>> points;   // scenario settings of each point (fixed + swept)
};

// Reads and checks the file's syntax and its top-level keys. Scenario and algorithm names and
// parameters are checked later, against the registries. Throws InputError naming the file.
Experiment load_experiment(const std::string& path);
// The same from the file's text (e.g. as recorded in a run's meta.json); `path` names it.
Experiment parse_experiment(const std::string& path, std::string text);

// "0:0.5:2" → {"0", "0.5", "1", "1.5", "2"}; "1, 2,3" → {"1", "2", "3"}; throws InputError.
std::vector<std::string> expand_sweep_values(const std::string& text);

}  // namespace dabench
