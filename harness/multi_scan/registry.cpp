#include "harness/multi_scan/registry.hpp"

namespace dabench {

Registry<MultiScanSolver>& multi_scan_algorithm_registry() {
  static Registry<MultiScanSolver> registry;
  return registry;
}

Registry<MultiScanScenario>& multi_scan_scenario_registry() {
  static Registry<MultiScanScenario> registry;
  return registry;
}

std::unique_ptr<MultiScanSolver> make_multi_scan_solver(std::string_view spec) {
  return multi_scan_algorithm_registry().make(spec, "multi-scan algorithm");
}

}  // namespace dabench
