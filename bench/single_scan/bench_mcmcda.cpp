// MCMCDA (algorithms/single_scan/mcmcda.hpp) and the MAP assignment (algorithms/single_scan/map_association.hpp) on the
// grid problems of bp-marginal-association Sec. V: 2×3 at spacing 0 and 3, 3×10 at spacing 3.
//
// mcmcda_*: full solves (graph, MAP start, chain of `samples` steps, frequencies) over a fixed
//   pool; counters ns_per_step (CPU time per chain step, set-up included; Google Benchmark
//   prints this inverted rate with a trailing "s", the number is nanoseconds) and steps_per_s.
// chain_*: MatchingChain::run alone, 1e5 steps per iteration on one problem after another, so
//   the per-step cost is measured without set-up.
// map_*: the MAP solve alone, per problem.
#include <benchmark/benchmark.h>

#include <string>

#include "algorithms/single_scan/association_graph.hpp"
#include "algorithms/single_scan/map_association.hpp"
#include "algorithms/single_scan/mcmcda.hpp"
#include "bench/single_scan/problem_pool.hpp"

namespace dabench::bench {
namespace {

constexpr int kPool = 64;

std::vector<SingleScanProblem> pool_of(int rows, int cols, double spacing) {
  auto pool = grid_pool({{"rows", std::to_string(rows)}, {"cols", std::to_string(cols)},
                         {"spacing", std::to_string(spacing)}}, kPool);
  for (std::size_t k = 0; k < pool.size(); ++k) pool[k].trial_key = TrialKey{1, 0, static_cast<std::uint32_t>(k)};
  return pool;
}

void set_step_counters(benchmark::State& state, double steps) {
  state.counters["ns_per_step"] = benchmark::Counter(steps * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["steps_per_s"] = benchmark::Counter(steps, benchmark::Counter::kIsRate);
}

void mcmcda_grid(benchmark::State& state, int rows, int cols, double spacing) {
  const auto pool = pool_of(rows, cols, spacing);
  const std::int64_t samples = state.range(0);
  const auto solver = make_single_scan_solver("mcmcda:samples=" + std::to_string(samples));
  MarginalTable marginals;
  SolveReport report;
  std::size_t next = 0;
  for (auto _ : state) {
    solver->solve(pool[next], marginals, report);
    benchmark::DoNotOptimize(marginals.row(0));
    next = next + 1 == pool.size() ? 0 : next + 1;
  }
  set_step_counters(state, static_cast<double>(state.iterations()) * static_cast<double>(samples));
  state.counters["targets"] = rows * cols;
}

void chain_grid(benchmark::State& state, int rows, int cols, double spacing) {
  const auto pool = pool_of(rows, cols, spacing);
  constexpr std::int64_t kSteps = 100000;
  std::vector<AssociationGraph> graphs(pool.size());
  std::vector<std::vector<int>> starts(pool.size());
  MapAssignment map;
  double edges = 0.0;
  for (std::size_t k = 0; k < pool.size(); ++k) {
    graphs[k].build(pool[k]);
    graphs[k].find_clusters();
    map.solve(pool[k], graphs[k], starts[k]);
    edges += graphs[k].edges();
  }
  MatchingChain chain;
  RandomStream rng(1, 0, 0);
  std::size_t next = 0;
  for (auto _ : state) {
    state.PauseTiming();
    chain.build(graphs[next]);
    chain.start(starts[next]);
    state.ResumeTiming();
    chain.run(rng, kSteps);
    benchmark::DoNotOptimize(chain.target_measurement(0));
    next = next + 1 == pool.size() ? 0 : next + 1;
  }
  set_step_counters(state, static_cast<double>(state.iterations()) * kSteps);
  state.counters["mean_edges"] = edges / static_cast<double>(pool.size());
}

void map_grid(benchmark::State& state, int rows, int cols, double spacing) {
  const auto pool = pool_of(rows, cols, spacing);
  const auto solver = make_single_scan_solver("map");
  MarginalTable marginals;
  SolveReport report;
  std::size_t next = 0;
  for (auto _ : state) {
    solver->solve(pool[next], marginals, report);
    benchmark::DoNotOptimize(marginals.row(0));
    next = next + 1 == pool.size() ? 0 : next + 1;
  }
  state.counters["targets"] = rows * cols;
}

}  // namespace

BENCHMARK_CAPTURE(mcmcda_grid, 2x3_s0, 2, 3, 0.0)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(mcmcda_grid, 2x3_s3, 2, 3, 3.0)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(mcmcda_grid, 3x10_s3, 3, 10, 3.0)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(chain_grid, 2x3_s0, 2, 3, 0.0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(chain_grid, 2x3_s3, 2, 3, 3.0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(chain_grid, 3x10_s3, 3, 10, 3.0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(map_grid, 2x3_s0, 2, 3, 0.0)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(map_grid, 2x3_s3, 2, 3, 3.0)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(map_grid, 3x10_s3, 3, 10, 3.0)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(map_grid, 3x30_s3, 3, 30, 3.0)->Unit(benchmark::kMicrosecond);

}  // namespace dabench::bench
