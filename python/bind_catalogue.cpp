// dabench.algorithms() and dabench.scenarios(): what `dabench list` prints, as data.
#include <string>
#include <type_traits>
#include <variant>

#include <fmt/format.h>

#include "harness/core/errors.hpp"
#include "harness/multi_scan/registry.hpp"
#include "harness/single_scan/registry.hpp"
#include "harness/tbd/registry.hpp"
#include "harness/tracking/registry.hpp"
#include "python/bindings.hpp"

namespace dabench::python {
namespace {

constexpr const char* kKinds = "single_scan, multi_scan, tracking or tbd";

// A parameter's default as a Python value (a named choice as its name).
py::object default_value(const ParamList::Entry& entry) {
  if (!entry.choices.empty()) return py::str(ParamList::format(entry));
  return std::visit([](auto* field) -> py::object { return py::cast(*field); }, entry.target);
}

template <class Product>
void describe(py::list& out, const Registry<Product>& registry, const char* kind) {
  for (const auto& [name, entry] : registry.entries()) {
    py::list params;
    for (const ParamList::Entry& param : entry.defaults) {
      py::dict row;
      row["name"] = param.key;
      row["default"] = default_value(param);
      row["doc"] = param.doc;
      if (!param.choices.empty()) row["choices"] = param.choices;
      params.append(row);
    }
    py::dict row;
    row["name"] = name;
    row["kind"] = kind;
    row["description"] = entry.summary;
    row["params"] = params;
    out.append(row);
  }
}

void check_kind(const std::string& kind) {
  if (kind != "single_scan" && kind != "multi_scan" && kind != "tracking" && kind != "tbd") {
    throw InputError(fmt::format("unknown kind '{}' ({})", kind, kKinds));
  }
}

py::list algorithms(const std::string& kind) {
  if (!kind.empty()) check_kind(kind);
  py::list out;
  if (kind.empty() || kind == "single_scan") describe(out, single_scan_algorithm_registry(), "single_scan");
  if (kind.empty() || kind == "multi_scan") describe(out, multi_scan_algorithm_registry(), "multi_scan");
  if (kind.empty() || kind == "tracking") describe(out, tracking_tracker_registry(), "tracking");
  if (kind.empty() || kind == "tbd") describe(out, tbd_tracker_registry(), "tbd");
  return out;
}

py::list scenarios(const std::string& kind) {
  if (!kind.empty()) check_kind(kind);
  py::list out;
  if (kind.empty() || kind == "single_scan") describe(out, single_scan_scenario_registry(), "single_scan");
  if (kind.empty() || kind == "multi_scan") describe(out, multi_scan_scenario_registry(), "multi_scan");
  if (kind.empty() || kind == "tracking") describe(out, tracking_scenario_registry(), "tracking");
  if (kind.empty() || kind == "tbd") describe(out, tbd_scenario_registry(), "tbd");
  return out;
}

}  // namespace

void bind_catalogue(py::module_& module) {
  module.def("algorithms", &algorithms, py::arg("kind") = "");
  module.def("scenarios", &scenarios, py::arg("kind") = "");
}

}  // namespace dabench::python
