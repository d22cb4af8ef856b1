#pragma once
// The interface of tracking-scenario generators: a pure function of (parameters, random
// stream) that draws one run of K scans with its truth. Parameters are fixed when the object
// is built (one per sweep point); generate() may be called from many threads at once.
#include "harness/core/random_stream.hpp"
#include "harness/tracking/problem.hpp"

namespace dabench {

class TrackingScenario {
 public:
  virtual ~TrackingScenario() = default;
  virtual void generate(RandomStream& rng, TrackingScenarioSample& sample) const = 0;
};

}  // namespace dabench
