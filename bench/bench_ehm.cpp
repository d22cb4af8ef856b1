// `ehm` (efficient hypothesis management, exact marginals) on the grid problems of
// bp-marginal-association Sec. V at baseline (Pd 0.6, λ_fa 0.01, r 1): experiment 1's 2×3 grid,
// experiment 2's 3×n grids and experiment 3's n×n grids at spacing 3.
//
// Each benchmark iteration solves the next instance of a fixed pool (512 instances for 2×3,
// 64 for the large grids); the reported time is the mean per instance. Counters:
//   median_us  median over the pool of per-instance times (each solved `repeats` times in a row)
//   max_width  largest net layer over the pool;  mean_nodes  mean net nodes per instance
//   max_bits   largest key space |K(t)| (shared measurements a node key can hold)
// Variants compare EHM2 (tree=1, default) with plain EHM (tree=0) and the target orders
// (order=0 greedy min-frontier, 1 Cuthill–McKee BFS, 2 input order).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>

#include "algorithms/ehm.hpp"
#include "bench/problem_pool.hpp"

namespace dabench::bench {
namespace {

void solve_grid_ehm(benchmark::State& state, const char* spec, int rows, int cols, double spacing, int pool_size,
                    int repeats) {
  const auto pool = grid_pool({{"rows", std::to_string(rows)}, {"cols", std::to_string(cols)},
                               {"spacing", std::to_string(spacing)}}, pool_size);
  const auto solver = make_single_scan_solver(spec);
  const auto* ehm = dynamic_cast<const Ehm*>(solver.get());
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
  std::vector<double> times;
  double nodes = 0.0;
  int width = 0, bits = 0;
  for (const auto& problem : pool) {
    const auto start = std::chrono::steady_clock::now();
    for (int r = 0; r < repeats; ++r) {
      solver->solve(problem, marginals, report);
      benchmark::DoNotOptimize(marginals.row(0));
    }
    times.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count() / repeats);
    if (ehm != nullptr) {
      nodes += static_cast<double>(ehm->stats().nodes);
      width = std::max(width, ehm->stats().max_layer_width);
      bits = std::max(bits, ehm->stats().max_key_bits);
    }
  }
  std::nth_element(times.begin(), times.begin() + static_cast<std::ptrdiff_t>(times.size() / 2), times.end());
  state.counters["median_us"] = times[times.size() / 2];
  state.counters["max_us"] = *std::max_element(times.begin(), times.end());
  state.counters["max_width"] = width;
  state.counters["mean_nodes"] = nodes / static_cast<double>(pool.size());
  state.counters["max_bits"] = bits;
  state.counters["targets"] = rows * cols;
}

}  // namespace

#define EHM_SMALL(name, spec, rows, cols, spacing) \
  BENCHMARK_CAPTURE(solve_grid_ehm, name, spec, rows, cols, spacing, 512, 32)->Unit(benchmark::kMicrosecond)
#define EHM_LARGE(name, spec, rows, cols) \
  BENCHMARK_CAPTURE(solve_grid_ehm, name, spec, rows, cols, 3.0, 64, 1)->Unit(benchmark::kMillisecond)->Iterations(64)

// Experiment 1: 2×3 grid.
EHM_SMALL(ehm_2x3_s0, "ehm", 2, 3, 0.0);
EHM_SMALL(ehm_2x3_s3, "ehm", 2, 3, 3.0);
EHM_SMALL(ehm_2x3_s0_path, "ehm:tree=0", 2, 3, 0.0);
EHM_SMALL(ehm_2x3_s3_path, "ehm:tree=0", 2, 3, 3.0);
// Experiment 2: 3×n grids, spacing 3.
EHM_LARGE(ehm_3x5_s3, "ehm", 3, 5);
EHM_LARGE(ehm_3x10_s3, "ehm", 3, 10);
EHM_LARGE(ehm_3x20_s3, "ehm", 3, 20);
EHM_LARGE(ehm_3x30_s3, "ehm", 3, 30);
EHM_LARGE(ehm_3x30_s3_path, "ehm:tree=0", 3, 30);
EHM_LARGE(ehm_3x30_s3_bfs, "ehm:order=1", 3, 30);
EHM_LARGE(ehm_3x30_s3_bfs_path, "ehm:order=1,tree=0", 3, 30);
EHM_LARGE(ehm_3x10_s3_input, "ehm:order=2", 3, 10);
// Experiment 3: n×n grids, spacing 3.
EHM_LARGE(ehm_5x5_s3, "ehm", 5, 5);
EHM_LARGE(ehm_8x8_s3, "ehm", 8, 8);
EHM_LARGE(ehm_10x10_s3, "ehm", 10, 10);
EHM_LARGE(ehm_10x10_s3_path, "ehm:tree=0", 10, 10);
EHM_LARGE(ehm_10x10_s3_bfs, "ehm:order=1", 10, 10);
EHM_LARGE(ehm_10x10_s3_bfs_path, "ehm:order=1,tree=0", 10, 10);

}  // namespace dabench::bench
