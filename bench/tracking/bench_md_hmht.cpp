// MD-HMHT (algorithms/tracking/md_hmht.hpp) on whole OTHR runs at the paper's four settings: the
// tracker call alone (TET of Table IV; the paper's MATLAB took 76-82 s at N_c = 125 and
// 1233-1279 s at N_c = 400), over a pool of 8 runs drawn once. Issue target: at most 1 s per
// run at N_c = 400 on one core. Counter: tracks = mean confirmed tracks output per run.
#include <benchmark/benchmark.h>

#include "bench/tracking/othr_pool.hpp"
#include "harness/tracking/registry.hpp"

namespace dabench::bench {
namespace {

void md_hmht(benchmark::State& state) {
  const double pd = static_cast<double>(state.range(0)) / 100.0, clutter = static_cast<double>(state.range(1));
  const auto pool = othr_pool(pd, clutter);
  auto tracker = make_tracker("md-hmht");
  TrackSet tracks;
  SolveReport report;
  double output = 0.0, calls = 0.0;
  std::size_t next = 0;
  for (auto _ : state) {
    tracker->run(pool[next].problem, tracks, report);
    benchmark::DoNotOptimize(tracks.tracks.data());
    output += static_cast<double>(tracks.tracks.size());
    calls += 1.0;
    next = (next + 1) % pool.size();
  }
  state.counters["tracks"] = output / calls;
}

BENCHMARK(md_hmht)->ArgNames({"pd%", "clutter"})->Args({75, 125})->Args({75, 400})->Args({40, 125})->Args({40, 400})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace dabench::bench
