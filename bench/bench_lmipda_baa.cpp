// LMIPDA and BAA on the grid problems of bp-marginal-association Sec. V (baseline Pd 0.6,
// λ_fa 0.01, r 1): 2×3 (6 targets) at spacing 0 and 3, and 3×30 (90 targets) at spacing 3.
// The grid scenario puts its Pd into each problem's context, which is where `lmipda` reads it.
//
// As in bench_single_scan.cpp: each iteration solves the next problem of a fixed pool of 512
// instances (reported time = mean per problem); the counter `median_us` is the median over the
// pool of per-problem times, each problem solved `kRepeats` times in a row.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>

#include "bench/problem_pool.hpp"

namespace dabench::bench {
namespace {

constexpr int kPool = 512;
constexpr int kRepeats = 32;

double pool_median_us(SingleScanSolver& solver, const std::vector<SingleScanProblem>& pool) {
  MarginalTable marginals;
  SolveReport report;
  std::vector<double> times;
  for (const auto& problem : pool) {
    const auto start = std::chrono::steady_clock::now();
    for (int r = 0; r < kRepeats; ++r) {
      solver.solve(problem, marginals, report);
      benchmark::DoNotOptimize(marginals.row(0));
    }
    times.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count() / kRepeats);
  }
  std::nth_element(times.begin(), times.begin() + times.size() / 2, times.end());
  return times[times.size() / 2];
}

void solve_grid_pool(benchmark::State& state, const char* spec, int rows, int cols, double spacing) {
  const auto pool = grid_pool({{"rows", std::to_string(rows)}, {"cols", std::to_string(cols)},
                               {"spacing", std::to_string(spacing)}}, kPool);
  const auto solver = make_single_scan_solver(spec);
  MarginalTable marginals;
  SolveReport report;
  std::size_t next = 0;
  long long skipped = 0;
  for (auto _ : state) {
    solver->solve(pool[next], marginals, report);
    benchmark::DoNotOptimize(marginals.row(0));
    skipped += !report.skipped.empty();
    next = next + 1 == pool.size() ? 0 : next + 1;
  }
  if (skipped > 0) {
    state.SkipWithError("instances refused (skipped)");
    return;
  }
  state.counters["median_us"] = pool_median_us(*solver, pool);
  state.counters["targets"] = rows * cols;
}

}  // namespace

BENCHMARK_CAPTURE(solve_grid_pool, lmipda_2x3_s0, "lmipda", 2, 3, 0.0)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(solve_grid_pool, lmipda_2x3_s3, "lmipda", 2, 3, 3.0)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(solve_grid_pool, lmipda_3x30_s3, "lmipda", 3, 30, 3.0)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(solve_grid_pool, baa_2x3_s0, "baa", 2, 3, 0.0)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(solve_grid_pool, baa_2x3_s3, "baa", 2, 3, 3.0)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(solve_grid_pool, baa_3x30_s3, "baa", 3, 30, 3.0)->Unit(benchmark::kMicrosecond);

}  // namespace dabench::bench
