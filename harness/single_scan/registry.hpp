#pragma once
// The registries of single-scan algorithms (DABENCH_REGISTER_SINGLE_SCAN_ALGORITHM) and single-scan scenarios (DABENCH_REGISTER_SINGLE_SCAN_SCENARIO).
// An algorithm registers itself with one line at the end of its source file, e.g.
//
//   DABENCH_REGISTER_SINGLE_SCAN_ALGORITHM(MyAlgorithm);
//
// (see harness/core/registry.hpp for what the class provides).
#include <memory>
#include <string_view>

#include "harness/core/registry.hpp"
#include "harness/single_scan/scenario.hpp"
#include "harness/single_scan/solver.hpp"

namespace dabench {

Registry<SingleScanSolver>& single_scan_algorithm_registry();
Registry<SingleScanScenario>& single_scan_scenario_registry();

// Parses a SPEC ("name", "name:key=value,...") and builds the object; throws InputError for an
// unknown name, an unknown key or an invalid value.
std::unique_ptr<SingleScanSolver> make_single_scan_solver(std::string_view spec);

template <class Solver>
struct SingleScanAlgorithmRegistration {
  SingleScanAlgorithmRegistration() {
    single_scan_algorithm_registry().add(make_registry_entry<Solver, SingleScanSolver>());
  }
};

template <class Scenario>
struct SingleScanScenarioRegistration {
  SingleScanScenarioRegistration() { single_scan_scenario_registry().add(make_registry_entry<Scenario, SingleScanScenario>()); }
};

}  // namespace dabench

#define DABENCH_REGISTER_SINGLE_SCAN_ALGORITHM(Solver) \
  static const ::dabench::SingleScanAlgorithmRegistration<Solver> dabench_single_scan_registration_##Solver {}
#define DABENCH_REGISTER_SINGLE_SCAN_SCENARIO(Scenario) \
  static const ::dabench::SingleScanScenarioRegistration<Scenario> dabench_scenario_registration_##Scenario {}
