// The tracking kind (harness/run/problem_kind.hpp): whole runs of K scans, each tracker scored
// against the truth (harness/tracking/metrics.hpp, options in the experiment's [metrics]), with
// the tracks, the measurements and, with `iterations = true`, the metrics per recorded
// iteration in their own files (tracking_execution.hpp).
#include "harness/core/json.hpp"
#include "harness/run/kinds/registry_kind.hpp"
#include "harness/run/kinds/tracking_execution.hpp"
#include "harness/tracking/registry.hpp"

namespace dabench {

namespace {

// Of iterations.csv: trials.csv's metric columns up to mospa_km, then free_energy (the recorded
// track set's objective).
const std::vector<std::string>& iteration_metric_columns() {
  static const std::vector<std::string> columns = {"nvt",          "tpd",          "nft",          "false_tracks",
                                                   "ghost_tracks", "broken_targets", "ttl_scans", "aee_range_km",
                                                   "aee_bearing_mrad", "mospa_km", "free_energy"};
  return columns;
}

class TrackingKind final : public RegistryKind<TrackingScenario, Tracker> {
 public:
  TrackingKind() : RegistryKind(tracking_scenario_registry(), tracking_tracker_registry(), make_tracker) {}
  std::string_view name() const override { return "tracking"; }
  std::string_view key() const override { return "tracking"; }
  std::string_view algorithm_noun() const override { return "tracker"; }
  std::string_view algorithms_title() const override { return "Trackers (for tracking scenarios):"; }
  std::string_view scenarios_title() const override {
    return "Tracking scenarios (whole runs of K scans, for trackers):";
  }
  void list_scenarios(std::string& out) const override {
    RegistryKind::list_scenarios(out);
    out += "  experiment [metrics] of tracking scenarios (harness/tracking/metrics.hpp):\n";
    TrackingMetricsOptions options;
    ParamList params;
    options.bind(params);
    for (const auto& param : params.entries()) {
      out += fmt::format("      {:<16} = {:<10} {}\n", param.key, ParamList::format(param), param.doc);
    }
  }
  bool records_iterations() const override { return true; }
  bool has_metric_options() const override { return true; }
  void check_metric_options(const std::vector<KeyValue>& settings) const override {
    make_options<TrackingMetricsOptions>(settings, "[metrics]");
  }
  const std::vector<std::string>& metric_columns() const override {
    static const std::vector<std::string> columns = {
        "nvt",          "tpd",              "nft",      "false_tracks", "ghost_tracks", "broken_targets", "ttl_scans",
        "aee_range_km", "aee_bearing_mrad", "mospa_km", "tet_s",        "iterations",   "converged",      "free_energy"};
    return columns;
  }
  std::vector<ItemFile> item_files(const std::string& point_columns, const Experiment& experiment) const override {
    std::vector<ItemFile> files = {
        {"tracks.csv", point_columns + ",trial,algorithm,track,confirmed,scan,g,g_dot,theta,theta_dot,"
                                       "var_g,var_g_dot,var_theta,var_theta_dot\n"},
        {"measurements.csv", point_columns + ",trial,scan,r,r_dot,azimuth,origin_target,origin_path\n"}};
    if (experiment.record_iterations) {
      std::string header = point_columns + ",trial,seed,algorithm,iteration";
      for (const std::string& metric : iteration_metric_columns()) header += "," + metric;
      files.push_back({"iterations.csv", header + "\n"});
    }
    return files;
  }
  void add_meta(const Experiment& experiment, JsonObject& meta) const override {
    meta.add_raw("tracking_metrics",
                 tracking_metrics_json(make_options<TrackingMetricsOptions>(experiment.metric_settings, "[metrics]")));
  }
  std::string_view error_column() const override { return "mospa_km"; }
  AlgorithmTimeColumn time_column() const override { return {"tet_s", 1.0}; }
  std::unique_ptr<RunExecution> make_execution(const RunPlan& plan) const override {
    return std::make_unique<TrackingExecution>(
        plan, point_scenarios(plan), make_options<TrackingMetricsOptions>(plan.experiment.metric_settings, "[metrics]"));
  }
};

}  // namespace

const ProblemKind& tracking_kind() {
  static const TrackingKind kind;
  return kind;
}

}  // namespace dabench
