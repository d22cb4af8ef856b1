#include "harness/tracking/registry.hpp"

namespace dabench {

Registry<Tracker>& tracking_tracker_registry() {
  static Registry<Tracker> registry;
  return registry;
}

Registry<TrackingScenario>& tracking_scenario_registry() {
  static Registry<TrackingScenario> registry;
  return registry;
}

std::unique_ptr<Tracker> make_tracker(std::string_view spec) {
  return tracking_tracker_registry().make(spec, "tracker");
}

}  // namespace dabench
