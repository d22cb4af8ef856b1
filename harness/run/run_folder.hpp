#pragma once
// The output folder of a run: refuses to mix runs, and prepares trials.csv for a fresh start
// (--force or a new folder) or for --resume (keeps the whole items already written), and the
// kind's per-item files (RunPlan::item_files: targets.csv, tracks.csv, ...) likewise.
#include <cstdio>
#include <string>

#include "harness/run/run_plan.hpp"

namespace dabench {

struct OpenedTrials {
  std::FILE* file = nullptr;     // positioned at the end, ready for appending
  long long items_done = 0;      // whole items already in the file
  bool resumed = false;
};

// `initial_meta` is written to meta.json before a fresh trials.csv is created.
OpenedTrials open_trials_file(const RunPlan& plan, bool resume, bool force, const std::string& initial_meta);

// Every file name a run of any kind writes into its folder (RunPlan::output_files of every kind
// and option). A fresh run (--force, or merge --force) removes those of them its own plan does
// not write, so that no result file of an earlier experiment stays beside the new run; files
// dabench never writes (a study's plots and digests) are left where they are.
const std::vector<std::string>& run_file_names();
void remove_other_run_files(const RunPlan& plan);  // throws InputError when one cannot be removed

// A per-item file matching trials.csv's `items_done` whole items: created with its header for
// a fresh run; for a resumed one, trimmed to the rows of those items (the writer writes it
// before trials.csv, so it never holds fewer items).
std::FILE* open_item_file(const RunPlan& plan, const ItemFile& file, long long items_done, bool resumed);

std::string trials_path(const RunPlan& plan);
std::string summary_path(const RunPlan& plan);
std::string meta_path(const RunPlan& plan);

}  // namespace dabench
