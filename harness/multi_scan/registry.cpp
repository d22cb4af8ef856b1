#include "harness/multi_scan/registry.hpp"

#include <fmt/format.h>

#include "harness/core/errors.hpp"

namespace dabench {

Registry<MultiScanSolver>& multi_scan_algorithm_registry() {
  static Registry<MultiScanSolver> registry;
  return registry;
}

Registry<MultiScanScenario>& multi_scan_scenario_registry() {
  static Registry<MultiScanScenario> registry;
  return registry;
}

std::unique_ptr<MultiScanSolver> make_multi_scan_solver(std::string_view spec_text) {
  const Spec spec = parse_spec(spec_text);
  const auto* entry = multi_scan_algorithm_registry().find(spec.name);
  if (entry == nullptr) {
    throw InputError(fmt::format("unknown multi-scan algorithm '{}' (known: {})", spec.name,
                                 multi_scan_algorithm_registry().names()));
  }
  return entry->create(spec.settings);
}

}  // namespace dabench
