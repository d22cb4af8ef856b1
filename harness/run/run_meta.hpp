#pragma once
// meta.json of a run folder (README "Result files"): what was run — the plan, its fingerprint,
// the build — and how it ran. `dabench run` writes it at the start, while running and at the
// end; `dabench merge` writes the merged run's from its shards' records.
#include <cmath>
#include <string>
#include <vector>

#include "harness/run/run_plan.hpp"

namespace dabench {

// How the run went: the fields that differ between runs of one plan (process and host fields,
// times), beside the plan's own.
struct RunRecord {
  std::string command_line;
  std::string status;            // "running", "interrupted" or "complete"
  long long items_done = 0;      // of this folder's items (a shard's own, when sharded)
  std::string start_time;        // UTC, 2026-01-31T12:00:00Z
  std::string end_time;          // empty while running
  double wall_seconds = 0.0;
  double work_fraction = std::nan("");  // busy thread time over wall time × threads
  bool resumed = false;
  long long processes = 1;       // merged runs: the number of shards
  std::string hosts;             // host name; merged runs: the shards' distinct hosts, comma-separated
  // MPI runs (`processes` ranks): each rank's host and threads, by rank; empty otherwise.
  std::vector<std::string> rank_hosts;
  std::vector<int> rank_threads;
};

std::string run_meta_json(const RunPlan& plan, const RunRecord& record);

std::string utc_now();
std::string host_name();

}  // namespace dabench
