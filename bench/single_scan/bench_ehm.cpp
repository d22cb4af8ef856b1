// `ehm` (efficient hypothesis management, exact marginals) on the grid problems of
// bp-marginal-association Sec. V at baseline (Pd 0.6, λ_fa 0.01, r 1): experiment 1's 2×3 grid,
// experiment 2's 3×n grids and experiment 3's n×n grids at spacing 3.
//
// Pools: 512 instances for 2×3 (each solved 32 times in a row for the median), 64 for the
// large grids (16 for a comparison variant on 10×10). Counters:
//   median_us, max_us  over solved instances;  skipped  instances refused by the work limit
//   max_width  largest net layer over the pool;  mean_nodes  mean net nodes per instance
//   max_bits   largest key space |K(t)| (shared measurements a node key can hold)
// Variants compare EHM2 (tree=1, default) with plain EHM (tree=0) and the target orders
// (order=0 auto = cheapest estimated of the others, 1 greedy min-frontier, 2 Cuthill–McKee BFS,
// 3 input order). Large grids run one pass over the pool (one solve per instance); instances
// refused by the work limit (default max_nodes) are counted in `skipped`, not timed.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>

#include "algorithms/single_scan/ehm.hpp"
#include "bench/single_scan/problem_pool.hpp"

namespace dabench::bench {
namespace {

struct PoolSummary {
  std::vector<double> times_us;  // per solved instance
  double nodes = 0.0;
  int width = 0, bits = 0, skipped = 0;
};

// Solves every instance of the pool `repeats` times in a row; per-instance time = mean of the repeats.
PoolSummary time_pool(SingleScanSolver& solver, const std::vector<SingleScanProblem>& pool, int repeats) {
  const auto* ehm = dynamic_cast<const Ehm*>(&solver);
  MarginalTable marginals;
  SolveReport report;
  PoolSummary summary;
  for (const auto& problem : pool) {
    const auto start = std::chrono::steady_clock::now();
    for (int r = 0; r < repeats; ++r) {
      solver.solve(problem, marginals, report);
      benchmark::DoNotOptimize(marginals.row(0));
    }
    const double us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count() / repeats;
    if (!report.skipped.empty()) {
      ++summary.skipped;
    } else {
      summary.times_us.push_back(us);
    }
    if (ehm != nullptr) {
      summary.nodes += static_cast<double>(ehm->stats().nodes);
      summary.width = std::max(summary.width, ehm->stats().max_layer_width);
      summary.bits = std::max(summary.bits, ehm->stats().max_key_bits);
    }
  }
  return summary;
}

// Small problems: the timed loop cycles through the pool; counters from a separate pass with
// `repeats` solves per instance. Large problems (repeats == 0): each benchmark iteration is one
// pass over the pool, one solve per instance, and the counters come from that pass.
// Counters: median_us / max_us over solved instances, skipped = instances refused by the work
// limit, max_width, mean_nodes (per instance; a refused one builds none), max_bits.
void solve_grid_ehm(benchmark::State& state, const char* spec, int rows, int cols, double spacing, int pool_size,
                    int repeats) {
  const auto pool = grid_pool({{"rows", std::to_string(rows)}, {"cols", std::to_string(cols)},
                               {"spacing", std::to_string(spacing)}}, pool_size);
  const auto solver = make_single_scan_solver(spec);
  PoolSummary summary;
  if (repeats > 0) {
    MarginalTable marginals;
    SolveReport report;
    std::size_t next = 0;
    for (auto _ : state) {
      solver->solve(pool[next], marginals, report);
      benchmark::DoNotOptimize(marginals.row(0));
      next = next + 1 == pool.size() ? 0 : next + 1;
    }
    summary = time_pool(*solver, pool, repeats);
  } else {
    for (auto _ : state) summary = time_pool(*solver, pool, 1);
  }
  auto& times = summary.times_us;
  if (!times.empty()) {
    std::nth_element(times.begin(), times.begin() + static_cast<std::ptrdiff_t>(times.size() / 2), times.end());
    state.counters["median_us"] = times[times.size() / 2];
    state.counters["max_us"] = *std::max_element(times.begin(), times.end());
  }
  state.counters["skipped"] = summary.skipped;
  state.counters["max_width"] = summary.width;
  state.counters["mean_nodes"] = summary.nodes / static_cast<double>(pool.size());
  state.counters["max_bits"] = summary.bits;
  state.counters["targets"] = rows * cols;
}

}  // namespace

#define EHM_SMALL(name, spec, rows, cols, spacing) \
  BENCHMARK_CAPTURE(solve_grid_ehm, name, spec, rows, cols, spacing, 512, 32)->Unit(benchmark::kMicrosecond)
#define EHM_LARGE(name, spec, rows, cols, pool) \
  BENCHMARK_CAPTURE(solve_grid_ehm, name, spec, rows, cols, 3.0, pool, 0)->Unit(benchmark::kMillisecond)->Iterations(1)

// Experiment 1: 2×3 grid.
EHM_SMALL(ehm_2x3_s0, "ehm", 2, 3, 0.0);
EHM_SMALL(ehm_2x3_s3, "ehm", 2, 3, 3.0);
EHM_SMALL(ehm_2x3_s0_path, "ehm:tree=0", 2, 3, 0.0);
EHM_SMALL(ehm_2x3_s3_path, "ehm:tree=0", 2, 3, 3.0);
// Experiment 2: 3×n grids, spacing 3.
EHM_LARGE(ehm_3x5_s3, "ehm", 3, 5, 64);
EHM_LARGE(ehm_3x10_s3, "ehm", 3, 10, 64);
EHM_LARGE(ehm_3x20_s3, "ehm", 3, 20, 64);
EHM_LARGE(ehm_3x30_s3, "ehm", 3, 30, 64);
EHM_LARGE(ehm_3x30_s3_path, "ehm:tree=0", 3, 30, 64);
EHM_LARGE(ehm_3x30_s3_greedy, "ehm:order=1", 3, 30, 64);
EHM_LARGE(ehm_3x30_s3_bfs, "ehm:order=2", 3, 30, 64);
EHM_LARGE(ehm_3x10_s3_input, "ehm:order=3", 3, 10, 64);
// Experiment 3: n×n grids, spacing 3.
EHM_LARGE(ehm_5x5_s3, "ehm", 5, 5, 64);
EHM_LARGE(ehm_8x8_s3, "ehm", 8, 8, 64);
EHM_LARGE(ehm_8x8_s3_greedy, "ehm:order=1", 8, 8, 64);
EHM_LARGE(ehm_8x8_s3_bfs, "ehm:order=2", 8, 8, 64);
EHM_LARGE(ehm_10x10_s3, "ehm", 10, 10, 64);
EHM_LARGE(ehm_10x10_s3_path, "ehm:tree=0", 10, 10, 16);

}  // namespace dabench::bench
