// Track-before-detect trackers per time step (the supplement's Fig. 4): whole 50-step runs of
// the `tbd` scenario's `persistent` layout (objects that exist for all steps unless they leave
// the region) with N = 0, 1, 3, ..., 11 objects, drawn once. One iteration = start() and every
// step of one run; the counter s_per_step is the mean time per step (seconds, SI-prefixed:
// 4.5m = 4.5 ms), `reported` the mean number of objects reported per step. Issue target
// (TBD-BP, L = 2, default particles): at most 5 ms per step per object plus 5 ms for the J new
// potential objects, on one core.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "harness/tbd/registry.hpp"

namespace dabench::bench {
namespace {

TbdSample persistent_run(int objects) {
  const auto* entry = tbd_scenario_registry().find("tbd");
  const auto scenario = entry->create({{"layout", "persistent"}, {"objects", std::to_string(objects)}});
  TbdSample sample;
  RandomStream rng(2023, 0, static_cast<std::uint32_t>(objects));
  scenario->generate(rng, sample);
  sample.problem.trial_key = {2023, 0, static_cast<std::uint32_t>(objects)};
  return sample;
}

void tbd_step(benchmark::State& state, const std::string& spec) {
  const TbdSample sample = persistent_run(static_cast<int>(state.range(0)));
  auto tracker = make_tbd_tracker(spec);
  std::vector<TbdEstimate> estimates;
  SolveReport report;
  double reported = 0.0, steps = 0.0;
  for (auto _ : state) {
    tracker->start(sample.problem);
    for (int k = 0; k < sample.problem.steps(); ++k) {
      tracker->step(k, estimates, report);
      reported += static_cast<double>(estimates.size());
      steps += 1.0;
    }
  }
  state.counters["s_per_step"] = benchmark::Counter(steps, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["reported"] = reported / steps;
}

void tbd_bp_l1(benchmark::State& state) { tbd_step(state, "tbd-bp:iterations=1"); }
void tbd_bp_l2(benchmark::State& state) { tbd_step(state, "tbd-bp:iterations=2"); }

BENCHMARK(tbd_bp_l1)->ArgName("objects")->Arg(0)->Arg(1)->Arg(3)->Arg(5)->Arg(7)->Arg(9)->Arg(11)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(tbd_bp_l2)->ArgName("objects")->Arg(0)->Arg(1)->Arg(3)->Arg(5)->Arg(7)->Arg(9)->Arg(11)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace dabench::bench
