#include "harness/run/shard_meta.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>

#include <fmt/format.h>

#include "harness/core/errors.hpp"
#include "harness/core/input_file.hpp"
#include "harness/core/json.hpp"
#include "harness/core/params.hpp"

namespace dabench {

namespace fs = std::filesystem;

std::optional<Shard> parse_shard_label(std::string_view text) {
  const auto slash = text.find('/');
  std::int64_t index = 0, count = 0;
  if (slash == std::string_view::npos || !parse_int64(text.substr(0, slash), index) ||
      !parse_int64(text.substr(slash + 1), count) || count < 1 || count > kMaxShards || index < 1 || index > count) {
    return std::nullopt;
  }
  return Shard{static_cast<int>(index), static_cast<int>(count)};
}

std::string ShardMeta::field(std::string_view key) const {
  const auto value = json_value(meta, key);
  if (!value) throw InputError(fmt::format("{}/meta.json: no '{}' field", path, key));
  return *value;
}

double ShardMeta::number(std::string_view key) const {
  double value = std::nan("");
  return parse_double(json_value(meta, key).value_or(""), value) ? value : std::nan("");
}

int ShardMeta::threads() const {
  const double value = number("threads");
  return std::isfinite(value) ? static_cast<int>(std::clamp(value, 1.0, 65536.0)) : 1;
}

ShardMeta parse_shard_meta(const std::string& path, std::string meta) {
  ShardMeta shard{path, std::move(meta), "", Shard{}};
  const auto label = json_value(shard.meta, "shard");
  if (!label) throw InputError(fmt::format("{}: not a shard (its run had no --shard K/N)", path));
  shard.label = *label;
  const auto parsed = parse_shard_label(*label);
  if (!parsed) throw InputError(fmt::format("{}/meta.json: malformed shard '{}'", path, *label));
  shard.shard = *parsed;
  const std::string status = shard.field("status");
  if (status != "complete") {
    throw InputError(fmt::format("{}: shard {} is {} ({} of {} items done); finish it with its dabench run command and "
                                 "--resume", path, shard.label, status,
                                 shard.field("items_done"),
                                 json_value(shard.meta, "shard_items").value_or("?")));
  }
  return shard;
}

ShardMeta read_shard_meta(const std::string& path) {
  const fs::path meta = fs::path(path) / "meta.json";
  if (!fs::exists(meta)) throw InputError(fmt::format("{}: no meta.json (not a run folder)", path));
  return parse_shard_meta(path, read_input_file(meta.string(), "a shard's meta.json", kMaxMetaBytes));
}

RunPlan shard_run_plan(const ShardMeta& shard, const std::string& output) {
  RunOptions options;
  std::int64_t trials = 0, seed = 0;
  if (!parse_int64(shard.field("trials_per_point"), trials) || !parse_int64(shard.field("seed"), seed)) {
    throw InputError(fmt::format("{}/meta.json: malformed trials_per_point or seed", shard.path));
  }
  options.trials = trials;
  options.seed = static_cast<std::uint64_t>(seed);
  options.threads = 1;
  options.output = output;
  RunPlan plan;
  try {
    plan = make_run_plan(parse_experiment(shard.field("experiment_path"), shard.field("experiment")), options);
  } catch (const InputError& error) {
    throw InputError(fmt::format("{}/meta.json: its experiment no longer makes a run plan: {}", shard.path,
                                 error.what()));
  }
  const std::string recorded = shard.field("fingerprint");
  if (plan.fingerprint() != recorded) {
    throw InputError(fmt::format("{}: its experiment now gives fingerprint {}, not the recorded {} (algorithms or "
                                 "defaults changed since the shards ran?)", shard.path, plan.fingerprint(),
                                 recorded));
  }
  return plan;
}

}  // namespace dabench
