// Multiple-scan methods of multiscan-convex-variational on the paper's own problem: the
// `bearings` scenario (Sec. IV) with exactly 8 targets, trials 0–3 of seed 2017. Arguments:
// scans per sensor (1: 4 scans, 3: 12 scans), particles per track, trial. The targets:
// one 12-scan, 8-target CVS(0.95) trial at 10 000 particles per track in ≤ 1 s on one core, CV
// the same (column-dual Newton, the default solver). Algorithm 2 (solver=pdca) runs on the same
// trials at 300 particles and 4 scans, where it finishes in seconds to a minute (12 scans at
// 10 000 particles would take about an hour per trial); compare it with the Newton runs of the
// same arguments. Counters: iterations (Newton iterations, or sweeps), line_search_steps,
// converged. Run pinned for stable numbers:
//   taskset -c 1 ./build/dabench_bench --benchmark_filter=bearings --benchmark_repetitions=3
#include <benchmark/benchmark.h>

#include <memory>
#include <string>

#include "harness/core/params.hpp"
#include "harness/multi_scan/registry.hpp"
#include "scenarios/multi_scan/bearings.hpp"

namespace dabench::bench {
namespace {

MultiScanSample bearings_sample(int scans_per_sensor, int particles, int trial) {
  const BearingsScenario scenario(make_options<BearingsOptions>({{"mean_targets", "8"},
                                                                 {"poisson_targets", "0"},
                                                                 {"particles", std::to_string(particles)},
                                                                 {"scans_per_sensor", std::to_string(scans_per_sensor)}},
                                                                "bearings"));
  RandomStream rng(2017, 0, static_cast<std::uint32_t>(trial));
  MultiScanSample sample;
  scenario.generate(rng, sample);
  return sample;
}

void bearings_trial(benchmark::State& state, const std::string& spec) {
  const MultiScanSample sample =
      bearings_sample(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)), static_cast<int>(state.range(2)));
  const std::unique_ptr<MultiScanSolver> solver = make_multi_scan_solver(spec);
  MultiScanBeliefs beliefs;
  SolveReport report;
  for (auto _ : state) {
    solver->solve(sample.problem, beliefs, report);
    benchmark::DoNotOptimize(beliefs.track.data());
  }
  if (!report.skipped.empty()) state.SkipWithError(("skipped:" + report.skipped).c_str());
  state.counters["iterations"] = report.iterations;
  state.counters["line_search_steps"] = report.line_search_steps;
  state.counters["converged"] = report.converged;
}

// 12 scans, 10 000 particles: the targets.
void full_size(benchmark::internal::Benchmark* b) {
  for (int trial = 0; trial < 4; ++trial) b->Args({3, 10000, trial});
  b->Unit(benchmark::kMillisecond)->Iterations(1);
}
// 4 scans, 300 particles: Algorithm 2 and L-BFGS beside Newton on the same trials.
void small(benchmark::internal::Benchmark* b) {
  for (int trial = 0; trial < 4; ++trial) b->Args({1, 300, trial});
  b->Unit(benchmark::kMillisecond)->Iterations(1);
}

BENCHMARK_CAPTURE(bearings_trial, cvs, std::string("cvs"))->Apply(full_size);
BENCHMARK_CAPTURE(bearings_trial, cv, std::string("cv"))->Apply(full_size);
BENCHMARK_CAPTURE(bearings_trial, cvh, std::string("cvh"))->Apply(full_size);
BENCHMARK_CAPTURE(bearings_trial, cvsh, std::string("cvsh"))->Apply(full_size);
BENCHMARK_CAPTURE(bearings_trial, cvsh1, std::string("cvsh1"))->Apply(full_size);
BENCHMARK_CAPTURE(bearings_trial, msbp, std::string("msbp"))->Apply(full_size);
BENCHMARK_CAPTURE(bearings_trial, jpda_bp, std::string("jpda-bp"))->Apply(full_size);
BENCHMARK_CAPTURE(bearings_trial, cvs_newton, std::string("cvs"))->Apply(small);
BENCHMARK_CAPTURE(bearings_trial, cvs_pdca, std::string("cvs:solver=pdca"))->Apply(small);
BENCHMARK_CAPTURE(bearings_trial, cv_newton, std::string("cv"))->Apply(small);
BENCHMARK_CAPTURE(bearings_trial, cv_pdca, std::string("cv:solver=pdca"))->Apply(small);
BENCHMARK_CAPTURE(bearings_trial, cvs_lbfgs, std::string("cvs:solver=lbfgs"))->Apply(small);
BENCHMARK_CAPTURE(bearings_trial, cv_lbfgs, std::string("cv:solver=lbfgs"))->Apply(small);

}  // namespace
}  // namespace dabench::bench
