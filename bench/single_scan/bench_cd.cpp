// Correlation decay (`cd`, eqs 40-41 of bp-marginal-association, Sec. IV-B) on the grid
// problems of Sec. V (baseline Pd 0.6, λ_fa 0.01, r 1): depths 3, 5, 7 on the 2×3 grid at
// spacing 0 and 3, and depths 3 and 5 on 3×10 at spacing 3 (depth 7 there takes ~50 ms a
// problem); memo off at depth 7 for comparison.
// Compare with BP on the same pools: --benchmark_filter='bp_2x3|cd_'.
//
// Each iteration solves the next problem of a fixed pool; the time is the mean per problem.
// Counters: median_us (median over the pool of per-problem times, each problem solved until
// ≥ 200 µs have passed), evals (mean evaluations of (40)/(41) per problem), skipped (problems
// refused by the budget; a refusal is fast, so times then under-state the cost).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>

#include "algorithms/single_scan/correlation_decay.hpp"
#include "bench/single_scan/problem_pool.hpp"

namespace dabench::bench {
namespace {

constexpr int kPool = 128;

double median_us(CorrelationDecay& solver, const std::vector<SingleScanProblem>& pool) {
  MarginalTable marginals;
  SolveReport report;
  std::vector<double> times;
  for (const auto& problem : pool) {
    int repeats = 0;
    const auto start = std::chrono::steady_clock::now();
    double elapsed = 0.0;
    do {
      solver.solve(problem, marginals, report);
      benchmark::DoNotOptimize(marginals.row(0));
      ++repeats;
      elapsed = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
    } while (elapsed < 200.0);
    times.push_back(elapsed / repeats);
  }
  std::nth_element(times.begin(), times.begin() + times.size() / 2, times.end());
  return times[times.size() / 2];
}

void solve_cd_grid(benchmark::State& state, int depth, bool memo, int rows, int cols, double spacing) {
  const auto pool = grid_pool({{"rows", std::to_string(rows)}, {"cols", std::to_string(cols)},
                               {"spacing", std::to_string(spacing)}}, kPool);
  CorrelationDecayOptions options;
  options.depth = depth;
  options.memo = memo;
  CorrelationDecay solver(options);
  MarginalTable marginals;
  SolveReport report;
  std::size_t next = 0;
  for (auto _ : state) {
    solver.solve(pool[next], marginals, report);
    benchmark::DoNotOptimize(marginals.row(0));
    next = next + 1 == pool.size() ? 0 : next + 1;
  }
  double evaluations = 0.0;
  int skipped = 0;
  for (const auto& problem : pool) {
    solver.solve(problem, marginals, report);
    evaluations += static_cast<double>(solver.evaluations());
    skipped += !report.skipped.empty();
  }
  state.counters["evals"] = evaluations / kPool;
  state.counters["skipped"] = skipped;
  state.counters["median_us"] = median_us(solver, pool);
  state.counters["targets"] = rows * cols;
}

}  // namespace

BENCHMARK_CAPTURE(solve_cd_grid, cd3_2x3_s0, 3, true, 2, 3, 0.0)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(solve_cd_grid, cd5_2x3_s0, 5, true, 2, 3, 0.0)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(solve_cd_grid, cd7_2x3_s0, 7, true, 2, 3, 0.0)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(solve_cd_grid, cd7_nomemo_2x3_s0, 7, false, 2, 3, 0.0)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(solve_cd_grid, cd3_2x3_s3, 3, true, 2, 3, 3.0)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(solve_cd_grid, cd5_2x3_s3, 5, true, 2, 3, 3.0)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(solve_cd_grid, cd7_2x3_s3, 7, true, 2, 3, 3.0)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(solve_cd_grid, cd7_nomemo_2x3_s3, 7, false, 2, 3, 3.0)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(solve_cd_grid, cd3_3x10_s3, 3, true, 3, 10, 3.0)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(solve_cd_grid, cd5_3x10_s3, 5, true, 3, 10, 3.0)->Unit(benchmark::kMicrosecond);

}  // namespace dabench::bench
