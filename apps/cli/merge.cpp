// dabench merge: the folders of `dabench run --shard K/N` joined into the unsharded run's.
#include <cstdio>

#include "apps/cli/command.hpp"
#include "harness/core/errors.hpp"
#include "harness/core/input_file.hpp"
#include "harness/run/shard_merge.hpp"

namespace dabench::cli {

namespace {

int run_merge(const Invocation& invocation) {
  po::options_description options("merge options");
  MergeOptions merge;
  merge.command_line = invocation.command_line;
  options.add_options()
      ("output", po::value(&merge.output), "folder of the merged run")
      ("shards", po::value(&merge.shards)->multitoken(), "the shard folders")
      ("force", po::bool_switch(&merge.force), "replace a run in the output folder")
      ("allow-mixed", po::bool_switch(&merge.allow_mixed), "merge shards written by different builds (recorded in meta.json)");
  po::positional_options_description positional;
  positional.add("output", 1).add("shards", -1);
  if (!parse_command(kMergeCommand, options, positional, invocation)) return 0;
  if (merge.output.empty() || merge.shards.empty()) throw InputError("merge: give the output folder, then the shard folders");
  const MergeOutcome outcome = merge_shards(merge);
  std::string files = "trials.csv";
  for (const std::string& file : outcome.item_files) files += ", " + file;
  std::fprintf(stderr, "dabench: merged %d shards, %lld trials; results in %s/ (%s, summary.csv, meta.json)\n",
               outcome.shards, outcome.items, printable_line(merge.output).c_str(), files.c_str());
  return 0;
}

}  // namespace

const Command kMergeCommand{
    "merge", "dabench merge OUT SHARD_DIR... [--force]",
    "Joins the folders of `dabench run --shard K/N` (K = 1..N, same experiment, seed and trials)\n"
    "into OUT: the trials.csv, summary.csv, meta.json and per-trial files of the unsharded run.\n"
    "Missing, duplicated, incomplete or foreign shards are errors.\n",
    run_merge};

}  // namespace dabench::cli
