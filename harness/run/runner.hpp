#pragma once
// `dabench run`: turns an experiment into work items (point, trial) — for the kinds other than
// single scan, units (point, trial, algorithm) — runs them on OpenMP threads in the order of
// harness/run/work_queue.hpp, and writes trials.csv (in item order, as items finish), the kind's per-item files
// (multi-scan: targets.csv; tracking: tracks.csv, measurements.csv, and iterations.csv when
// the experiment records iterations), summary.csv and meta.json.
//
// Every item (every unit) draws its scenario from its own counter-based stream (seed, point,
// trial) and runs the reference and every algorithm (its algorithm) on that same draw, so rows
// are bit-identical (timings aside) for any thread count, schedule or resume history. Everything that can be wrong with the
// experiment (scenario, parameters of every point, algorithm SPECs, output folder) is checked
// before the first trial runs.
//
// Under mpirun (RunOptions::transport), every rank reads the experiment; rank 0 opens the
// output folder, hands chunks of units to its own threads and, on request, to the other ranks'
// threads, and writes every rank's rows through the same ordered writer, so the files are
// those of a single process. A worker rank writes nothing.
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>
#include <string>

namespace dabench {

class MpiTransport;

// `--shard K/N`: this process runs shard K (1-based) of N (harness/run/run_plan.hpp says which
// items) into its own folder; `dabench merge` joins the N folders.
struct Shard {
  int index = 1;
  int count = 1;
};

struct RunOptions {
  std::string experiment_path;
  std::optional<std::int64_t> trials;   // overrides the file's `trials`
  std::optional<int> threads;           // default: OpenMP's default (all cores)
  std::optional<std::uint64_t> seed;    // overrides the file's `seed`
  std::optional<std::string> output;    // overrides the file's `output`
  bool resume = false;                  // finish the run in the output folder
  bool force = false;                   // discard the run in the output folder
  std::optional<Shard> shard;           // run one shard (default output: the file's + "-shard-K-of-N")
  // A previous run of the same plan (its folder): its per-unit times order the units longest
  // first (harness/run/work_queue.hpp; not for single scan, whose items run in order).
  std::optional<std::string> costs_from;
  std::string command_line;             // recorded in meta.json
  const MpiTransport* transport = nullptr;  // under mpirun: this rank's link to the others
  // For a caller's own progress display (the Python module's): the items done and the items of
  // this process, called as blocks finish, from any of the run's threads. The progress line on
  // stderr (drawn when stderr is a terminal) is left out when draw_progress is false.
  std::function<void(long long done, long long total)> on_progress;
  bool draw_progress = true;
};

struct RunOutcome {
  long long items_total = 0;            // of this process: the plan's, or its shard's
  long long items_written = 0;
  bool interrupted = false;
  std::vector<std::string> item_files;  // written beside trials.csv (e.g. targets.csv)
  std::string output;
  bool worker_rank = false;             // an MPI rank other than 0: rank 0 reports the run
  // Set when a write failed (disk full, I/O error): "FILE: write failed (reason)". The run then
  // stopped there, its files hold whole rows of the items before, and --resume finishes it.
  std::string write_error;
};

// Throws InputError for anything wrong before the run starts.
RunOutcome run_experiment(const RunOptions& options);

// Stops the run in progress as Ctrl-C does (the trials in flight finish; --resume completes it),
// for a caller that runs run_experiment on another thread. No effect when no run is in progress.
void interrupt_run();

}  // namespace dabench
