// dabench.register(): a Python function of a single-scan problem (ψ, n × m, as a float64 array)
// returning its marginals (n × (m+1), column 0 = missed detection) becomes a single-scan
// algorithm that experiment files, dabench.run() and dabench.marginals() name like a built-in
// one. Its parameters (register's params: name → default int, float, bool or str) are set by a
// SPEC ("name:key=value") and passed as keyword arguments.
//
// The function runs under the GIL: in a run on T threads the built-in algorithms run in
// parallel, but calls of Python functions take turns. A call that raises, or returns anything
// but a finite array of the right shape, is that row's failed:<reason>; the run goes on.
#include <atomic>
#include <cmath>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include <fmt/format.h>

#include "harness/core/errors.hpp"
#include "harness/single_scan/registry.hpp"
#include "python/bindings.hpp"

namespace dabench::python {
namespace {

std::atomic<int> g_generation{0};

using ParamValue = std::variant<std::int64_t, double, bool, std::string>;

struct PythonParam {
  std::string key;
  ParamValue value;
};

// What register() was given. Dropped with the GIL (from whichever thread drops the last solver),
// or left to the process's end when the interpreter is already gone.
struct PythonAlgorithm {
  std::string name;
  py::object function;
  std::vector<PythonParam> defaults;  // fixed once registered: ParamList entries point into it

  PythonAlgorithm() = default;
  PythonAlgorithm(const PythonAlgorithm&) = delete;
  PythonAlgorithm& operator=(const PythonAlgorithm&) = delete;
  ~PythonAlgorithm() {
    if (Py_IsInitialized()) {
      const py::gil_scoped_acquire gil;
      function = py::object();
    } else {
      function.release();
    }
  }
};

std::set<std::string>& python_names() {  // the algorithms register() made
  static std::set<std::string> names;
  return names;
}

void bind_values(ParamList& params, std::vector<PythonParam>& values) {
  for (PythonParam& param : values) {
    std::visit([&](auto& field) { params.add(param.key, field, "(Python)"); }, param.value);
  }
}

std::vector<PythonParam> settings_applied(const PythonAlgorithm& algorithm, const std::vector<KeyValue>& settings) {
  std::vector<PythonParam> values = algorithm.defaults;
  ParamList params;
  bind_values(params, values);
  for (const KeyValue& setting : settings) params.assign(setting.key, setting.value, algorithm.name);
  return values;
}

class PythonSolver final : public SingleScanSolver {
 public:
  PythonSolver(std::shared_ptr<PythonAlgorithm> algorithm, std::vector<PythonParam> values)
      : algorithm_(std::move(algorithm)), values_(std::move(values)) {}

  void solve(const SingleScanProblem& problem, MarginalTable& marginals, SolveReport& report) override {
    report.reset();
    const int n = problem.targets(), m = problem.measurements();
    const py::gil_scoped_acquire gil;
    py::array_t<double> psi({static_cast<py::ssize_t>(n), static_cast<py::ssize_t>(m)});
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < m; ++j) psi.mutable_at(i, j) = problem.normalized_weight(i, j);
    }
    py::dict keywords;
    for (const PythonParam& param : values_) {
      keywords[py::str(param.key)] = std::visit([](const auto& value) { return py::cast(value); }, param.value);
    }
    py::object returned;
    try {
      returned = algorithm_->function(psi, **keywords);
    } catch (py::error_already_set& error) {
      throw std::runtime_error(fmt::format("{}: {}", py::str(error.type().attr("__name__")).cast<std::string>(),
                                           py::str(error.value()).cast<std::string>()));
    }
    read_marginals(returned, n, m, marginals);
  }

 private:
  static std::string type_name(const py::handle& value) {
    return py::str(py::type::handle_of(value).attr("__name__")).cast<std::string>();
  }

