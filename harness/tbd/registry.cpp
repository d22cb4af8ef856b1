#include "harness/tbd/registry.hpp"

namespace dabench {

Registry<TbdTracker>& tbd_tracker_registry() {
  static Registry<TbdTracker> registry;
  return registry;
}

Registry<TbdScenario>& tbd_scenario_registry() {
  static Registry<TbdScenario> registry;
  return registry;
}

std::unique_ptr<TbdTracker> make_tbd_tracker(std::string_view spec) {
  return tbd_tracker_registry().make(spec, "track-before-detect tracker");
}

}  // namespace dabench
