#include "harness/single_scan/registry.hpp"

#include <fmt/format.h>

#include "harness/core/errors.hpp"

namespace dabench {

Registry<SingleScanSolver>& single_scan_algorithm_registry() {
  static Registry<SingleScanSolver> registry;
  return registry;
}

Registry<SingleScanScenario>& single_scan_scenario_registry() {
  static Registry<SingleScanScenario> registry;
  return registry;
}

std::unique_ptr<SingleScanSolver> make_single_scan_solver(std::string_view spec_text) {
  const Spec spec = parse_spec(spec_text);
  const auto* entry = single_scan_algorithm_registry().find(spec.name);
  if (entry == nullptr) {
    throw InputError(fmt::format("unknown algorithm '{}' (known: {})", spec.name, single_scan_algorithm_registry().names()));
  }
  return entry->create(spec.settings);
}

}  // namespace dabench
