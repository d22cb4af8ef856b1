#pragma once
// The registries of trackers (DABENCH_REGISTER_TRACKING_TRACKER) and tracking scenarios (DABENCH_REGISTER_TRACKING_SCENARIO).
// An algorithm registers itself with one line at the end of its source file, e.g.
//
//   DABENCH_REGISTER_TRACKING_TRACKER(MyAlgorithm);
//
// (see harness/core/registry.hpp for what the class provides).
#include <memory>
#include <string_view>

#include "harness/core/registry.hpp"
#include "harness/tracking/scenario.hpp"
#include "harness/tracking/tracker.hpp"

namespace dabench {

Registry<Tracker>& tracking_tracker_registry();
Registry<TrackingScenario>& tracking_scenario_registry();

// Parses a SPEC ("name", "name:key=value,...") and builds the object; throws InputError for an
// unknown name, an unknown key or an invalid value.
std::unique_ptr<Tracker> make_tracker(std::string_view spec);

template <class Made>
struct TrackingTrackerRegistration {
  TrackingTrackerRegistration() { tracking_tracker_registry().add(make_registry_entry<Made, Tracker>()); }
};

template <class Scenario>
struct TrackingScenarioRegistration {
  TrackingScenarioRegistration() {
    tracking_scenario_registry().add(make_registry_entry<Scenario, TrackingScenario>());
  }
};

}  // namespace dabench

#define DABENCH_REGISTER_TRACKING_TRACKER(Made) \
  static const ::dabench::TrackingTrackerRegistration<Made> dabench_tracker_registration_##Made {}
#define DABENCH_REGISTER_TRACKING_SCENARIO(Scenario) \
  static const ::dabench::TrackingScenarioRegistration<Scenario> dabench_tracking_scenario_registration_##Scenario {}
