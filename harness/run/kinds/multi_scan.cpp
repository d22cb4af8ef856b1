// The multi-scan kind (harness/run/problem_kind.hpp): particle/hypothesis tracks over several
// scans, each algorithm measured against the scenario's truth, with a row per target in
// targets.csv (multi_scan_execution.hpp).
#include "harness/multi_scan/registry.hpp"
#include "harness/run/kinds/multi_scan_execution.hpp"
#include "harness/run/kinds/registry_kind.hpp"

namespace dabench {

namespace {

class MultiScanKind final : public RegistryKind<MultiScanScenario, MultiScanSolver> {
 public:
  MultiScanKind() : RegistryKind(multi_scan_scenario_registry(), multi_scan_algorithm_registry(), make_multi_scan_solver) {}
  std::string_view name() const override { return "multi-scan"; }
  std::string_view key() const override { return "multi_scan"; }
  std::string_view algorithm_noun() const override { return "multi-scan algorithm"; }
  std::string_view algorithms_title() const override { return "Multi-scan algorithms (for multi-scan scenarios):"; }
  std::string_view scenarios_title() const override {
    return "Multi-scan scenarios (run multi-scan algorithms; metrics against the truth):";
  }
  const std::vector<std::string>& metric_columns() const override {
    static const std::vector<std::string> columns = {
        "n_targets", "n_scans",    "n_measurements", "mean_hpd",          "max_hpd",  "mean_entropy",
        "time_us",   "iterations", "converged",      "line_search_steps", "residual", "inner_residual"};
    return columns;
  }
  std::vector<ItemFile> item_files(const std::string& point_columns, const Experiment&) const override {
    return {{"targets.csv", point_columns + ",trial,seed,algorithm,target,hpd,entropy,hpd_likelihood\n"}};
  }
  std::string_view error_column() const override { return "mean_hpd"; }
  AlgorithmTimeColumn time_column() const override { return {"time_us", 1e-6}; }
  std::unique_ptr<RunExecution> make_execution(const RunPlan& plan) const override {
    return std::make_unique<MultiScanExecution>(plan, point_scenarios(plan));
  }
};

}  // namespace

const ProblemKind& multi_scan_kind() {
  static const MultiScanKind kind;
  return kind;
}

}  // namespace dabench
