#pragma once
// The interface of scenario generators: a pure function of (parameters, random stream) that
// draws one single-scan problem. Parameters are fixed when the scenario object is built (one
// per sweep point); generate() may be called from many threads at once.
#include <vector>

#include "harness/core/random_stream.hpp"
#include "harness/single_scan/problem.hpp"

namespace dabench {

struct ScenarioSample {
  SingleScanProblem problem;
  // Ground truth of the draw, for statistics tests and diagnostics.
  std::vector<int> true_measurement;  // per target: 1-based measurement it generated, 0 if none
  int detections = 0;                 // targets that generated a measurement
  int gated_out_detections = 0;       // of those, measurements outside their own track's gate
  int false_alarms = 0;               // false alarms drawn (before pruning ungated ones)
};

class SingleScanScenario {
 public:
  virtual ~SingleScanScenario() = default;
  virtual void generate(RandomStream& rng, ScenarioSample& sample) const = 0;
};

}  // namespace dabench
