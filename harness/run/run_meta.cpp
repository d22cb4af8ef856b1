#include "harness/run/run_meta.hpp"

#include <unistd.h>

#include <ctime>
#include <filesystem>

#include <fmt/format.h>

#include "harness/core/build_info.hpp"
#include "harness/core/errors.hpp"
#include "harness/core/input_file.hpp"
#include "harness/core/json.hpp"
#include "harness/core/params.hpp"

namespace dabench {

void require_complete_run(const std::string& folder, std::string_view command) {
  const std::string path = (std::filesystem::path(folder) / "meta.json").string();
  std::error_code error;
  if (!std::filesystem::exists(path, error)) return;
  const auto status = json_value(read_input_file(path, "run meta.json", kMaxMetaBytes), "status");
  if (!status || *status == "complete") return;  // (a meta.json written by hand may say nothing)
  throw InputError(fmt::format("{}: {}: the run is {} (meta.json), not complete; finish it with `dabench run ... --resume` "
                               "first", command, folder, *status == "running" ? "still running, or was killed" : *status));
}

const ProblemKind& recorded_kind(const std::string& folder, std::string_view command) {
  const std::string path = (std::filesystem::path(folder) / "meta.json").string();
  std::error_code error;
  if (!std::filesystem::exists(path, error)) {
    throw InputError(fmt::format("{}: {}: meta.json is missing (its scenario says the run's kind)", command, folder));
  }
  const auto scenario = json_value(read_input_file(path, "run meta.json", kMaxMetaBytes), "scenario");
  if (!scenario) throw InputError(fmt::format("{}: {}: no \"scenario\" (the run's kind)", command, path));
  const ProblemKind* kind = kind_of_scenario(*scenario);
  if (kind == nullptr) {
    throw InputError(fmt::format("{}: {}: scenario '{}' is of no problem kind this build knows", command, folder, *scenario));
  }
  return *kind;
}

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm parts{};
  gmtime_r(&now, &parts);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &parts);
  return text;
}

std::string host_name() {
  char name[256] = {};
  return gethostname(name, sizeof name - 1) == 0 ? std::string(name) : std::string("unknown");
}

RecordedBuild this_build() {
  const BuildInfo& build = build_info();
  RecordedBuild recorded;
  recorded.version = build.version;
  recorded.git_commit = build.git_commit;
  recorded.source_modified = build.source == Provenance::unknown    ? "null"
                             : build.source == Provenance::modified ? "true"
                                                                    : "false";
  recorded.compiler = build.compiler;
  recorded.flags = build.flags;
  recorded.build_type = build.build_type;
  return recorded;
}

std::string RecordedBuild::describe() const {
  const char* modified = source_modified == "true" ? ", modified source" : "";
  return fmt::format("dabench {} (git {}{}), {} {} {}", version, git_commit.substr(0, 12), modified, compiler, flags,
                     build_type);
}

std::string run_meta_json(const RunPlan& plan, const RunRecord& record) {
  const RecordedBuild build = record.build.value_or(this_build());
  const auto json_list = [](auto begin, auto end) {
    std::string list = "[";
    for (auto it = begin; it != end; ++it) list += (it == begin ? "" : ", ") + JsonObject::quote(*it);
    return list + "]";
  };
  const std::string specs = json_list(plan.specs.begin() + plan.references, plan.specs.end());
  const std::string references = json_list(plan.specs.begin(), plan.specs.begin() + plan.references);
  JsonObject meta;
  meta.add("schema", "dabench-run-1")
      .add("status", record.status)
      .add("fingerprint", plan.fingerprint());
  if (plan.shard) meta.add("shard", plan.shard_label()).add("shard_items", plan.shard_items());
  meta.add("command_line", record.command_line)
      .add("experiment_path", plan.experiment.path)
      .add("experiment_name", plan.experiment.name)
      .add("experiment", plan.experiment.text)
      .add("scenario", plan.experiment.scenario)
      .add("seed", static_cast<long long>(plan.seed))
      .add("trials_per_point", static_cast<long long>(plan.trials))
      .add("points", static_cast<long long>(plan.point_params.size()))
      .add("items_total", plan.items())
      .add("items_done", record.items_done)
      .add_raw("algorithms", specs)
      .add_raw("references", references)
      .add("version", build.version)
      .add("git_commit", build.git_commit)
      .add_raw("source_modified", build.source_modified)
      .add("compiler", build.compiler)
      .add("flags", build.flags)
      .add("build_type", build.build_type)
      .add("threads", static_cast<long long>(plan.threads))
      .add("processes", record.processes)
      .add("host", record.hosts);
  if (!record.rank_hosts.empty()) {
    std::string threads = "[";
    for (std::size_t k = 0; k < record.rank_threads.size(); ++k) threads += (k ? ", " : "") + std::to_string(record.rank_threads[k]);
    meta.add("ranks", static_cast<long long>(record.rank_hosts.size()))
        .add_raw("rank_threads", threads + "]")
        .add_raw("rank_hosts", json_list(record.rank_hosts.begin(), record.rank_hosts.end()));
  }
  meta
      .add("resumed", record.resumed)
      .add("start_time", record.start_time)
      .add("end_time", record.end_time)
      .add("wall_seconds", record.wall_seconds)
      .add("work_fraction", record.work_fraction);
  plan.kind->add_meta(plan.experiment, meta);
  if (!record.mixed_builds.empty()) {
    std::vector<std::string> builds;
    for (const RecordedBuild& shard : record.mixed_builds) builds.push_back(shard.describe());
    meta.add("allow_mixed", true).add_raw("shard_builds", json_list(builds.begin(), builds.end()));
  }
  if (plan.experiment.record_iterations) meta.add("record_iterations", true);
  if (plan.experiment.record_beliefs) meta.add("record_beliefs", true);
  return meta.str();
}

}  // namespace dabench
