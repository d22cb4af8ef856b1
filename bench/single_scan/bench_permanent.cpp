// The exact methods on dense random problems, where EHM's net is wide: `permanent` (subset
// recursion over the smaller side, algorithms/single_scan/permanent.hpp) against `ehm`, `jt` and
// `exact` (enumeration) by n targets × m measurements and the share of gated pairs (density 1:
// every target gates every measurement; 0.5: half the pairs, at random). Weights are i.i.d.
// exponential(3), the same pool for every method (seeded by the size and density). A refused
// problem (skipped:work_limit, skipped:memory) is counted in `skipped`, and its time is that of
// the refusal. Which method wins where: see docs/algorithms.md.
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>
#include <vector>

#include "harness/core/random_stream.hpp"
#include "harness/single_scan/registry.hpp"

namespace dabench::bench {
namespace {

std::vector<SingleScanProblem> dense_pool(int n, int m, double density, int size) {
  std::vector<SingleScanProblem> pool(static_cast<std::size_t>(size));
  for (int p = 0; p < size; ++p) {
    RandomStream rng(20161, static_cast<std::uint32_t>(n * 1000 + m), static_cast<std::uint32_t>(p + 100000 * (density < 1.0)));
    SingleScanProblem& problem = pool[static_cast<std::size_t>(p)];
    problem.psi = RowMatrix::Zero(n, m);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < m; ++j) {
        if (rng.uniform() < density) problem.psi(i, j) = -3.0 * std::log(1.0 - rng.uniform());
      }
    }
  }
  return pool;
}

void solve_dense(benchmark::State& state, const char* spec, int n, int m, double density) {
  const auto pool = dense_pool(n, m, density, 8);
  const auto solver = make_single_scan_solver(spec);
  MarginalTable marginals;
  SolveReport report;
  std::size_t next = 0;
  long long skipped = 0, solves = 0;
  for (auto _ : state) {
    solver->solve(pool[next], marginals, report);
    benchmark::DoNotOptimize(marginals.row(0));
    skipped += report.skipped.empty() ? 0 : 1;
    ++solves;
    next = next + 1 == pool.size() ? 0 : next + 1;
  }
  state.counters["skipped"] = solves > 0 ? static_cast<double>(skipped) / static_cast<double>(solves) : 0.0;
}

void register_all() {
  struct Size {
    int n, m;
  };
  for (const double density : {1.0, 0.5}) {
    for (const Size size : {Size{4, 4}, Size{6, 8}, Size{8, 8}, Size{10, 12}, Size{12, 12}, Size{14, 16}, Size{16, 24}}) {
      for (const char* spec : {"permanent", "ehm", "jt", "exact"}) {
        // Enumeration and the junction tree (its cliques hold every target) are hopeless beyond 8 targets.
        if ((std::string(spec) == "exact" || std::string(spec) == "jt") && size.n > 8) continue;
        const std::string name = std::string("exact_dense/") + spec + "/" + std::to_string(size.n) + "x" +
                                 std::to_string(size.m) + "/density_" + (density < 1.0 ? "0.5" : "1");
        benchmark::RegisterBenchmark(name.c_str(), solve_dense, spec, size.n, size.m, density)
            ->Unit(benchmark::kMicrosecond)
            ->MinTime(0.05);
      }
    }
  }
}

const bool registered = (register_all(), true);

}  // namespace
}  // namespace dabench::bench
