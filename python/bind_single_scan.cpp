// dabench.marginals(), marginals_batch(), time_solver() and draw(): single-scan problems from
// numpy arrays solved by any registered algorithm, as `dabench solve` solves them, and the
// problem a run draws for (seed, point, trial).
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string_view>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include <fmt/format.h>
#include <omp.h>

#include "harness/core/errors.hpp"
#include "harness/core/random_stream.hpp"
#include "harness/core/row_fields.hpp"
#include "harness/run/library.hpp"
#include "harness/run/run_plan.hpp"
#include "harness/single_scan/registry.hpp"
#include "python/bindings.hpp"

namespace dabench::python {
namespace {

using Clock = std::chrono::steady_clock;
constexpr std::size_t kCachedSolvers = 64;

// This thread's solvers by SPEC, made once and reused (a solver keeps its buffers between
// problems), dropped when an algorithm is registered or unregistered.
SingleScanSolver& cached_solver(const std::string& spec) {
  thread_local std::unordered_map<std::string, std::unique_ptr<SingleScanSolver>> cache;
  thread_local int generation = -1;
  if (generation != registration_generation() || cache.size() >= kCachedSolvers) {
    cache.clear();
    generation = registration_generation();
  }
  if (const auto found = cache.find(spec); found != cache.end()) return *found->second;
  return *cache.emplace(spec, make_single_scan_solver(spec)).first->second;
}

ScanContext scan_context(const char* caller, std::optional<double> pd, std::optional<double> lambda_fa) {
  ScanContext context;
  if (pd) {
    if (!(*pd > 0.0 && *pd < 1.0)) throw InputError(fmt::format("{}: pd {} must be in (0, 1)", caller, *pd));
    context.pd = *pd;
  }
  if (lambda_fa) {
    if (!(*lambda_fa > 0.0)) throw InputError(fmt::format("{}: lambda_fa {} must be > 0", caller, *lambda_fa));
    context.lambda_fa = *lambda_fa;
  }
  return context;
}

WeightsFormat weights_format(const std::string& layout, bool log) { return {parse_weights_layout(layout), log}; }

struct Solved {
  MarginalTable marginals;
  SolveReport report;
  double time_us = 0.0;
};

// One solve as the runner does it: a throw is a failed:<reason> status, a table that is not a
// distribution skipped:numerical.
void solve(SingleScanSolver& solver, const SingleScanProblem& problem, Solved& out) {
  out.report.reset();
  const auto start = Clock::now();
  try {
    if (!refuse_must_detect(solver, problem, out.report)) solver.solve(problem, out.marginals, out.report);
  } catch (const std::exception& error) {
    out.report.skipped = "failed:" + one_line(error.what());
  }
  out.time_us = std::chrono::duration<double, std::micro>(Clock::now() - start).count();
  reject_non_distribution(problem, out.marginals, out.report);
}

std::string status_text(const SolveReport& report) {
  if (report.skipped.empty()) return "ok";
  if (report.skipped.rfind("failed:", 0) == 0) return report.skipped;
  return "skipped:" + report.skipped;
}

py::dict report_dict(const Solved& solved) {
  py::dict out;
  out["status"] = status_text(solved.report);
  out["iterations"] = solved.report.iterations;
  out["converged"] = solved.report.converged;
  out["w_star"] = solved.report.w_star;
  out["free_energy"] = solved.report.free_energy;
  out["captured_mass"] = solved.report.captured_mass;
  out["time_us"] = solved.time_us;
  return out;
}

// The marginals, or with `report` (marginals or None, report); SkippedError when the algorithm
// refused and no report was asked for (`where` names the problem of a batch).
py::object result(const Solved& solved, const std::string& spec, bool report, long long where = -1) {
  const bool ok = solved.report.skipped.empty();
  if (!ok && !report) {
    const std::string problem = where < 0 ? "" : fmt::format("weights[{}]: ", where);
    throw SkippedError(fmt::format("{}{}: {} (the algorithm refused this problem)", problem, spec, status_text(solved.report)));
  }
  py::object marginals = ok ? py::object(marginals_array(solved.marginals)) : py::object(py::none());
  if (!report) return marginals;
  return py::make_tuple(marginals, report_dict(solved));
}

py::object marginals(const py::handle& weights, const std::string& algorithm, const std::string& layout, bool log,
                     bool report, std::optional<double> pd, std::optional<double> lambda_fa) {
  SingleScanProblem problem = problem_from_array(weights, weights_format(layout, log), "weights");
  problem.context = scan_context("marginals", pd, lambda_fa);
  SingleScanSolver& solver = cached_solver(algorithm);
  Solved solved;
  {
    const py::gil_scoped_release release;
    solve(solver, problem, solved);
  }
  return result(solved, algorithm, report);
}

py::object marginals_batch(const py::sequence& weights, const std::string& algorithm, std::optional<int> threads,
                           const std::string& layout, bool log, bool report, std::optional<double> pd,
                           std::optional<double> lambda_fa) {
  if (threads && *threads < 1) throw InputError(fmt::format("marginals_batch: threads {} must be >= 1", *threads));
  const WeightsFormat format = weights_format(layout, log);
  const ScanContext context = scan_context("marginals_batch", pd, lambda_fa);
  const auto count = static_cast<long long>(py::len(weights));
  std::vector<SingleScanProblem> problems(static_cast<std::size_t>(count));
  for (long long k = 0; k < count; ++k) {
    try {
      problems[k] = problem_from_array(weights[static_cast<py::size_t>(k)], format, "weights");
    } catch (const InputError& bad) {  // "weights:ROW: ..." names the problem: "weights[k]:ROW: ..."
      throw InputError(fmt::format("weights[{}]{}", k, std::string_view(bad.what()).substr(std::strlen("weights"))));
    }
    problems[k].context = context;
  }
  make_single_scan_solver(algorithm);  // an unknown algorithm or parameter raises here, not in a thread
  std::vector<Solved> solved(static_cast<std::size_t>(count));
  {
    const py::gil_scoped_release release;
    const int team = threads.value_or(omp_get_max_threads());
#pragma omp parallel num_threads(team)
    {
      const auto solver = make_single_scan_solver(algorithm);
#pragma omp for schedule(dynamic)
      for (long long k = 0; k < count; ++k) solve(*solver, problems[k], solved[k]);
    }
  }
  py::list out(count), reports(report ? count : 0);
  for (long long k = 0; k < count; ++k) {
    const auto slot = static_cast<py::size_t>(k);
    if (!report) {
      out[slot] = result(solved[k], algorithm, false, k);
      continue;
    }
    const auto pair = result(solved[k], algorithm, true, k).cast<py::tuple>();
    out[slot] = pair[0];
    reports[slot] = pair[1];
  }
  if (!report) return out;
  return py::make_tuple(out, reports);
}

py::dict time_solver(const py::handle& weights, const std::string& algorithm, double budget_s, int min_samples,
                     const std::string& layout, bool log, std::optional<double> pd, std::optional<double> lambda_fa) {
  RepeatTimingOptions options;
  options.budget_seconds = budget_s;
  options.min_samples = min_samples;
  if (!(budget_s > 0.0 && std::isfinite(budget_s))) throw InputError(fmt::format("time_solver: budget_s {} must be > 0 seconds", budget_s));
  if (min_samples < 1) throw InputError(fmt::format("time_solver: min_samples {} must be >= 1", min_samples));
  SingleScanProblem problem = problem_from_array(weights, weights_format(layout, log), "weights");
  problem.context = scan_context("time_solver", pd, lambda_fa);
  const auto solver = make_single_scan_solver(algorithm);
  Solved first;
  RepeatTiming timing;
  {
    const py::gil_scoped_release release;
    solve(*solver, problem, first);
    if (first.report.skipped.empty()) timing = time_single_scan(*solver, problem, options);
  }
  result(first, algorithm, false);  // SkippedError for a refused problem, as `solve --time` exits 3
  py::dict out;
  out["algorithm"] = algorithm;
  out["targets"] = problem.targets();
  out["measurements"] = problem.measurements();
  out["solves"] = timing.calls;
  out["samples"] = timing.samples;
  out["batch"] = timing.batch;
  out["median_us"] = timing.median * 1e6;
  out["p10_us"] = timing.p10 * 1e6;
  out["p90_us"] = timing.p90 * 1e6;
  out["median_interval"] = timing.median_interval;
  out["stable"] = timing.stable;
  return out;
}

// A parameter value from Python as the text an experiment file would hold.
std::string setting_text(const std::string& key, const py::handle& value) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::int_>(value)) return py::str(value).cast<std::string>();
  if (py::isinstance<py::float_>(value)) return fmt::format("{}", value.cast<double>());
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  throw InputError(fmt::format("draw: parameter {}: a {} is not a number, bool or text", key,
                               py::str(py::type::handle_of(value).attr("__name__")).cast<std::string>()));
}

