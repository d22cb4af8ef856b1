#pragma once
// Name → factory tables for algorithms and scenarios. An algorithm registers itself with one
// line in its own source file:
//
//   DABENCH_REGISTER_SINGLE_SCAN(BeliefPropagation);
//
// where the class provides `using Options = ...;` (a struct with bind() and validate()),
// `static constexpr std::string_view kName`, `kSummary`, and a constructor from Options.
// Multiple-scan algorithms use DABENCH_REGISTER_MULTI_SCAN, trackers DABENCH_REGISTER_TRACKER,
// scenarios DABENCH_REGISTER_SCENARIO (single scan), DABENCH_REGISTER_MULTI_SCAN_SCENARIO or
// DABENCH_REGISTER_TRACKING_SCENARIO.
// Registries are function-local statics, filled before main() by objects in OBJECT libraries
// (which the linker never drops).
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "harness/params.hpp"
#include "harness/multi_scan_scenario.hpp"
#include "harness/scenario.hpp"
#include "harness/multi_scan_solver.hpp"
#include "harness/single_scan_solver.hpp"
#include "harness/tracker.hpp"
#include "harness/tracking_scenario.hpp"

namespace dabench {

template <class Product>
class Registry {
 public:
  using Factory = std::function<std::unique_ptr<Product>(const std::vector<KeyValue>&)>;
  using Resolver = std::function<std::vector<KeyValue>(const std::vector<KeyValue>&)>;
  struct Entry {
    std::string name;
    std::string summary;
    std::vector<ParamList::Entry> defaults;  // points into a static default Options object
    Factory create;      // validated settings → object; throws InputError
    Resolver resolve;    // settings → every parameter with its effective value, in bind order
  };

  void add(Entry entry) {
    const std::string name = entry.name;
    entries_.emplace(name, std::move(entry));
  }
  const Entry* find(std::string_view name) const {
    const auto it = entries_.find(std::string(name));
    return it == entries_.end() ? nullptr : &it->second;
  }
  const std::map<std::string, Entry>& entries() const { return entries_; }

  std::string names() const {
    std::string text;
    for (const auto& [name, entry] : entries_) text += (text.empty() ? "" : ", ") + name;
    return text;
  }

 private:
  std::map<std::string, Entry> entries_;
};

Registry<SingleScanSolver>& single_scan_registry();
Registry<MultiScanSolver>& multi_scan_registry();
Registry<SingleScanScenario>& scenario_registry();
Registry<MultiScanScenario>& multi_scan_scenario_registry();
Registry<Tracker>& tracker_registry();
Registry<TrackingScenario>& tracking_scenario_registry();

// Parses a SPEC ("bp", "bp:delta=1e-6") and builds the solver; throws InputError for an
// unknown name, an unknown key or an invalid value.
std::unique_ptr<SingleScanSolver> make_single_scan_solver(std::string_view spec);
std::unique_ptr<MultiScanSolver> make_multi_scan_solver(std::string_view spec);
std::unique_ptr<Tracker> make_tracker(std::string_view spec);

template <class Made, class Product>
typename Registry<Product>::Entry make_registry_entry() {
  using Options = typename Made::Options;
  return {std::string(Made::kName), std::string(Made::kSummary), default_entries<Options>(),
          [](const std::vector<KeyValue>& settings) -> std::unique_ptr<Product> {
            return std::make_unique<Made>(make_options<Options>(settings, Made::kName));
          },
          [](const std::vector<KeyValue>& settings) {
            Options options = make_options<Options>(settings, Made::kName);
            ParamList params;
            options.bind(params);
            std::vector<KeyValue> values;
            for (const auto& entry : params.entries()) values.push_back({entry.key, ParamList::format(entry)});
            return values;
          }};
}

template <class Solver>
struct SingleScanRegistration {
  SingleScanRegistration() {
    single_scan_registry().add(make_registry_entry<Solver, SingleScanSolver>());
  }
};

template <class Solver>
struct MultiScanRegistration {
  MultiScanRegistration() { multi_scan_registry().add(make_registry_entry<Solver, MultiScanSolver>()); }
};

template <class Scenario>
struct ScenarioRegistration {
  ScenarioRegistration() { scenario_registry().add(make_registry_entry<Scenario, SingleScanScenario>()); }
};

template <class Scenario>
struct MultiScanScenarioRegistration {
  MultiScanScenarioRegistration() {
    multi_scan_scenario_registry().add(make_registry_entry<Scenario, MultiScanScenario>());
  }
};

template <class Made>
struct TrackerRegistration {
  TrackerRegistration() { tracker_registry().add(make_registry_entry<Made, Tracker>()); }
};

template <class Scenario>
struct TrackingScenarioRegistration {
  TrackingScenarioRegistration() {
    tracking_scenario_registry().add(make_registry_entry<Scenario, TrackingScenario>());
  }
};

}  // namespace dabench

#define DABENCH_REGISTER_SINGLE_SCAN(Solver) \
  static const ::dabench::SingleScanRegistration<Solver> dabench_single_scan_registration_##Solver {}
#define DABENCH_REGISTER_MULTI_SCAN(Solver) \
  static const ::dabench::MultiScanRegistration<Solver> dabench_multi_scan_registration_##Solver {}
#define DABENCH_REGISTER_SCENARIO(Scenario) \
  static const ::dabench::ScenarioRegistration<Scenario> dabench_scenario_registration_##Scenario {}
#define DABENCH_REGISTER_MULTI_SCAN_SCENARIO(Scenario) \
  static const ::dabench::MultiScanScenarioRegistration<Scenario> dabench_multi_scan_scenario_registration_##Scenario {}
#define DABENCH_REGISTER_TRACKER(Made) \
  static const ::dabench::TrackerRegistration<Made> dabench_tracker_registration_##Made {}
#define DABENCH_REGISTER_TRACKING_SCENARIO(Scenario) \
  static const ::dabench::TrackingScenarioRegistration<Scenario> dabench_tracking_scenario_registration_##Scenario {}
