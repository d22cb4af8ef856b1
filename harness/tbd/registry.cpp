#include "harness/tbd/registry.hpp"

#include <fmt/format.h>

#include "harness/core/errors.hpp"

namespace dabench {

Registry<TbdTracker>& tbd_tracker_registry() {
  static Registry<TbdTracker> registry;
  return registry;
}

Registry<TbdScenario>& tbd_scenario_registry() {
  static Registry<TbdScenario> registry;
  return registry;
}

std::unique_ptr<TbdTracker> make_tbd_tracker(std::string_view spec_text) {
  const Spec spec = parse_spec(spec_text);
  const auto* entry = tbd_tracker_registry().find(spec.name);
  if (entry == nullptr) {
    const std::string known = tbd_tracker_registry().names();
    throw InputError(fmt::format("unknown track-before-detect tracker '{}' (known: {})", spec.name,
                                 known.empty() ? "none registered" : known));
  }
  return entry->create(spec.settings);
}

}  // namespace dabench
