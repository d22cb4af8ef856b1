#include "harness/run/run_plan.hpp"

#include <omp.h>

#include <algorithm>
#include <utility>

#include <fmt/format.h>

#include "harness/core/csv.hpp"

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

// A SPEC naming an algorithm of another kind than the scenario's: say so.
std::string kind_hint(const std::string& spec, const ProblemKind& kind, const std::string& scenario) {
  std::string name;
  try {
    name = parse_spec(spec).name;
  } catch (const InputError&) {
    return {};
  }
  for (const ProblemKind* other : problem_kinds()) {
    if (other != &kind && other->has_algorithm(name)) {
      return fmt::format(" ('{}' is a {}; scenario '{}' is {})", name, other->algorithm_noun(), scenario, kind.name());
    }
  }
  return {};
}

}  // namespace

const std::vector<std::string>& RunPlan::metric_columns() const { return kind->metric_columns(); }

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
  return kind->item_files(point_columns(point_params.front()), experiment);
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

  plan.kind = kind_of_scenario(experiment.scenario);
  if (plan.kind == nullptr) {
    std::string known;
    for (const ProblemKind* kind : problem_kinds()) {
      const std::string names = kind->scenario_names();
      if (!names.empty()) known += (known.empty() ? "" : ", ") + names;
    }
    throw InputError(fmt::format("{}: unknown scenario '{}' (known: {})", path, experiment.scenario, known));
  }
  const ProblemKind& kind = *plan.kind;
  if (!experiment.metric_settings.empty()) {
    if (!kind.has_metric_options()) {
      throw InputError(fmt::format("{}: scenario '{}' is {}, whose metrics have no [metrics] options (remove the "
                                   "section)", path, experiment.scenario, kind.name()));
    }
    try {
      kind.check_metric_options(experiment.metric_settings);
    } catch (const InputError& error) {
      throw InputError(fmt::format("{}: {}", path, error.what()));
    }
  }
  if (experiment.record_iterations && !kind.records_iterations()) {
    throw InputError(fmt::format("{}: 'iterations = true' records tracker iterations, but scenario '{}' is {} "
                                 "(remove the line)", path, experiment.scenario, kind.name()));
  }
  if (experiment.record_beliefs && !kind.records_beliefs()) {
    throw InputError(fmt::format("{}: 'beliefs = true' records track-before-detect beliefs, but scenario '{}' is {} "
                                 "(remove the line)", path, experiment.scenario, kind.name()));
  }
  if (!kind.shares_items() && !experiment.references.empty()) {
    throw InputError(fmt::format("{}: scenario '{}' is {}: its metrics are against the truth, so "
                                 "'reference' lines are not used (remove them)", path, experiment.scenario,
                                 kind.name()));
  }
  const auto resolve = [&](std::size_t p) {
    try {
      return kind.resolve(experiment.scenario, experiment.points[p]);
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
      kind.check_algorithm(spec);
    } catch (const InputError& error) {
      throw InputError(fmt::format("{}: {}{}", path, error.what(), kind_hint(spec, kind, experiment.scenario)));
    }
  }
  return plan;
}

}  // namespace dabench
