#pragma once
// One shard of a `dabench run --shard K/N` as `dabench merge` reads it: its folder's meta.json,
// checked to be a complete shard, and the run plan rebuilt from the experiment it records.
// The shard label "K/N" is parsed here for `run --shard` and for merge alike.
#include <optional>
#include <string>
#include <string_view>

#include "harness/run/run_plan.hpp"

namespace dabench {

constexpr int kMaxShards = 1000000;  // N of --shard K/N

// "K/N" with 1 <= K <= N <= kMaxShards; nothing otherwise.
std::optional<Shard> parse_shard_label(std::string_view text);

struct ShardMeta {
  std::string path;   // the shard's folder, as given
  std::string meta;   // its meta.json
  std::string label;  // "K/N"
  Shard shard;

  std::string field(std::string_view key) const;  // throws InputError naming the file when absent
  double number(std::string_view key) const;      // NaN when absent or not a number
  int threads() const;                            // its "threads", 1 when absent, at most 2^16
};

// Checks `meta` (the text of PATH/meta.json): a shard label, status complete. Throws InputError
// of one line naming the folder otherwise.
ShardMeta parse_shard_meta(const std::string& path, std::string meta);
// PATH/meta.json (a regular file of at most kMaxMetaBytes), parsed.
ShardMeta read_shard_meta(const std::string& path);
// The plan of the shard's run, rebuilt from the experiment text, seed and trials it records and
// writing to `output`; its fingerprint must be the recorded one (else the algorithms or defaults
// changed since the shard ran). Throws InputError.
RunPlan shard_run_plan(const ShardMeta& shard, const std::string& output);

}  // namespace dabench
