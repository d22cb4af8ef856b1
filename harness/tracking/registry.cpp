#include "harness/tracking/registry.hpp"

#include <fmt/format.h>

#include "harness/core/errors.hpp"

namespace dabench {

Registry<Tracker>& tracking_tracker_registry() {
  static Registry<Tracker> registry;
  return registry;
}

Registry<TrackingScenario>& tracking_scenario_registry() {
  static Registry<TrackingScenario> registry;
  return registry;
}

std::unique_ptr<Tracker> make_tracker(std::string_view spec_text) {
  const Spec spec = parse_spec(spec_text);
  const auto* entry = tracking_tracker_registry().find(spec.name);
  if (entry == nullptr) {
    const std::string known = tracking_tracker_registry().names();
    throw InputError(fmt::format("unknown tracker '{}' (known: {})", spec.name, known.empty() ? "none registered" : known));
  }
  return entry->create(spec.settings);
}

}  // namespace dabench
