#pragma once
// The output folder of a run: refuses to mix runs, and prepares trials.csv, the kind's per-item
// files (RunPlan::item_files: targets.csv, tracks.csv, ...) and checksums.csv for a fresh start
// (--force or a new folder) or for --resume (keeps the whole items already written and verified).
#include <cstdio>
#include <string>
#include <vector>

#include "harness/run/run_plan.hpp"

namespace dabench {

// The files a run appends to, in the ordered writer's order: the kind's per-item files
// (RunPlan::item_files), trials.csv, then checksums.csv (harness/run/row_checksums.hpp).
struct OpenedRun {
  std::vector<std::FILE*> files;  // unbuffered, positioned at the end
  std::vector<std::string> names; // of files but the last (checksums.csv)
  long long items_done = 0;       // whole items already written and verified
  bool resumed = false;
};

// A fresh run (a new folder, or --force) creates the files with their headers, after writing
// `initial_meta` to meta.json. --resume checks meta.json's fingerprint and shard, verifies every
// recorded row against checksums.csv (InputError naming the first row that differs) and keeps
// the whole items of the verified rows (of a shard: its own), trimming each file to them.
OpenedRun open_run_files(const RunPlan& plan, bool resume, bool force, const std::string& initial_meta);

// Every file name a run of any kind writes into its folder (RunPlan::output_files of every kind
// and option). A fresh run (--force, or merge --force) removes those of them its own plan does
// not write, so that no result file of an earlier experiment stays beside the new run; files
// dabench never writes (a study's plots and digests) are left where they are.
const std::vector<std::string>& run_file_names();
void remove_other_run_files(const RunPlan& plan);  // throws WriteError when one cannot be removed

std::string trials_path(const RunPlan& plan);
std::string summary_path(const RunPlan& plan);
std::string meta_path(const RunPlan& plan);

}  // namespace dabench
