#include "harness/run/run_plan.hpp"

#include <omp.h>

#include <algorithm>
#include <utility>

#include <fmt/format.h>

#include "harness/core/csv.hpp"
#include "harness/multi_scan/registry.hpp"
#include "harness/single_scan/registry.hpp"
#include "harness/tbd/metrics.hpp"
#include "harness/tbd/registry.hpp"
#include "harness/tracking/metrics.hpp"
#include "harness/tracking/registry.hpp"

namespace dabench {

namespace {

std::string point_columns(const std::vector<KeyValue>& params) {
  std::string header = "point";
  for (const KeyValue& kv : params) {
    header += ',';
    append_csv_field(header, kv.key);
  }
  return header;
}

std::string_view kind_name(RunKind kind) {
  switch (kind) {
    case RunKind::single_scan: return "single-scan";
    case RunKind::multi_scan: return "multi-scan";
    case RunKind::tracking: return "tracking";
    case RunKind::tbd: return "track-before-detect";
  }
  return {};
}

// A SPEC naming an algorithm of another kind than the scenario's: say so.
std::string kind_hint(const std::string& spec, RunKind kind, const std::string& scenario) {
  std::string name;
  try {
    name = parse_spec(spec).name;
  } catch (const InputError&) {
    return {};
  }
  const auto hint = [&](std::string_view what) {
    return fmt::format(" ('{}' is a {}; scenario '{}' is {})", name, what, scenario, kind_name(kind));
  };
  if (kind != RunKind::single_scan && single_scan_algorithm_registry().find(name) != nullptr) return hint("single-scan algorithm");
  if (kind != RunKind::multi_scan && multi_scan_algorithm_registry().find(name) != nullptr) return hint("multi-scan algorithm");
  if (kind != RunKind::tracking && tracking_tracker_registry().find(name) != nullptr) return hint("tracker");
  if (kind != RunKind::tbd && tbd_tracker_registry().find(name) != nullptr) return hint("track-before-detect tracker");
  return {};
}

void check_spec(const std::string& spec, RunKind kind) {
  switch (kind) {
    case RunKind::single_scan: make_single_scan_solver(spec); return;
    case RunKind::multi_scan: make_multi_scan_solver(spec); return;
    case RunKind::tracking: make_tracker(spec); return;
    case RunKind::tbd: make_tbd_tracker(spec); return;
  }
}

}  // namespace

const std::vector<std::string>& RunPlan::metric_columns() const {
  switch (kind) {
    case RunKind::multi_scan: return multi_scan_metric_columns();
    case RunKind::tracking: return tracking_metric_columns();
    case RunKind::tbd: return tbd_metric_columns();
    case RunKind::single_scan: break;
  }
  return single_scan_metric_columns();
}

std::string RunPlan::trials_header() const {
  std::string header = point_columns(point_params.front()) + ",trial,seed,algorithm,status";
  for (const std::string& metric : metric_columns()) header += "," + metric;
  return header + "\n";
}

std::vector<std::string> RunPlan::output_files() const {
  std::vector<std::string> names = {"trials.csv", "summary.csv", "meta.json", "checksums.csv"};
  for (const ItemFile& file : item_files()) names.push_back(file.name);
  return names;
}

std::vector<ItemFile> RunPlan::item_files() const {
  const std::string point = point_columns(point_params.front());
  switch (kind) {
    case RunKind::multi_scan: return {{"targets.csv", point + ",trial,seed,algorithm,target,hpd,entropy,hpd_likelihood\n"}};
    case RunKind::tracking: {
      std::vector<ItemFile> files = {
          {"tracks.csv", point + ",trial,algorithm,track,confirmed,scan,g,g_dot,theta,theta_dot,"
                                 "var_g,var_g_dot,var_theta,var_theta_dot\n"},
          {"measurements.csv", point + ",trial,scan,r,r_dot,azimuth,origin_target,origin_path\n"}};
      if (experiment.record_iterations) {
        std::string header = point + ",trial,seed,algorithm,iteration";
        for (const std::string& metric : tracking_iteration_metric_columns()) header += "," + metric;
        files.push_back({"iterations.csv", header + "\n"});
      }
      return files;
    }
    case RunKind::tbd: {
      std::vector<ItemFile> files = {
          {"steps.csv", point + ",trial,seed,algorithm,k,n_objects,n_estimates,gospa,gospa_p2,localisation,missed,"
                                "false,time_us\n"},
          {"estimates.csv", point + ",trial,algorithm,k,label,existence,x,y,vx,vy\n"},
          {"frames.csv", point + ",trial,k,column,row,z1,z2\n"}};
      if (experiment.record_beliefs) files.push_back({"beliefs.csv", point + ",trial,algorithm,k,label,existence,x,y,weight\n"});
      return files;
    }
    case RunKind::single_scan: break;
  }
  return {};
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
  if (experiment.record_iterations) mix("iterations");  // runs without it keep their fingerprint
  if (experiment.record_beliefs) mix("beliefs");
  for (const KeyValue& kv : experiment.metric_settings) mix("metrics." + kv.key + "=" + kv.value);
  return fmt::format("{:016x}", hash);
}

long long RunPlan::shard_items() const {
  if (!shard) return items();
  const long long blocks = (items() + kItemsPerBlock - 1) / kItemsPerBlock;
  const long long first = shard->index - 1;
  if (first >= blocks) return 0;
  const long long own_blocks = (blocks - 1 - first) / shard->count + 1;
  const long long last = first + (own_blocks - 1) * shard->count;  // its last block, maybe short
  return (own_blocks - 1) * kItemsPerBlock + std::min(kItemsPerBlock, items() - last * kItemsPerBlock);
}

long long RunPlan::global_item(long long local) const {
  if (!shard) return local;
  const long long block = (local / kItemsPerBlock) * shard->count + (shard->index - 1);
  return block * kItemsPerBlock + local % kItemsPerBlock;
}

long long RunPlan::local_item(long long global) const {
  if (global < 0 || global >= items()) return -1;
  if (!shard) return global;
  const long long block = global / kItemsPerBlock;
  if (block % shard->count != shard->index - 1) return -1;
  return (block / shard->count) * kItemsPerBlock + global % kItemsPerBlock;
}

std::string RunPlan::shard_label() const { return shard ? fmt::format("{}/{}", shard->index, shard->count) : std::string(); }

std::vector<std::string> RunPlan::point_row_prefixes() const {
  std::vector<std::string> prefixes;
  for (std::size_t p = 0; p < point_params.size(); ++p) {
    std::string prefix = std::to_string(p);
    for (const KeyValue& kv : point_params[p]) {
      prefix += ',';
      append_csv_field(prefix, kv.value);
    }
    prefixes.push_back(std::move(prefix));
  }
  return prefixes;
}

std::vector<std::string> RunPlan::spec_fields() const {
  std::vector<std::string> fields;
  for (const std::string& spec : specs) {
    std::string field;
    append_csv_field(field, spec);
    fields.push_back(std::move(field));
  }
  return fields;
}

RunPlan make_run_plan(const RunOptions& options) { return make_run_plan(load_experiment(options.experiment_path), options); }

RunPlan make_run_plan(Experiment loaded, const RunOptions& options) {
  RunPlan plan;
  plan.experiment = std::move(loaded);
  const Experiment& experiment = plan.experiment;
  const std::string& path = experiment.path;
  plan.trials = options.trials.value_or(experiment.trials);
  if (plan.trials < 1) throw InputError(fmt::format("--trials must be >= 1 (got {})", plan.trials));
  if (plan.trials > 0x7fffffff) throw InputError("--trials must be below 2^31");
  plan.seed = options.seed.value_or(experiment.seed);
  plan.threads = options.threads.value_or(omp_get_max_threads());
  if (plan.threads < 1 || plan.threads > 1024) throw InputError(fmt::format("--threads must be in 1..1024 (got {})", plan.threads));
  plan.shard = options.shard;
  if (plan.shard && !(plan.shard->count >= 1 && plan.shard->index >= 1 && plan.shard->index <= plan.shard->count)) {
    throw InputError(fmt::format("--shard {}: K/N needs 1 <= K <= N", plan.shard_label()));
  }
  plan.output = options.output.value_or(
      plan.shard ? fmt::format("{}-shard-{}-of-{}", experiment.output, plan.shard->index, plan.shard->count)
                 : experiment.output);

  const auto* single_scan = single_scan_scenario_registry().find(experiment.scenario);
  const auto* multi_scan = multi_scan_scenario_registry().find(experiment.scenario);
  const auto* tracking = tracking_scenario_registry().find(experiment.scenario);
  const auto* tbd = tbd_scenario_registry().find(experiment.scenario);
  if (single_scan == nullptr && multi_scan == nullptr && tracking == nullptr && tbd == nullptr) {
    std::string known = single_scan_scenario_registry().names();
    for (const std::string& more : {multi_scan_scenario_registry().names(), tracking_scenario_registry().names(),
                                    tbd_scenario_registry().names()}) {
      if (!more.empty()) known += ", " + more;
    }
    throw InputError(fmt::format("{}: unknown scenario '{}' (known: {})", path, experiment.scenario, known));
  }
  plan.kind = multi_scan != nullptr ? RunKind::multi_scan
              : tracking != nullptr ? RunKind::tracking
              : tbd != nullptr      ? RunKind::tbd
                                    : RunKind::single_scan;
  if (!experiment.metric_settings.empty()) {
    if (plan.kind != RunKind::tbd && plan.kind != RunKind::tracking) {
      throw InputError(fmt::format("{}: scenario '{}' is {}, whose metrics have no [metrics] options (remove the "
                                   "section)", path, experiment.scenario, kind_name(plan.kind)));
    }
    try {
      if (plan.kind == RunKind::tbd) make_options<TbdMetricsOptions>(experiment.metric_settings, "[metrics]");
      else make_options<TrackingMetricsOptions>(experiment.metric_settings, "[metrics]");
    } catch (const InputError& error) {
      throw InputError(fmt::format("{}: {}", path, error.what()));
    }
  }
  if (experiment.record_iterations && plan.kind != RunKind::tracking) {
    throw InputError(fmt::format("{}: 'iterations = true' records tracker iterations, but scenario '{}' is {} "
                                 "(remove the line)", path, experiment.scenario, kind_name(plan.kind)));
  }
  if (experiment.record_beliefs && plan.kind != RunKind::tbd) {
    throw InputError(fmt::format("{}: 'beliefs = true' records track-before-detect beliefs, but scenario '{}' is {} "
                                 "(remove the line)", path, experiment.scenario, kind_name(plan.kind)));
  }
  if (plan.kind != RunKind::single_scan && !experiment.references.empty()) {
    throw InputError(fmt::format("{}: scenario '{}' is {}: its metrics are against the truth, so "
                                 "'reference' lines are not used (remove them)", path, experiment.scenario,
                                 kind_name(plan.kind)));
  }
  const auto resolve = [&](std::size_t p) {
    try {
      const std::vector<KeyValue>& settings = experiment.points[p];
      return multi_scan != nullptr ? multi_scan->resolve(settings)
             : tracking != nullptr ? tracking->resolve(settings)
             : tbd != nullptr      ? tbd->resolve(settings)
                                   : single_scan->resolve(settings);
    } catch (const InputError& error) {
      throw InputError(fmt::format("{}: sweep point {}: {}", path, p, error.what()));
    }
  };
  // First the points whose keys differ from the point before (each sweep block's first): a
  // misspelt key is reported at once, not after every point of the blocks before it (a sweep may
  // have 10^6 points, each checked in turn below).
  const auto same_keys = [](const std::vector<KeyValue>& a, const std::vector<KeyValue>& b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end(),
                      [](const KeyValue& x, const KeyValue& y) { return x.key == y.key; });
  };
  for (std::size_t p = 0; p < experiment.points.size(); ++p) {
    if (p == 0 || !same_keys(experiment.points[p], experiment.points[p - 1])) (void)resolve(p);
  }
  plan.point_params.reserve(experiment.points.size());
  for (std::size_t p = 0; p < experiment.points.size(); ++p) plan.point_params.push_back(resolve(p));
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
      check_spec(spec, plan.kind);
    } catch (const InputError& error) {
      throw InputError(fmt::format("{}: {}{}", path, error.what(), kind_hint(spec, plan.kind, experiment.scenario)));
    }
  }
  return plan;
}

}  // namespace dabench
