#include "harness/single_scan/registry.hpp"

namespace dabench {

Registry<SingleScanSolver>& single_scan_algorithm_registry() {
  static Registry<SingleScanSolver> registry;
  return registry;
}

Registry<SingleScanScenario>& single_scan_scenario_registry() {
  static Registry<SingleScanScenario> registry;
  return registry;
}

std::unique_ptr<SingleScanSolver> make_single_scan_solver(std::string_view spec) {
  return single_scan_algorithm_registry().make(spec, "algorithm");
}

}  // namespace dabench
