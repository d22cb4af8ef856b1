#include "harness/run_plan.hpp"

#include <omp.h>

#include <fmt/format.h>

#include "harness/csv.hpp"
#include "harness/registry.hpp"

namespace dabench {

std::string RunPlan::trials_header() const {
  std::string header = "point";
  for (const KeyValue& kv : point_params.front()) {
    header += ',';
    append_csv_field(header, kv.key);
  }
  header += ",trial,seed,algorithm,status";
  for (const std::string& metric : single_scan_metric_columns()) header += "," + metric;
  return header + "\n";
}

std::string RunPlan::fingerprint() const {
  // FNV-1a over everything that determines the rows.
  std::uint64_t hash = 1469598103934665603ull;
  const auto mix = [&hash](std::string_view text) {
    for (const char c : text) {
      hash ^= static_cast<unsigned char>(c);
      hash *= 1099511628211ull;
    }
    hash ^= 0xff;
    hash *= 1099511628211ull;
  };
  mix(experiment.scenario);
  for (const auto& params : point_params) {
    for (const KeyValue& kv : params) mix(kv.key + "=" + kv.value);
  }
  for (const auto& spec : specs) mix(spec);
  mix(std::to_string(trials));
  mix(std::to_string(seed));
  return fmt::format("{:016x}", hash);
}

RunPlan make_run_plan(const RunOptions& options) {
  RunPlan plan;
  plan.experiment = load_experiment(options.experiment_path);
  const Experiment& experiment = plan.experiment;
  const std::string& path = experiment.path;
  plan.trials = options.trials.value_or(experiment.trials);
  if (plan.trials < 1) throw InputError(fmt::format("--trials must be >= 1 (got {})", plan.trials));
  if (plan.trials > 0x7fffffff) throw InputError("--trials must be below 2^31");
  plan.seed = options.seed.value_or(experiment.seed);
  plan.threads = options.threads.value_or(omp_get_max_threads());
  if (plan.threads < 1 || plan.threads > 1024) throw InputError(fmt::format("--threads must be in 1..1024 (got {})", plan.threads));
  plan.output = options.output.value_or(experiment.output);

  const auto* scenario = scenario_registry().find(experiment.scenario);
  if (scenario == nullptr) {
    throw InputError(fmt::format("{}: unknown scenario '{}' (known: {})", path, experiment.scenario,
                                 scenario_registry().names()));
  }
  for (std::size_t p = 0; p < experiment.points.size(); ++p) {
    try {
      plan.point_params.push_back(scenario->resolve(experiment.points[p]));
    } catch (const InputError& error) {
      throw InputError(fmt::format("{}: sweep point {}: {}", path, p, error.what()));
    }
  }
  plan.point_settings = experiment.points;

  for (const std::string& spec : experiment.references) {
    const std::string text(trim(spec));
    for (const auto& known : plan.specs) {
      if (known == text) throw InputError(fmt::format("{}: reference '{}' given twice", path, text));
    }
    plan.specs.push_back(text);
  }
  plan.references = static_cast<int>(plan.specs.size());
  for (const std::string& spec : experiment.algorithms) {
    const std::string text(trim(spec));
    bool duplicate = false;
    for (const auto& known : plan.specs) duplicate = duplicate || known == text;
    if (!duplicate) plan.specs.push_back(text);
  }
  for (const std::string& spec : plan.specs) {
    try {
      make_single_scan_solver(spec);
    } catch (const InputError& error) {
      throw InputError(fmt::format("{}: {}", path, error.what()));
    }
  }
  return plan;
}

}  // namespace dabench
