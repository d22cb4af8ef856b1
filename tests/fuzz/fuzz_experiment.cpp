// libFuzzer target: an experiment file's text through the parser and the run planner, as
// `dabench run FILE` reads it before any output is written (harness/core/experiment.hpp,
// harness/run/run_plan.hpp). Any input must give a plan or an InputError; anything else (another
// exception, a crash, a sanitizer report, a hang, memory beyond libFuzzer's limit) is a finding.
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>

#include "harness/core/errors.hpp"
#include "harness/core/experiment.hpp"
#include "harness/run/run_plan.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace dabench;
  RunOptions options;
  options.threads = 1;
  options.output = "fuzz-output";  // the plan names it; nothing is written
  try {
    Experiment experiment = parse_experiment("fuzz.ini", std::string(reinterpret_cast<const char*>(data), size));
    // Planning checks every sweep point alike, ~10 µs each here under ASan: past 10^4 points an
    // input would only spend the 10 s budget repeating checks (the parser bounds sweeps at 10^6).
    if (experiment.points.size() > 10000) return 0;
    const RunPlan plan = make_run_plan(std::move(experiment), options);
    // What a run computes from the plan before its first trial.
    (void)plan.fingerprint();
    (void)plan.trials_header();
    (void)plan.item_files();
    (void)plan.point_row_prefixes();
    (void)plan.spec_fields();
  } catch (const InputError&) {
  }
  return 0;
}
