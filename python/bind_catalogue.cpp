// dabench.algorithms() and dabench.scenarios(): what `dabench list` prints, as data; and
// dabench.kinds(): each problem kind's trials.csv columns and its primary error and time columns.
#include <string>
#include <variant>

#include <fmt/format.h>

#include "harness/core/errors.hpp"
#include "harness/run/problem_kind.hpp"
#include "python/bindings.hpp"

namespace dabench::python {
namespace {

// A parameter's default as a Python value (a named choice as its name).
py::object default_value(const ParamList::Entry& entry) {
  if (!entry.choices.empty()) return py::str(ParamList::format(entry));
  return std::visit([](auto* field) -> py::object { return py::cast(*field); }, entry.target);
}

void describe(py::list& out, const std::vector<CatalogueEntry>& entries, std::string_view kind) {
  for (const CatalogueEntry& entry : entries) {
    py::list params;
    for (const ParamList::Entry& param : *entry.params) {
      py::dict row;
      row["name"] = param.key;
      row["default"] = default_value(param);
      row["doc"] = param.doc;
      if (!param.choices.empty()) row["choices"] = param.choices;
      params.append(row);
    }
    py::dict row;
    row["name"] = *entry.name;
    row["kind"] = std::string(kind);
    row["description"] = *entry.summary;
    row["params"] = params;
    out.append(row);
  }
}

// The kinds `kind` names: every one when empty; InputError for a name of none.
std::vector<const ProblemKind*> kinds_named(const std::string& kind) {
  std::vector<const ProblemKind*> named;
  std::string keys;
  const auto& kinds = problem_kinds();
  for (std::size_t k = 0; k < kinds.size(); ++k) {
    if (kind.empty() || kinds[k]->key() == kind) named.push_back(kinds[k]);
    keys += fmt::format("{}{}", k == 0 ? "" : k + 1 == kinds.size() ? " or " : ", ", kinds[k]->key());
  }
  if (named.empty()) throw InputError(fmt::format("unknown kind '{}' ({})", kind, keys));
  return named;
}

py::list algorithms(const std::string& kind) {
  py::list out;
  for (const ProblemKind* named : kinds_named(kind)) describe(out, named->algorithm_entries(), named->key());
  return out;
}

py::list scenarios(const std::string& kind) {
  py::list out;
  for (const ProblemKind* named : kinds_named(kind)) describe(out, named->scenario_entries(), named->key());
  return out;
}

py::list kinds() {
  py::list out;
  for (const ProblemKind* kind : problem_kinds()) {
    const AlgorithmTimeColumn time = kind->time_column();
    py::dict row;
    row["kind"] = std::string(kind->key());
    row["name"] = std::string(kind->name());
    row["columns"] = kind->metric_columns();
    row["error"] = std::string(kind->error_column());
    row["time"] = std::string(time.column);
    row["time_to_seconds"] = time.to_seconds;
    row["time_count"] = time.count_column.empty() ? py::object(py::none()) : py::str(std::string(time.count_column));
    out.append(row);
  }
  return out;
}

}  // namespace

void bind_catalogue(py::module_& module) {
  module.def("algorithms", &algorithms, py::arg("kind") = "");
  module.def("scenarios", &scenarios, py::arg("kind") = "");
  module.def("kinds", &kinds);
}

}  // namespace dabench::python
