#pragma once
// A pool of 8 whole OTHR runs (scenarios/othr: K = 30 scans, 4 targets, 4 paths) drawn once at
// one of Table IV's settings, for the trackers' TET benchmarks.
#include <cstdint>
#include <vector>

#include "harness/core/random_stream.hpp"
#include "scenarios/tracking/othr.hpp"

namespace dabench::bench {

inline std::vector<TrackingScenarioSample> othr_pool(double pd, double clutter) {
  OthrOptions options;
  options.pd = pd;
  options.clutter = clutter;
  const OthrScenario scenario(options);
  std::vector<TrackingScenarioSample> pool(8);
  for (int run = 0; run < 8; ++run) {
    RandomStream rng(2019, 0, static_cast<std::uint32_t>(run));
    scenario.generate(rng, pool[run]);
  }
  return pool;
}

}  // namespace dabench::bench
