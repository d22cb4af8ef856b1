#pragma once
// Shared timing loop of the single-scan benchmarks (bench_*.cpp only: needs Google Benchmark).
#include <algorithm>
#include <chrono>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench/single_scan/problem_pool.hpp"

namespace dabench::bench {

// Each iteration solves the next problem of a pool of kPool grid instances (time = mean per
// problem); the counter median_us is the median over the pool of per-problem times, each
// problem solved kRepeats times in a row to amortise the clock. Refused instances mark the
// benchmark as failed (SkipWithError) instead of timing a refusal.
inline constexpr int kPool = 512;
inline constexpr int kRepeats = 32;

inline double median_us(SingleScanSolver& solver, const std::vector<SingleScanProblem>& pool) {
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

inline void solve_grid(benchmark::State& state, const char* spec, int rows, int cols, double spacing) {
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
    state.SkipWithError("instances refused (skipped: work limit)");
    return;
  }
  state.counters["median_us"] = median_us(*solver, pool);
  state.counters["targets"] = rows * cols;
}

}  // namespace dabench::bench
