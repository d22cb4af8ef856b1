#pragma once
// The interface of multiple-scan scenario generators (multiscan-convex-variational, Sec. IV):
// a pure function of (parameters, random stream) that draws one MultiScanProblem together
// with what the metrics against truth need. Parameters are fixed when the object is built
// (one per sweep point); generate() may be called from many threads at once.
//
// Metrics against truth (harness/multi_scan/particle_metrics.hpp) read a belief q^i over a track's
// hypotheses as a density: p̂(x_A) = q^i(A)·density_scale[i](A). For particle tracks the
// scenario also places one "truth probe" hypothesis at the true state, with a prior weight
// so small (a fraction ε of a particle's) that it changes no other belief by more than ~ε,
// so every algorithm evaluates its own posterior density at the truth (eq 92 needs p(x*)).
#include <vector>

#include "harness/core/random_stream.hpp"
#include "harness/multi_scan/problem.hpp"

namespace dabench {

struct MultiScanSample {
  MultiScanProblem problem;
  std::vector<int> truth_probe;        // per track: index of its truth-probe hypothesis
  std::vector<Vector> density_scale;   // per track: s(A) ≥ 0, p̂(x_A) = q(A)·s(A) (probe included)
  // Ground truth counts, for statistics tests and diagnostics (sums over scans).
  int detections = 0;    // target-originated measurements
  int false_alarms = 0;  // clutter measurements
};

class MultiScanScenario {
 public:
  virtual ~MultiScanScenario() = default;
  virtual void generate(RandomStream& rng, MultiScanSample& sample) const = 0;
};

}  // namespace dabench