  static void read_marginals(const py::object& returned, int n, int m, MarginalTable& marginals) {
    const py::array array = py::array::ensure(returned);
    const char kind = array ? array.dtype().kind() : '?';
    if (!array || (kind != 'f' && kind != 'i' && kind != 'u')) {
      throw std::runtime_error(fmt::format("returned a {}, not an array of numbers", type_name(returned)));
    }
    const auto values = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
    if (values.ndim() != 2 || values.shape(0) != n || values.shape(1) != m + 1) {
      std::string shape;
      for (py::ssize_t d = 0; d < values.ndim(); ++d) shape += fmt::format("{}{}", d ? ", " : "", values.shape(d));
      throw std::runtime_error(fmt::format("returned shape ({}), expected ({}, {})", shape, n, m + 1));
    }
    marginals.reshape(n, m);
    const double* data = values.data();
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j <= m; ++j) {
        const double p = data[static_cast<std::size_t>(i) * (m + 1) + j];
        if (!std::isfinite(p)) throw std::runtime_error(fmt::format("returned {} at ({}, {})", p, i, j));
        marginals(i, j) = p;
      }
    }
  }

  std::shared_ptr<PythonAlgorithm> algorithm_;
  std::vector<PythonParam> values_;
};

ParamValue param_value(const std::string& name, const std::string& key, const py::handle& value) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>();
  if (py::isinstance<py::int_>(value)) return value.cast<std::int64_t>();
  if (py::isinstance<py::float_>(value)) return value.cast<double>();
  if (py::isinstance<py::str>(value)) {
    const auto text = value.cast<std::string>();
    if (text.find_first_of(",=") != std::string::npos) {
      throw InputError(fmt::format("register: {}: the default of {} holds ',' or '=', which a SPEC cannot", name, key));
    }
    return text;
  }
  throw InputError(fmt::format("register: {}: the default of {} is a {}: give an int, float, bool or str", name, key,
                               py::str(py::type::handle_of(value).attr("__name__")).cast<std::string>()));
}

bool valid_name(const std::string& name) {
  if (name.empty() || !std::isalpha(static_cast<unsigned char>(name[0]))) return false;
  for (const char c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') return false;
  }
  return true;
}

void register_algorithm(const std::string& name, const py::object& function, const std::optional<py::dict>& params,
                        const std::string& description) {
  if (run_in_progress()) throw InputError("register: a run is in progress");
  if (!valid_name(name)) {
    throw InputError(fmt::format("register: '{}' is not a name (a letter, then letters, digits, '-', '_' or '.')", name));
  }
  if (single_scan_algorithm_registry().find(name) != nullptr && python_names().count(name) == 0) {
    throw InputError(fmt::format("register: '{}' is a built-in algorithm", name));
  }
  if (!PyCallable_Check(function.ptr())) throw py::type_error(fmt::format("register: {}: the function is not callable", name));
  auto algorithm = std::make_shared<PythonAlgorithm>();
  algorithm->name = name;
  algorithm->function = function;
  if (params) {
    for (const auto& [key, value] : *params) {
      const auto text = py::str(key).cast<std::string>();
      if (!valid_name(text) || text.find_first_of("-.") != std::string::npos) {
        throw InputError(fmt::format("register: {}: parameter '{}' is not an identifier", name, text));
      }
      algorithm->defaults.push_back({text, param_value(name, text, value)});
    }
  }
  ParamList defaults;
  bind_values(defaults, algorithm->defaults);
  Registry<SingleScanSolver>::Entry entry{
      name, description.empty() ? "(Python function)" : description, defaults.entries(),
      [algorithm](const std::vector<KeyValue>& settings) -> std::unique_ptr<SingleScanSolver> {
        return std::make_unique<PythonSolver>(algorithm, settings_applied(*algorithm, settings));
      },
      [algorithm](const std::vector<KeyValue>& settings) {
        std::vector<PythonParam> values = settings_applied(*algorithm, settings);
        ParamList bound;
        bind_values(bound, values);
        std::vector<KeyValue> out;
        for (const auto& param : bound.entries()) out.push_back({param.key, ParamList::format(param)});
        return out;
      }};
  single_scan_algorithm_registry().replace(std::move(entry));
  python_names().insert(name);
  ++g_generation;
}

void unregister_algorithm(const std::string& name) {
  if (run_in_progress()) throw InputError("unregister: a run is in progress");
  if (python_names().erase(name) == 0) throw InputError(fmt::format("unregister: '{}' was not registered from Python", name));
  single_scan_algorithm_registry().remove(name);
  ++g_generation;
}

}  // namespace

int registration_generation() { return g_generation.load(); }

void bind_registration(py::module_& module) {
  module.def("register", &register_algorithm, py::arg("name"), py::arg("function"), py::arg("params") = py::none(),
             py::arg("description") = "");
  module.def("unregister", &unregister_algorithm, py::arg("name"));
  module.def("registered", [] { return std::vector<std::string>(python_names().begin(), python_names().end()); });
}

}  // namespace dabench::python
