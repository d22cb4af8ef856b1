// The track-before-detect kind (harness/run/problem_kind.hpp): K image frames, each tracker run
// frame by frame and scored by GOSPA per step (options in the experiment's [metrics]), with
// the steps, the estimates, the frames and, with `beliefs = true`, the beliefs in their own
// files (tbd_execution.hpp).
#include "harness/core/json.hpp"
#include "harness/run/kinds/registry_kind.hpp"
#include "harness/run/kinds/tbd_execution.hpp"
#include "harness/tbd/registry.hpp"

namespace dabench {

namespace {

class TbdKind final : public RegistryKind<TbdScenario, TbdTracker> {
 public:
  TbdKind() : RegistryKind(tbd_scenario_registry(), tbd_tracker_registry(), make_tbd_tracker) {}
  std::string_view name() const override { return "track-before-detect"; }
  std::string_view key() const override { return "tbd"; }
  std::string_view algorithm_noun() const override { return "track-before-detect tracker"; }
  std::string_view algorithms_title() const override { return "Track-before-detect trackers (for track-before-detect scenarios; frame by frame):"; }
  std::string_view scenarios_title() const override {
    return "Track-before-detect scenarios (K image frames of J data cells; experiment [metrics]: GOSPA c, p, alpha):";
  }
  bool records_beliefs() const override { return true; }
  bool has_metric_options() const override { return true; }
  void check_metric_options(const std::vector<KeyValue>& settings) const override {
    make_options<TbdMetricsOptions>(settings, "[metrics]");
  }
  const std::vector<std::string>& metric_columns() const override {
    static const std::vector<std::string> columns = {"n_steps",   "gospa",     "gospa_p2",     "localisation",
                                                     "missed",    "false",     "n_objects",    "n_estimates",
                                                     "step_time_us", "iterations", "converged"};
    return columns;
  }
  std::vector<ItemFile> item_files(const std::string& point_columns, const Experiment& experiment) const override {
    std::vector<ItemFile> files = {
        {"steps.csv", point_columns + ",trial,seed,algorithm,k,n_objects,n_estimates,gospa,gospa_p2,localisation,"
                                      "missed,false,time_us\n"},
        {"estimates.csv", point_columns + ",trial,algorithm,k,label,existence,x,y,vx,vy\n"},
        {"frames.csv", point_columns + ",trial,k,column,row,z1,z2\n"}};
    if (experiment.record_beliefs) {
      files.push_back({"beliefs.csv", point_columns + ",trial,algorithm,k,label,existence,x,y,weight\n"});
    }
    return files;
  }
  void add_meta(const Experiment& experiment, JsonObject& meta) const override {
    meta.add_raw("tbd_metrics", tbd_metrics_json(make_options<TbdMetricsOptions>(experiment.metric_settings, "[metrics]")));
  }
  std::string_view error_column() const override { return "gospa"; }
  AlgorithmTimeColumn time_column() const override { return {"step_time_us", 1e-6, "n_steps"}; }
  std::unique_ptr<RunExecution> make_execution(const RunPlan& plan) const override {
    return std::make_unique<TbdExecution>(plan, point_scenarios(plan),
                                          make_options<TbdMetricsOptions>(plan.experiment.metric_settings, "[metrics]"));
  }
};

}  // namespace

const ProblemKind& tbd_kind() {
  static const TbdKind kind;
  return kind;
}

}  // namespace dabench