py::array_t<double> vector_array(const Vector& values) {
  py::array_t<double> out(values.size());
  for (Eigen::Index k = 0; k < values.size(); ++k) out.mutable_at(k) = values[k];
  return out;
}

py::dict draw(const std::string& scenario, std::optional<std::uint64_t> seed, std::int64_t trial,
              const std::optional<py::dict>& point_params, std::int64_t point) {
  constexpr auto kMaxIndex = static_cast<std::int64_t>(std::numeric_limits<std::uint32_t>::max());
  if (trial < 0 || trial > kMaxIndex) throw InputError(fmt::format("draw: trial {} must be in [0, {}]", trial, kMaxIndex));
  if (point < 0 || point > kMaxIndex) throw InputError(fmt::format("draw: point {} must be in [0, {}]", point, kMaxIndex));
  std::string name = scenario;
  std::vector<KeyValue> settings;
  std::uint64_t stream_seed = seed.value_or(0);
  const bool experiment = scenario.size() > 4 && scenario.compare(scenario.size() - 4, 4, ".ini") == 0;
  if (experiment) {  // the experiment's point `point`, and its seed unless one is given
    if (point_params) throw InputError("draw: an experiment's points set the parameters: give point=K, not point_params");
    RunOptions options;
    options.experiment_path = scenario;
    options.seed = seed;
    const RunPlan plan = make_run_plan(options);
    if (plan.kind != &single_scan_kind()) throw InputError(fmt::format("draw: {} is not a single-scan experiment", scenario));
    if (point >= static_cast<std::int64_t>(plan.point_settings.size())) {
      throw InputError(fmt::format("draw: point {} of {}: it has points 0 to {}", point, scenario, plan.point_settings.size() - 1));
    }
    name = plan.experiment.scenario;
    settings = plan.point_settings[static_cast<std::size_t>(point)];
    stream_seed = plan.seed;
  } else {
    if (!seed) throw InputError("draw: give seed= (the run's seed) with a scenario name");
    if (point_params) {
      for (const auto& [key, value] : *point_params) {
        const auto text_key = py::str(key).cast<std::string>();
        settings.push_back({text_key, setting_text(text_key, value)});
      }
    }
  }
  const auto* entry = single_scan_scenario_registry().find(name);
  if (entry == nullptr) {
    throw InputError(fmt::format("draw: unknown single-scan scenario '{}' (known: {})", name, single_scan_scenario_registry().names()));
  }
  const auto generator = entry->create(settings);
  ScenarioSample sample;
  RandomStream rng(stream_seed, static_cast<std::uint32_t>(point), static_cast<std::uint32_t>(trial));
  generator->generate(rng, sample);
  const SingleScanProblem& problem = sample.problem;

  py::dict params;
  for (const KeyValue& setting : entry->resolve(settings)) params[py::str(setting.key)] = setting.value;
  py::dict out;
  out["scenario"] = name;
  out["seed"] = stream_seed;
  out["point"] = point;
  out["trial"] = trial;
  out["params"] = params;
  py::array_t<double> psi({static_cast<py::ssize_t>(problem.targets()), static_cast<py::ssize_t>(problem.measurements())});
  for (int i = 0; i < problem.targets(); ++i) {
    for (int j = 0; j < problem.measurements(); ++j) psi.mutable_at(i, j) = problem.psi(i, j);
  }
  out["psi"] = psi;
  out["miss_weight"] = problem.miss_weight.size() ? py::object(vector_array(problem.miss_weight)) : py::object(py::none());
  out["clutter_weight"] = problem.clutter_weight.size() ? py::object(vector_array(problem.clutter_weight)) : py::object(py::none());
  out["pd"] = problem.context.pd;
  out["lambda_fa"] = problem.context.lambda_fa;
  out["true_measurement"] = py::array_t<int>(static_cast<py::ssize_t>(sample.true_measurement.size()), sample.true_measurement.data());
  out["detections"] = sample.detections;
  out["gated_out_detections"] = sample.gated_out_detections;
  out["false_alarms"] = sample.false_alarms;
  return out;
}

}  // namespace

void bind_single_scan(py::module_& module) {
  module.def("marginals", &marginals, py::arg("weights"), py::arg("algorithm") = "bp", py::kw_only(),
             py::arg("layout") = "psi", py::arg("log") = false, py::arg("report") = false, py::arg("pd") = py::none(),
             py::arg("lambda_fa") = py::none());
  module.def("marginals_batch", &marginals_batch, py::arg("weights"), py::arg("algorithm") = "bp",
             py::arg("threads") = py::none(), py::kw_only(), py::arg("layout") = "psi", py::arg("log") = false,
             py::arg("report") = false, py::arg("pd") = py::none(), py::arg("lambda_fa") = py::none());
  module.def("time_solver", &time_solver, py::arg("weights"), py::arg("algorithm") = "bp", py::arg("budget_s") = 2.0,
             py::kw_only(), py::arg("min_samples") = 10, py::arg("layout") = "psi", py::arg("log") = false,
             py::arg("pd") = py::none(), py::arg("lambda_fa") = py::none());
  module.def("draw", &draw, py::arg("scenario"), py::arg("seed") = py::none(), py::arg("trial") = 0,
             py::arg("point_params") = py::none(), py::kw_only(), py::arg("point") = 0);
}

}  // namespace dabench::python
