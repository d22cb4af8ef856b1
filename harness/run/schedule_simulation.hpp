#pragma once
// `dabench schedule`: the wall time a finished run's work would take on W workers, simulated
// from its per-unit times. The work queue of the runner itself (harness/run/work_queue.hpp) hands
// out the units in simulated time (a worker that frees first takes the next chunk; the queue
// learns each unit's time when its chunk ends, as in a run), and so does the policy it replaced:
// blocks of 8 whole items in item order. The times are the algorithms' own (trials.csv's time
// column of the run's kind, harness/run/problem_kind.hpp): the draw of the scenario, the metrics
// and the writing are not in them, so a prediction is a lower estimate of a real run's wall time.
#include <string>
#include <string_view>
#include <vector>

#include "harness/run/problem_kind.hpp"
#include "harness/run/work_queue.hpp"

namespace dabench {

// A run's work, unit by unit in unit order (harness/run/work_queue.hpp).
struct RunCosts {
  std::string source;                 // the file the times came from
  const ProblemKind* kind = nullptr;  // the run's (meta.json's scenario)
  bool from_means = false;            // summary.csv: per point and algorithm means, not per trial
  int parts = 1;                      // units per item
  int points = 1;
  std::vector<int> item_points;       // per item, its point
  std::vector<double> unit_seconds;   // per unit
  long long items() const { return static_cast<long long>(item_points.size()); }
  // One unit per item (single scan: an item's algorithms share the reference), run in order.
  bool shared_items() const { return kind != nullptr && kind->shares_items(); }
};

// The times of the run's kind's time column (meta.json's scenario says the kind) in
// FOLDER/trials.csv, else FOLDER/runs.csv (the track-before-detect reports' per-run digest of the
// same columns), else FOLDER/summary.csv (a committed study that keeps only its summary: every
// trial of a point then costs the point's mean time of each algorithm, the columns' `_mean`). An
// item is the rows of one (point, trial), in file order, items in (point, trial) order; a missing
// time (a skipped row) counts 0. With `trials`, only the items of trials < trials are kept.
// InputError (one line, naming `command`) for a folder without any or without meta.json, a file
// without the columns, or items of unequal row counts.
RunCosts read_run_costs(const std::string& folder, std::string_view command, long long trials = -1);

struct SchedulePrediction {
  double wall_seconds = 0.0;
  double work_fraction = 0.0;  // busy time over wall time × workers
};

// The runner's queue (single scan: in order; the other kinds: longest first) on `workers`; with
// `known_costs`, as `dabench run --costs-from` a run of the same plan orders it (each unit's own
// time known in advance).
SchedulePrediction simulate_work_queue(const RunCosts& costs, long long workers, bool known_costs = false);
// The replaced policy: blocks of 8 items (all of an item's units together) in item order.
SchedulePrediction simulate_item_blocks(const RunCosts& costs, long long workers);
// No schedule beats max(total / workers, the longest unit).
double schedule_lower_bound(const RunCosts& costs, long long workers);

}  // namespace dabench
