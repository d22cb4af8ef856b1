// dabench solve: one single-scan problem from a weights file; its marginals, or the timing of
// the algorithm's calls on it (--time).
#include <cmath>
#include <cstdio>

#include <fmt/format.h>

#include "apps/cli/command.hpp"
#include "harness/core/csv.hpp"
#include "harness/core/errors.hpp"
#include "harness/core/json.hpp"
#include "harness/core/repeat_timing.hpp"
#include "harness/run/library.hpp"
#include "harness/single_scan/registry.hpp"
#include "harness/single_scan/weights_csv.hpp"

namespace dabench::cli {

namespace {

// `solve --time`: the algorithm's calls alone on `problem`, repeated (harness/core/repeat_timing.hpp);
// CSV or JSON on stdout, times in µs per solve.
std::string timing_report(const std::string& spec, const std::string& format, SingleScanSolver& solver,
                          const SingleScanProblem& problem, const RepeatTimingOptions& options) {
  const RepeatTiming timing = time_single_scan(solver, problem, options);
  const long long targets = problem.targets(), measurements = problem.measurements();
  if (format == "json") {
    JsonObject json;
    json.add("algorithm", spec)
        .add("targets", targets)
        .add("measurements", measurements)
        .add("solves", timing.calls)
        .add("samples", timing.samples)
        .add("batch", timing.batch)
        .add("median_us", timing.median * 1e6)
        .add("p10_us", timing.p10 * 1e6)
        .add("p90_us", timing.p90 * 1e6)
        .add("median_interval", timing.median_interval)
        .add("stable", timing.stable);
    return json.str();
  }
  std::string row;
  append_csv_field(row, spec);
  return "algorithm,targets,measurements,solves,samples,batch,median_us,p10_us,p90_us,median_interval,stable\n" + row +
         fmt::format(",{},{},{},{},{},{},{},{},{},{}\n", targets, measurements, timing.calls, timing.samples, timing.batch,
                     timing.median * 1e6, timing.p10 * 1e6, timing.p90 * 1e6, timing.median_interval,
                     timing.stable ? 1 : 0);
}

int run_solve(const Invocation& invocation) {
  po::options_description options("solve options");
  std::string spec, weights, format, layout;
  double pd = std::nan(""), lambda_fa = std::nan("");
  bool time = false, log_weights = false;
  RepeatTimingOptions timing;
  options.add_options()
      ("algorithm", po::value(&spec)->required(), "algorithm SPEC")
      ("weights", po::value(&weights)->required(), "headerless CSV of psi, one row per target (or as --layout says)")
      ("layout", po::value(&layout)->default_value("psi"),
       "psi (n x m, missed weight 1 implied), stonesoup (n x (m+1), missed-detection column first, as pyehm), "
       "tcl (n x (m+n), missed detections on a diagonal block) or matlab (jpdaEvents' (m+1) x (n+1): row 1 missed "
       "detections, column 1 clutter)")
      ("log", po::bool_switch(&log_weights), "the file holds natural logs of the weights (-inf for 0)")
      ("format", po::value(&format)->default_value("csv"), "csv or json")
      ("pd", po::value(&pd), "detection probability, for algorithms that need it")
      ("lambda-fa", po::value(&lambda_fa), "false-alarm density, for algorithms that need it")
      ("time", po::bool_switch(&time),
       "time the algorithm instead of printing marginals: batches of >= 1 ms until the median's 95% interval is "
       "within 1% (or the budget is spent); prints median and 10/90 percentiles per solve in us")
      ("time-budget", po::value(&timing.budget_seconds), "--time: seconds of measurement at most, unless fewer "
                                                          "samples than --time-min-samples (default 2)")
      ("time-min-samples", po::value(&timing.min_samples), "--time: timed batches at least (default 10)");
  const auto parsed = parse_command(kSolveCommand, options, po::positional_options_description(), invocation);
  if (!parsed) return 0;
  for (const char* option : {"time-budget", "time-min-samples"}) {
    if (parsed->count(option) && !time) throw InputError(fmt::format("solve: --{} needs --time", option));
  }
  if (format != "csv" && format != "json") throw InputError(fmt::format("solve: --format must be csv or json, not '{}'", format));
  if (!std::isnan(pd) && !(pd > 0.0 && pd < 1.0)) throw InputError(fmt::format("solve: --pd {} must be in (0, 1)", pd));
  if (!std::isnan(lambda_fa) && !(lambda_fa > 0.0)) throw InputError(fmt::format("solve: --lambda-fa {} must be > 0", lambda_fa));
  if (!(timing.budget_seconds > 0.0 && std::isfinite(timing.budget_seconds))) {
    throw InputError(fmt::format("solve: --time-budget {} must be > 0 seconds", timing.budget_seconds));
  }
  if (timing.min_samples < 1) throw InputError(fmt::format("solve: --time-min-samples {} must be >= 1", timing.min_samples));

  auto solver = make_single_scan_solver(spec);
  SingleScanProblem problem = read_weights_csv(weights, {parse_weights_layout(layout), log_weights});
  problem.context.pd = pd;
  problem.context.lambda_fa = lambda_fa;
  MarginalTable marginals;
  SolveReport report;
  if (!refuse_must_detect(*solver, problem, report)) solver->solve(problem, marginals, report);
  reject_non_distribution(problem, marginals, report);
  if (!report.skipped.empty()) {
    std::fprintf(stderr, "dabench: %s: skipped:%s (the algorithm refused this problem)\n", spec.c_str(), report.skipped.c_str());
    return 3;
  }
  if (time) {
    print_stdout(timing_report(spec, format, *solver, problem, timing));
    return 0;
  }
  std::string out;
  if (format == "csv") {
    out = "target,measurement,probability\n";
    for (int i = 0; i < marginals.targets(); ++i) {
      for (int j = 0; j <= marginals.measurements(); ++j) out += fmt::format("{},{},{}\n", i + 1, j, marginals(i, j));
    }
  } else {
    std::string rows = "[";
    for (int i = 0; i < marginals.targets(); ++i) {
      rows += i ? ",\n    [" : "\n    [";
      for (int j = 0; j <= marginals.measurements(); ++j) rows += fmt::format("{}{}", j ? ", " : "", marginals(i, j));
      rows += "]";
    }
    rows += "\n  ]";
    JsonObject json;
    json.add("algorithm", spec)
        .add("targets", static_cast<long long>(marginals.targets()))
        .add("measurements", static_cast<long long>(marginals.measurements()))
        .add("iterations", static_cast<long long>(report.iterations))
        .add("converged", report.converged)
        .add("w_star", report.w_star);
    if (std::isfinite(report.free_energy)) json.add("free_energy", report.free_energy);
    if (std::isfinite(report.captured_mass)) json.add("captured_mass", report.captured_mass);
    json.add_raw("marginals", rows);
    out = json.str();
  }
  print_stdout(out);
  return 0;
}

}  // namespace

const Command kSolveCommand{
    "solve",
    "dabench solve --algorithm SPEC --weights FILE [--layout psi|stonesoup|tcl|matlab] [--log] [--format csv|json] [--pd P] [--lambda-fa L] [--time]",
    "Solves one single-scan problem: FILE is a headerless CSV of psi, one row per target and one\n"
    "column per measurement (or another tracker's matrix: --layout); prints\n"
    "target,measurement,probability (measurement 0 = missed).\n"
    "With --time, times the algorithm's calls on that problem instead (the same input repeatedly:\n"
    "warm caches) and prints algorithm,targets,measurements,solves,samples,batch,median_us,p10_us,\n"
    "p90_us,median_interval,stable (median_interval: half-width of the median's 95% interval over\n"
    "the median; the percentiles are of batch means when a batch holds several solves).\n",
    run_solve};

}  // namespace dabench::cli
