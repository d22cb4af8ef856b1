// Fractional BP (`fbp`, Algorithm 1 of multiscan-convex-variational) against `bp` on the grid
// pools of bench_single_scan.cpp (2×3 at spacing 0 and 3, 3×10 at spacing 3), at γ = 1 (the
// BP energy) and γ = 0.5. Issue target: fbp within 3× of bp per problem.
//
// The timed loop solves the next problem of the pool with fbp (time = mean per problem).
// Counters: fbp_us and bp_us (median over the pool of per-problem times, each problem solved
// kRepeats times in a row), ratio_median / ratio_p95 / ratio_max (per-problem fbp/bp time
// ratios over the pool), fbp_iters and bp_iters (mean iterations). Both at their defaults:
// bp stops by the Theorem-3 rule at δ = 1e-3, fbp at max |Δ log y| < 1e-9.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>

#include "bench/single_scan/grid_timing.hpp"

namespace dabench::bench {
namespace {

struct PoolTimes {
  std::vector<double> us;  // per problem
  double mean_iterations = 0.0;
};

PoolTimes time_pool(SingleScanSolver& solver, const std::vector<SingleScanProblem>& pool) {
  MarginalTable marginals;
  SolveReport report;
  PoolTimes out;
  for (const auto& problem : pool) {
    const auto start = std::chrono::steady_clock::now();
    for (int r = 0; r < kRepeats; ++r) {
      solver.solve(problem, marginals, report);
      benchmark::DoNotOptimize(marginals.row(0));
    }
    out.us.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count() / kRepeats);
    out.mean_iterations += report.iterations;
  }
  out.mean_iterations /= static_cast<double>(pool.size());
  return out;
}

double quantile(std::vector<double> values, double p) {
  const auto k = static_cast<std::size_t>(p * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  return values[k];
}

void fbp_vs_bp(benchmark::State& state, const char* spec, int rows, int cols, double spacing) {
  const auto pool = grid_pool({{"rows", std::to_string(rows)}, {"cols", std::to_string(cols)},
                               {"spacing", std::to_string(spacing)}}, kPool);
  const auto fbp = make_single_scan_solver(spec);
  const auto bp = make_single_scan_solver("bp");
  MarginalTable marginals;
  SolveReport report;
  std::size_t next = 0;
  for (auto _ : state) {
    fbp->solve(pool[next], marginals, report);
    benchmark::DoNotOptimize(marginals.row(0));
    next = next + 1 == pool.size() ? 0 : next + 1;
  }
  const PoolTimes f = time_pool(*fbp, pool);
  const PoolTimes b = time_pool(*bp, pool);
  std::vector<double> ratios(pool.size());
  for (std::size_t k = 0; k < pool.size(); ++k) ratios[k] = f.us[k] / b.us[k];
  state.counters["fbp_us"] = quantile(f.us, 0.5);
  state.counters["bp_us"] = quantile(b.us, 0.5);
  state.counters["ratio_median"] = quantile(ratios, 0.5);
  state.counters["ratio_p95"] = quantile(ratios, 0.95);
  state.counters["ratio_max"] = *std::max_element(ratios.begin(), ratios.end());
  state.counters["fbp_iters"] = f.mean_iterations;
  state.counters["bp_iters"] = b.mean_iterations;
}

}  // namespace

BENCHMARK_CAPTURE(fbp_vs_bp, fbp_g1_2x3_s0, "fbp", 2, 3, 0.0)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(fbp_vs_bp, fbp_g1_2x3_s3, "fbp", 2, 3, 3.0)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(fbp_vs_bp, fbp_g1_3x10_s3, "fbp", 3, 10, 3.0)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(fbp_vs_bp, fbp_g0_5_2x3_s0, "fbp:gamma=0.5", 2, 3, 0.0)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(fbp_vs_bp, fbp_g0_5_2x3_s3, "fbp:gamma=0.5", 2, 3, 3.0)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(fbp_vs_bp, fbp_g0_5_3x10_s3, "fbp:gamma=0.5", 3, 10, 3.0)->Unit(benchmark::kMicrosecond);

}  // namespace dabench::bench
