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

#include "bench/single_scan/grid_timing.hpp"

namespace dabench::bench {

BENCHMARK_CAPTURE(solve_grid, lmipda_2x3_s0, "lmipda", 2, 3, 0.0)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(solve_grid, lmipda_2x3_s3, "lmipda", 2, 3, 3.0)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(solve_grid, lmipda_3x30_s3, "lmipda", 3, 30, 3.0)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(solve_grid, baa_2x3_s0, "baa", 2, 3, 0.0)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(solve_grid, baa_2x3_s3, "baa", 2, 3, 3.0)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(solve_grid, baa_3x30_s3, "baa", 3, 30, 3.0)->Unit(benchmark::kMicrosecond);

}  // namespace dabench::bench
