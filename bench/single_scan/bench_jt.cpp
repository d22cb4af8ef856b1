// Junction tree (`jt`, eqs 37-39 of Williams & Lau 2014, Sec. IV-A) on the grid problems of
// Sec. V (baseline Pd 0.6, λ_fa 0.01, r 1) at the paper's thresholds τ ∈ {1e-1, 1e-2, 1e-3}
// (on ψ, the default reading): 2×3 and 3×3 targets at spacing 0 and 3, next to BP.
//
// Each benchmark walks a fixed pool of problems (bench/single_scan/problem_pool.hpp). Counters:
//   median_us  median over the pool's SOLVED problems of the per-problem time (each solved
//              `repeats` times in a row to amortise the clock);
//   skipped    fraction of the pool refused by the memory budget (skipped:memory; default
//              3.5 GiB of tables per cluster), measured on the same pass;
//   states     median over the solved problems of the clique states (libDAI's maxstates measure).
// The mean time per iteration (Google Benchmark's own column) includes refused problems, which
// cost microseconds (the refusal happens during elimination, before any table exists).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <string>

#include "algorithms/single_scan/junction_tree.hpp"
#include "bench/single_scan/problem_pool.hpp"

namespace dabench::bench {
namespace {

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

void solve_grid_jt(benchmark::State& state, const char* spec, int rows, int cols, double spacing, int pool_size,
                   int repeats) {
  const auto pool = grid_pool({{"rows", std::to_string(rows)}, {"cols", std::to_string(cols)},
                               {"spacing", std::to_string(spacing)}}, pool_size);
  const auto solver = make_single_scan_solver(spec);
  auto* jt = dynamic_cast<JunctionTree*>(solver.get());  // null for bp
  MarginalTable marginals;
  SolveReport report;

  // One pass over the pool: per-problem medians and the refused fraction.
  std::vector<double> times, states;
  int skipped = 0;
  for (const auto& problem : pool) {
    const auto start = std::chrono::steady_clock::now();
    for (int r = 0; r < repeats; ++r) {
      solver->solve(problem, marginals, report);
      benchmark::DoNotOptimize(marginals.row(0));
    }
    const double us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count() / repeats;
    if (!report.skipped.empty()) {
      ++skipped;
      continue;
    }
    times.push_back(us);
    if (jt != nullptr) states.push_back(static_cast<double>(jt->largest_clique_states()));
  }

  std::size_t next = 0;
  for (auto _ : state) {
    solver->solve(pool[next], marginals, report);
    benchmark::DoNotOptimize(marginals.row(0));
    next = next + 1 == pool.size() ? 0 : next + 1;
  }
  state.counters["median_us"] = median(times);
  state.counters["skipped"] = static_cast<double>(skipped) / static_cast<double>(pool.size());
  if (jt != nullptr) state.counters["states"] = median(states);
  state.counters["targets"] = rows * cols;
}

}  // namespace

// 2×3: pools of 256 problems, 8 repeats each for the medians.
BENCHMARK_CAPTURE(solve_grid_jt, bp_2x3_s0, "bp", 2, 3, 0.0, 256, 8)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(solve_grid_jt, jt_1e-1_2x3_s0, "jt:threshold=1e-1", 2, 3, 0.0, 256, 8)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(solve_grid_jt, jt_1e-2_2x3_s0, "jt:threshold=1e-2", 2, 3, 0.0, 256, 8)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(solve_grid_jt, jt_1e-3_2x3_s0, "jt:threshold=1e-3", 2, 3, 0.0, 256, 8)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(solve_grid_jt, bp_2x3_s3, "bp", 2, 3, 3.0, 256, 8)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(solve_grid_jt, jt_1e-1_2x3_s3, "jt:threshold=1e-1", 2, 3, 3.0, 256, 8)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(solve_grid_jt, jt_1e-2_2x3_s3, "jt:threshold=1e-2", 2, 3, 3.0, 256, 8)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(solve_grid_jt, jt_1e-3_2x3_s3, "jt:threshold=1e-3", 2, 3, 3.0, 256, 8)->Unit(benchmark::kMicrosecond);
// 3×3: pools of 48 problems, one solve each for the medians (the largest take seconds).
BENCHMARK_CAPTURE(solve_grid_jt, bp_3x3_s0, "bp", 3, 3, 0.0, 48, 1)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(solve_grid_jt, jt_1e-1_3x3_s0, "jt:threshold=1e-1", 3, 3, 0.0, 48, 1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(solve_grid_jt, jt_1e-2_3x3_s0, "jt:threshold=1e-2", 3, 3, 0.0, 48, 1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(solve_grid_jt, jt_1e-3_3x3_s0, "jt:threshold=1e-3", 3, 3, 0.0, 48, 1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(solve_grid_jt, bp_3x3_s3, "bp", 3, 3, 3.0, 48, 1)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(solve_grid_jt, jt_1e-1_3x3_s3, "jt:threshold=1e-1", 3, 3, 3.0, 48, 1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(solve_grid_jt, jt_1e-2_3x3_s3, "jt:threshold=1e-2", 3, 3, 3.0, 48, 1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(solve_grid_jt, jt_1e-3_3x3_s3, "jt:threshold=1e-3", 3, 3, 3.0, 48, 1)->Unit(benchmark::kMillisecond);

}  // namespace dabench::bench
