// The single-scan kind (harness/run/problem_kind.hpp): problems of one scan's weights ψ, every
// algorithm against the experiment's reference on the same draw (single_scan_execution.hpp).
#include "harness/run/kinds/registry_kind.hpp"
#include "harness/run/kinds/single_scan_execution.hpp"
#include "harness/single_scan/registry.hpp"

namespace dabench {

namespace {

class SingleScanKind final : public RegistryKind<SingleScanScenario, SingleScanSolver> {
 public:
  SingleScanKind()
      : RegistryKind(single_scan_scenario_registry(), single_scan_algorithm_registry(), make_single_scan_solver) {}
  std::string_view name() const override { return "single-scan"; }
  std::string_view key() const override { return "single_scan"; }
  std::string_view algorithm_noun() const override { return "single-scan algorithm"; }
  std::string_view algorithms_title() const override { return "Algorithms (SPEC = name or name:key=value,...):"; }
  std::string_view scenarios_title() const override {
    return "Scenarios (parameters settable in an experiment's [scenario] and [sweep] sections):";
  }
  bool shares_items() const override { return true; }
  const std::vector<std::string>& metric_columns() const override {
    static const std::vector<std::string> columns = {"n_targets", "n_measurements", "max_error", "mean_error",
                                                     "time_us",   "iterations",     "converged", "w_star"};
    return columns;
  }
  std::string_view error_column() const override { return "max_error"; }
  AlgorithmTimeColumn time_column() const override { return {"time_us", 1e-6}; }
  std::unique_ptr<RunExecution> make_execution(const RunPlan& plan) const override {
    return std::make_unique<SingleScanExecution>(plan, point_scenarios(plan));
  }
};

}  // namespace

const ProblemKind& single_scan_kind() {
  static const SingleScanKind kind;
  return kind;
}

}  // namespace dabench
