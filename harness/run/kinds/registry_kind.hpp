#pragma once
// The part of a problem kind (harness/run/problem_kind.hpp) that its two registries answer:
// scenarios and algorithms by name, a SPEC's check, and the plan's scenario created per sweep
// point for the execution. Each kind in this folder derives from it.
#include <algorithm>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "harness/core/registry.hpp"
#include "harness/run/problem_kind.hpp"
#include "harness/run/run_plan.hpp"

namespace dabench {

template <class Scenario, class Algorithm>
class RegistryKind : public ProblemKind {
 public:
  using MakeAlgorithm = std::unique_ptr<Algorithm> (*)(std::string_view spec);
  RegistryKind(Registry<Scenario>& scenarios, Registry<Algorithm>& algorithms, MakeAlgorithm make)
      : scenarios_(scenarios), algorithms_(algorithms), make_(make) {}

  void list_algorithms(std::string& out) const override { describe(out, algorithms_); }
  std::vector<CatalogueEntry> algorithm_entries() const override { return entries_of(algorithms_); }
  std::vector<CatalogueEntry> scenario_entries() const override { return entries_of(scenarios_); }
  void list_scenarios(std::string& out) const override { describe(out, scenarios_); }
  bool has_scenario(const std::string& scenario) const override { return scenarios_.find(scenario) != nullptr; }
  std::string scenario_names() const override { return scenarios_.names(); }
  std::vector<KeyValue> resolve(const std::string& scenario, const std::vector<KeyValue>& settings) const override {
    return scenarios_.find(scenario)->resolve(settings);
  }
  bool has_algorithm(const std::string& name) const override { return algorithms_.find(name) != nullptr; }
  void check_algorithm(const std::string& spec) const override { make_(spec); }

 protected:
  // The experiment's scenario, created once per sweep point with its settings.
  std::vector<std::unique_ptr<Scenario>> point_scenarios(const RunPlan& plan) const {
    const auto* entry = scenarios_.find(plan.experiment.scenario);
    std::vector<std::unique_ptr<Scenario>> made;
    for (const auto& settings : plan.point_settings) made.push_back(entry->create(settings));
    return made;
  }

 private:
  template <class Product>
  static std::vector<CatalogueEntry> entries_of(const Registry<Product>& registry) {
    std::vector<CatalogueEntry> entries;
    for (const auto& [name, entry] : registry.entries()) entries.push_back({&name, &entry.summary, &entry.defaults});
    return entries;
  }

  // A registry's entries for `dabench list`: the columns are as wide as the longest name and key,
  // so no entry pushes its value.
  template <class Product>
  static void describe(std::string& out, const Registry<Product>& registry) {
    if (registry.entries().empty()) out += "  (none registered)\n";
    std::size_t name_width = 10, key_width = 16;
    for (const auto& [name, entry] : registry.entries()) {
      name_width = std::max(name_width, name.size());
      for (const auto& param : entry.defaults) key_width = std::max(key_width, param.key.size());
    }
    for (const auto& [name, entry] : registry.entries()) {
      out += fmt::format("  {:<{}} {}\n", name, name_width, entry.summary);
      for (const auto& param : entry.defaults) {
        out += fmt::format("      {:<{}} = {:<10} {}\n", param.key, key_width, ParamList::format(param), param.doc);
      }
    }
  }

  Registry<Scenario>& scenarios_;
  Registry<Algorithm>& algorithms_;
  MakeAlgorithm make_;
};

}  // namespace dabench
