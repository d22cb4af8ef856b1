#pragma once
// The registries of track-before-detect trackers (DABENCH_REGISTER_TBD_TRACKER) and scenarios
// (DABENCH_REGISTER_TBD_SCENARIO). An algorithm registers itself with one line at the end of
// its source file, e.g.
//
//   DABENCH_REGISTER_TBD_TRACKER(MyTbdTracker);
//
// (see harness/core/registry.hpp for what the class provides).
#include <memory>
#include <string_view>

#include "harness/core/registry.hpp"
#include "harness/tbd/scenario.hpp"
#include "harness/tbd/tracker.hpp"

namespace dabench {

Registry<TbdTracker>& tbd_tracker_registry();
Registry<TbdScenario>& tbd_scenario_registry();

// Parses a SPEC ("name", "name:key=value,...") and builds the tracker; throws InputError for an
// unknown name, an unknown key or an invalid value.
std::unique_ptr<TbdTracker> make_tbd_tracker(std::string_view spec);

template <class Made>
struct TbdTrackerRegistration {
  TbdTrackerRegistration() { tbd_tracker_registry().add(make_registry_entry<Made, TbdTracker>()); }
};

template <class Scenario>
struct TbdScenarioRegistration {
  TbdScenarioRegistration() { tbd_scenario_registry().add(make_registry_entry<Scenario, TbdScenario>()); }
};

}  // namespace dabench

#define DABENCH_REGISTER_TBD_TRACKER(Made) \
  static const ::dabench::TbdTrackerRegistration<Made> dabench_tbd_tracker_registration_##Made {}
#define DABENCH_REGISTER_TBD_SCENARIO(Scenario) \
  static const ::dabench::TbdScenarioRegistration<Scenario> dabench_tbd_scenario_registration_##Scenario {}
