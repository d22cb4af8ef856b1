#pragma once
// Fixed pools of grid problems for the benchmarks: drawn once from the registered `grid`
// scenario with a fixed seed, so every benchmark run times the same instances.
#include <string>
#include <vector>

#include "harness/core/params.hpp"
#include "harness/single_scan/registry.hpp"

namespace dabench::bench {

inline std::vector<SingleScanProblem> grid_pool(std::vector<KeyValue> settings, int count, std::uint64_t seed = 7) {
  const auto scenario = single_scan_scenario_registry().find("grid")->create(settings);
  std::vector<SingleScanProblem> pool;
  ScenarioSample sample;
  for (int k = 0; k < count; ++k) {
    RandomStream rng(seed, 0, static_cast<std::uint32_t>(k));
    scenario->generate(rng, sample);
    pool.push_back(sample.problem);
  }
  return pool;
}

}  // namespace dabench::bench
