#pragma once
// The registries of multi-scan algorithms (DABENCH_REGISTER_MULTI_SCAN_ALGORITHM) and multi-scan scenarios (DABENCH_REGISTER_MULTI_SCAN_SCENARIO).
// An algorithm registers itself with one line at the end of its source file, e.g.
//
//   DABENCH_REGISTER_MULTI_SCAN_ALGORITHM(MyAlgorithm);
//
// (see harness/core/registry.hpp for what the class provides).
#include <memory>
#include <string_view>

#include "harness/core/registry.hpp"
#include "harness/multi_scan/scenario.hpp"
#include "harness/multi_scan/solver.hpp"

namespace dabench {

Registry<MultiScanSolver>& multi_scan_algorithm_registry();
Registry<MultiScanScenario>& multi_scan_scenario_registry();

// Parses a SPEC ("name", "name:key=value,...") and builds the object; throws InputError for an
// unknown name, an unknown key or an invalid value.
std::unique_ptr<MultiScanSolver> make_multi_scan_solver(std::string_view spec);

template <class Solver>
struct MultiScanAlgorithmRegistration {
  MultiScanAlgorithmRegistration() { multi_scan_algorithm_registry().add(make_registry_entry<Solver, MultiScanSolver>()); }
};

template <class Scenario>
struct MultiScanScenarioRegistration {
  MultiScanScenarioRegistration() {
    multi_scan_scenario_registry().add(make_registry_entry<Scenario, MultiScanScenario>());
  }
};

}  // namespace dabench

#define DABENCH_REGISTER_MULTI_SCAN_ALGORITHM(Solver) \
  static const ::dabench::MultiScanAlgorithmRegistration<Solver> dabench_multi_scan_registration_##Solver {}
#define DABENCH_REGISTER_MULTI_SCAN_SCENARIO(Scenario) \
  static const ::dabench::MultiScanScenarioRegistration<Scenario> dabench_multi_scan_scenario_registration_##Scenario {}
