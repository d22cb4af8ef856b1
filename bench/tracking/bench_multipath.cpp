// Module 3 of JDT-VB (algorithms/multipath_association): loopy BP for the multipath association
// marginals of one scan, at OTHR-like sizes (targets × 4 propagation paths × measurements), each
// pseudo-target gating about `gated` measurements (the rest χ = −∞), χ ~ U(−3, 3) inside the gate.
// Time = mean per scan over a pool of 64 scans (measured, loaded 2-core VM, CPU time: 33 µs for
// 4×20 gated 3, 115 µs for 10×40 gated 3, 0.85 ms for 10×40 gated 10; the dense version took 10×
// longer); counter `iterations` = mean BP iterations
// (tolerance 1e-9 on the message log ratios).
#include <benchmark/benchmark.h>

#include <cmath>
#include <limits>
#include <vector>

#include "algorithms/tracking/multipath_association.hpp"
#include "harness/core/random_stream.hpp"

namespace dabench::bench {
namespace {

std::vector<MultipathEvidence> evidence_pool(int targets, int measurements, int gated) {
  constexpr int kPaths = 4;
  std::vector<MultipathEvidence> pool(64);
  RandomStream rng(2024, 0, 0);
  for (auto& evidence : pool) {
    evidence.targets = targets;
    evidence.paths = kPaths;
    const int rows = targets * kPaths;
    evidence.detection = RowMatrix::Constant(rows, measurements, -std::numeric_limits<double>::infinity());
    for (int p = 0; p < rows; ++p) {
      for (int j = 0; j < measurements; ++j) {
        if (rng.uniform() * measurements < gated) evidence.detection(p, j) = rng.uniform(-3.0, 3.0);
      }
    }
    evidence.miss = Vector::Constant(rows, std::log(0.4));
    evidence.clutter = Vector::Constant(measurements, 0.0);
  }
  return pool;
}

void multipath_bp(benchmark::State& state) {
  const auto pool = evidence_pool(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)),
                                  static_cast<int>(state.range(2)));
  MultipathAssociationBp bp;
  MultipathAssociation result;
  std::size_t next = 0;
  double iterations = 0.0;
  for (auto _ : state) {
    bp.solve(pool[next], {}, result);
    benchmark::DoNotOptimize(result.detection.data());
    iterations += result.iterations;
    next = next + 1 == pool.size() ? 0 : next + 1;
  }
  state.counters["iterations"] = iterations / static_cast<double>(state.iterations());
}

BENCHMARK(multipath_bp)->ArgNames({"targets", "measurements", "gated"})
    ->Args({4, 20, 3})->Args({10, 40, 3})->Args({10, 40, 10})->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace dabench::bench
