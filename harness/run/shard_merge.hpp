#pragma once
// `dabench merge OUT SHARD_DIR...`: joins the folders written by `dabench run --shard K/N`
// (K = 1..N, one run plan) into the files an unsharded run writes, in OUT: trials.csv and the
// kind's per-item files with every row in item order, summary.csv recomputed from trials.csv,
// and meta.json as the run writes it, its process fields from the shards (processes = N, their
// hosts, the most threads, the earliest start and latest end, wall time summed over shards).
//
// Before OUT is touched it checks that every folder is a complete shard (meta.json with status
// complete and a "shard" field), that all belong to one plan (same fingerprint, seed,
// experiment text and N) and one build (version, commit, compiler and flags; else only with
// --allow-mixed, which meta.json records with each shard's build) and that 1..N each appear
// once; the plan is rebuilt from the recorded experiment and must give the recorded fingerprint
// (the same algorithms and defaults). OUT is locked (harness/run/folder_lock.hpp) for the whole
// merge. While merging it checks every row against its shard's checksums.csv and that each
// shard's files hold exactly its own items, in order, with one trials.csv row per item and
// algorithm; the merged folder gets its own checksums.csv, and meta.json records the shards'
// build. On any error the files being written are removed. Every error is one line naming the
// folder or file: an InputError, or a WriteError (exit 1) naming the file that could not be
// written and why.
#include <string>
#include <vector>

namespace dabench {

struct MergeOptions {
  std::string output;
  std::vector<std::string> shards;  // shard folders, in any order
  bool force = false;               // replace a run already in `output`
  bool allow_mixed = false;         // merge shards written by different builds (recorded in meta.json)
  std::string command_line;         // recorded in meta.json
};

struct MergeOutcome {
  long long items = 0;
  int shards = 0;
  std::vector<std::string> item_files;  // written beside trials.csv (e.g. targets.csv)
};

MergeOutcome merge_shards(const MergeOptions& options);

}  // namespace dabench
