#include "harness/registry.hpp"

#include <fmt/format.h>

namespace dabench {

Registry<SingleScanSolver>& single_scan_registry() {
  static Registry<SingleScanSolver> registry;
  return registry;
}

Registry<MultiScanSolver>& multi_scan_registry() {
  static Registry<MultiScanSolver> registry;
  return registry;
}

Registry<SingleScanScenario>& scenario_registry() {
  static Registry<SingleScanScenario> registry;
  return registry;
}

Registry<MultiScanScenario>& multi_scan_scenario_registry() {
  static Registry<MultiScanScenario> registry;
  return registry;
}

Registry<Tracker>& tracker_registry() {
  static Registry<Tracker> registry;
  return registry;
}

Registry<TrackingScenario>& tracking_scenario_registry() {
  static Registry<TrackingScenario> registry;
  return registry;
}

std::unique_ptr<SingleScanSolver> make_single_scan_solver(std::string_view spec_text) {
  const Spec spec = parse_spec(spec_text);
  const auto* entry = single_scan_registry().find(spec.name);
  if (entry == nullptr) {
    throw InputError(fmt::format("unknown algorithm '{}' (known: {})", spec.name, single_scan_registry().names()));
  }
  return entry->create(spec.settings);
}

std::unique_ptr<MultiScanSolver> make_multi_scan_solver(std::string_view spec_text) {
  const Spec spec = parse_spec(spec_text);
  const auto* entry = multi_scan_registry().find(spec.name);
  if (entry == nullptr) {
    throw InputError(fmt::format("unknown multi-scan algorithm '{}' (known: {})", spec.name,
                                 multi_scan_registry().names()));
  }
  return entry->create(spec.settings);
}

std::unique_ptr<Tracker> make_tracker(std::string_view spec_text) {
  const Spec spec = parse_spec(spec_text);
  const auto* entry = tracker_registry().find(spec.name);
  if (entry == nullptr) {
    const std::string known = tracker_registry().names();
    throw InputError(fmt::format("unknown tracker '{}' (known: {})", spec.name, known.empty() ? "none registered" : known));
  }
  return entry->create(spec.settings);
}

}  // namespace dabench
