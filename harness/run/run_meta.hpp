#pragma once
// meta.json of a run folder (docs/result-files.md): what was run — the plan, its fingerprint,
// the build — and how it ran. `dabench run` writes it at the start, while running and at the
// end; `dabench merge` writes the merged run's from its shards' records.
#include <cmath>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "harness/run/run_plan.hpp"

namespace dabench {

// The build that wrote a run's rows, as meta.json records it.
struct RecordedBuild {
  std::string version, git_commit;
  std::string source_modified;  // JSON: true, false or null (unknown)
  std::string compiler, flags, build_type;

  bool operator==(const RecordedBuild&) const = default;
  std::string describe() const;  // "dabench 0.1.0 (git abc1234, modified source), gcc ... -O2 Release"
};
RecordedBuild this_build();

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
  // Merged runs: the shards' build (this_build() otherwise); with `merge --allow-mixed` and
  // shards of different builds, each shard's, in shard order.
  std::optional<RecordedBuild> build;
  std::vector<RecordedBuild> mixed_builds;
};

std::string run_meta_json(const RunPlan& plan, const RunRecord& record);

// Throws InputError of one line when FOLDER/meta.json says the run is not complete (a folder
// without meta.json or without a status, e.g. published data, passes): `command` refuses a run that is still running,
// was killed or interrupted, whose numbers would silently cover only some trials.
void require_complete_run(const std::string& folder, std::string_view command);

// The problem kind of the run in FOLDER: the kind whose registry holds meta.json's scenario.
// InputError of one line, naming `command`, for a folder without meta.json or a scenario this
// build does not know.
const ProblemKind& recorded_kind(const std::string& folder, std::string_view command);

std::string utc_now();
std::string host_name();

}  // namespace dabench
