// libFuzzer target: a shard's meta.json as `dabench merge` reads it (harness/run/shard_meta.hpp):
// the shard label and status, then the run plan rebuilt from the experiment text, seed and trials
// it records, checked against its fingerprint. Any input must give a shard or an InputError.
#include <cstddef>
#include <cstdint>
#include <string>

#include "harness/core/errors.hpp"
#include "harness/core/experiment.hpp"
#include "harness/run/shard_meta.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace dabench;
  try {
    const ShardMeta shard = parse_shard_meta("fuzz-shard", std::string(reinterpret_cast<const char*>(data), size));
    (void)shard.threads();
    (void)shard.number("wall_seconds");
    // Planning checks every sweep point alike (~10 µs each under ASan): past 10^4 points an input
    // would only spend the 10 s budget repeating checks, as in fuzz_experiment.
    if (parse_experiment(shard.field("experiment_path"), shard.field("experiment")).points.size() > 10000) return 0;
    RunPlan plan = shard_run_plan(shard, "fuzz-output");
    plan.shard = shard.shard;
    const long long items = plan.shard_items();
    if (items > 0) (void)plan.local_item(plan.global_item(items - 1));
  } catch (const InputError&) {
  }
  return 0;
}
