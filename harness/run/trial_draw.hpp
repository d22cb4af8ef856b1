#pragma once
// The prologue every kind's run_item shares: a work item's sweep point and trial, and its
// sample drawn from the point's scenario on the trial's own random stream
// RandomStream(seed, point, trial) — so a trial's problem depends on (seed, point, trial) alone,
// whatever the thread, process or shard that draws it.
#include <cstdint>
#include <memory>
#include <vector>

#include "harness/core/random_stream.hpp"
#include "harness/run/run_plan.hpp"

namespace dabench {

struct TrialIndex {
  std::uint32_t point = 0;
  std::uint32_t trial = 0;
};

// Draws item's sample into `sample` from scenarios[point]; returns (point, trial).
template <class Scenario, class Sample>
TrialIndex draw_trial(const RunPlan& plan, const std::vector<std::unique_ptr<Scenario>>& scenarios, long long item,
                      Sample& sample) {
  const TrialIndex index{static_cast<std::uint32_t>(item / plan.trials), static_cast<std::uint32_t>(item % plan.trials)};
  RandomStream rng(plan.seed, index.point, index.trial);
  scenarios[index.point]->generate(rng, sample);
  return index;
}

}  // namespace dabench
