#include "apps/cli.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <numeric>
#include <optional>
#include <set>
#include <sstream>

#include <boost/program_options.hpp>
#include <fmt/format.h>

#include "harness/core/build_info.hpp"
#include "harness/core/csv.hpp"
#include "harness/core/errors.hpp"
#include "harness/core/experiment.hpp"
#include "harness/core/heap_policy.hpp"
#include "harness/core/input_file.hpp"
#include "harness/core/json.hpp"
#include "harness/core/params.hpp"
#include "harness/core/repeat_timing.hpp"
#include "harness/multi_scan/registry.hpp"
#include "harness/run/library.hpp"
#include "harness/run/mpi_transport.hpp"
#include "harness/run/paired_comparison.hpp"
#include "harness/run/run_meta.hpp"
#include "harness/run/runner.hpp"
#include "harness/run/schedule_simulation.hpp"
#include "harness/run/shard_merge.hpp"
#include "harness/run/shard_meta.hpp"
#include "harness/single_scan/registry.hpp"
#include "harness/single_scan/weights_csv.hpp"
#include "harness/tbd/registry.hpp"
#include "harness/tracking/metrics.hpp"
#include "harness/tracking/registry.hpp"

namespace dabench {

namespace po = boost::program_options;
namespace fs = std::filesystem;

namespace {

// Writes `text` to stdout and flushes it: a failed write (a full disk, a closed pipe or
// stdout) is a WriteError, exit status 1.
void print_stdout(const std::string& text) {
  errno = 0;
  if (std::fwrite(text.data(), 1, text.size(), stdout) != text.size() || std::fflush(stdout) != 0) {
    throw WriteError(fmt::format("standard output: write failed ({})", std::strerror(errno != 0 ? errno : EIO)));
  }
}

// A standard stream the caller closed (`>&-`) is opened on /dev/null the wrong way round (read
// only for stdout and stderr): writes to it fail, as they should, and no result file opened
// later can take its descriptor and receive what was meant for the terminal.
void hold_closed_standard_streams() {
  for (const int fd : {STDIN_FILENO, STDOUT_FILENO, STDERR_FILENO}) {
    if (fcntl(fd, F_GETFD) != -1 || errno != EBADF) continue;
    const int opened = open("/dev/null", fd == STDIN_FILENO ? O_WRONLY : O_RDONLY);
    if (opened >= 0 && opened != fd) {
      dup2(opened, fd);
      close(opened);
    }
  }
}

// Each subcommand's synopsis and what it does; `dabench --help` lists the synopses and
// `dabench COMMAND --help` adds the description and the options.
struct CommandUsage {
  const char* synopsis;
  const char* description;
};

constexpr CommandUsage kListUsage{
    "dabench list",
    "Prints the algorithms and trackers with their parameters and defaults, the scenarios and the\n"
    "experiment files.\n"};
constexpr CommandUsage kSolveUsage{
    "dabench solve --algorithm SPEC --weights FILE [--layout psi|stonesoup|tcl|matlab] [--log] [--format csv|json] [--pd P] [--lambda-fa L] [--time]",
    "Solves one single-scan problem: FILE is a headerless CSV of psi, one row per target and one\n"
    "column per measurement (or another tracker's matrix: --layout); prints\n"
    "target,measurement,probability (measurement 0 = missed).\n"
    "With --time, times the algorithm's calls on that problem instead (the same input repeatedly:\n"
    "warm caches) and prints algorithm,targets,measurements,solves,samples,batch,median_us,p10_us,\n"
    "p90_us,median_interval,stable (median_interval: half-width of the median's 95% interval over\n"
    "the median; the percentiles are of batch means when a batch holds several solves).\n"};
constexpr CommandUsage kRunUsage{
    "dabench run EXPERIMENT.ini [--trials N] [--threads T] [--seed S] [--out DIR] [--resume|--force] [--shard K/N] [--costs-from DIR]",
    "Runs an experiment file and writes trials.csv, summary.csv and meta.json (and the kind's\n"
    "per-trial files) into its output folder. Ctrl-C stops after the trials in flight.\n"
    "With --shard K/N, runs only shard K of N (blocks of 8 trials, round robin) into its own\n"
    "folder (default: the experiment's output + -shard-K-of-N); `dabench merge` joins them.\n"
    "With --costs-from DIR (a previous run of the same plan), the (trial, algorithm) units of a\n"
    "multi-scan, tracking or track-before-detect run start longest first by their times there.\n"};
constexpr CommandUsage kScheduleUsage{
    "dabench schedule RUN_DIR [--workers 1,2,16,64,256] [--trials N] [--format table|csv]",
    "Predicts the wall time of a finished run's work on W workers (threads of all ranks), simulated\n"
    "over the run's own per-unit times: the runner's work queue, the 8-item blocks it replaced, and\n"
    "the queue of a rerun with --costs-from. The times come from trials.csv (or a track-before-detect\n"
    "report's runs.csv, or summary.csv's means per point and algorithm) and are the algorithms'\n"
    "alone: drawing, metrics and writing come on top. With --trials N: the first N trials of each point.\n"};
constexpr CommandUsage kCompareUsage{
    "dabench compare RUN_DIR [RUN_DIR_B] --algorithms A[,B] [--metric M,...] [--format table|csv]",
    "Paired comparison on the same trials: two algorithms of one run, or one algorithm in two runs of\n"
    "the same plan (same fingerprint and seed). Per sweep point and metric (default: the kind's error\n"
    "and time): the mean paired difference A - B with its 95% t interval, the two-sided Wilcoxon\n"
    "signed-rank p-value (zeros dropped; exact up to 50 untied differences, else normal with the tie\n"
    "correction), Holm-adjusted over the points, and the share of trials where A is lower.\n"};
constexpr CommandUsage kMergeUsage{
    "dabench merge OUT SHARD_DIR... [--force]",
    "Joins the folders of `dabench run --shard K/N` (K = 1..N, same experiment, seed and trials)\n"
    "into OUT: the trials.csv, summary.csv, meta.json and per-trial files of the unsharded run.\n"
    "Missing, duplicated, incomplete or foreign shards are errors.\n"};

std::string program_usage() {
  std::string text = "usage: ";
  const char* indent = "";
  for (const CommandUsage* usage : {&kListUsage, &kSolveUsage, &kRunUsage, &kMergeUsage, &kScheduleUsage, &kCompareUsage}) {
    text += fmt::format("{}{}\n", indent, usage->synopsis);
    indent = "       ";
  }
  return text + "       dabench --version\n"
                "       dabench COMMAND --help\n"
                "SPEC is NAME or NAME:key=value,key=value (see `dabench list`).\n";
}

// "dabench 0.1.0 (git <commit>)", with ", modified source" when the build's tree differed from
// that commit; the commit left out when the build did not record one.
std::string version_line() {
  const BuildInfo& build = build_info();
  if (build.git_commit.empty() || build.git_commit == "unknown") return fmt::format("dabench {}\n", build.version);
  const char* modified = build.source == Provenance::modified ? ", modified source" : "";
  return fmt::format("dabench {} (git {}{})\n", build.version, build.git_commit, modified);
}

std::string joined_command_line(int argc, char** argv) {
  std::string text;
  for (int k = 0; k < argc; ++k) {
    if (k > 0) text += ' ';
    text += argv[k];
  }
  return text;
}

// The command that finishes an interrupted run: the same words, --force/--resume replaced.
std::string resume_command_line(int argc, char** argv) {
  std::string text;
  for (int k = 0; k < argc; ++k) {
    const std::string word = argv[k];
    if (word == "--force" || word == "--resume") continue;
    text += (text.empty() ? "" : " ") + word;
  }
  return text + " --resume";
}

// Parses the options of one subcommand, with --help/-h added; po errors become InputError with
// the subcommand named. Returns nothing after printing the subcommand's usage for --help (before
// required options are checked, so `dabench run --help` needs no experiment).
std::optional<po::variables_map> parse_command(const std::string& command, const CommandUsage& usage,
                                               po::options_description options,
                                               const po::positional_options_description& positional, int argc,
                                               char** argv) {
  options.add_options()("help,h", "print this usage and exit");
  po::variables_map values;
  try {
    po::store(po::command_line_parser(argc, argv).options(options).positional(positional).run(), values);
    if (values.count("help")) {
      std::ostringstream text;
      text << "usage: " << usage.synopsis << "\n" << usage.description << "\n" << options;
      print_stdout(text.str());
      return std::nullopt;
    }
    po::notify(values);
  } catch (const po::error& error) {
    throw InputError(fmt::format("{}: {}", command, error.what()));
  }
  return values;
}

fs::path experiments_folder() {
  if (fs::is_directory("experiments")) return "experiments";
  return fs::path(DABENCH_SOURCE_DIR) / "experiments";
}

int command_list(int argc, char** argv) {
  if (!parse_command("list", kListUsage, po::options_description("list options"), po::positional_options_description(),
                     argc, argv)) {
    return 0;
  }
  std::string out;
  // Each section's columns are as wide as its longest name and key, so no entry pushes its value.
  const auto describe = [&out](const auto& registry) {
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
  };
  out += "Algorithms (SPEC = name or name:key=value,...):\n";
  describe(single_scan_algorithm_registry());
  out += "\nMulti-scan algorithms (for multi-scan scenarios):\n";
  describe(multi_scan_algorithm_registry());
  out += "\nTrackers (for tracking scenarios):\n";
  describe(tracking_tracker_registry());
  out += "\nTrack-before-detect trackers (for track-before-detect scenarios; frame by frame):\n";
  describe(tbd_tracker_registry());
  out += "\nScenarios (parameters settable in an experiment's [scenario] and [sweep] sections):\n";
  describe(single_scan_scenario_registry());
  out += "\nMulti-scan scenarios (run multi-scan algorithms; metrics against the truth):\n";
  describe(multi_scan_scenario_registry());
  out += "\nTracking scenarios (whole runs of K scans, for trackers):\n";
  describe(tracking_scenario_registry());
  out += "  experiment [metrics] of tracking scenarios (harness/tracking/metrics.hpp):\n";
  TrackingMetricsOptions tracking_metrics;
  ParamList tracking_metric_params;
  tracking_metrics.bind(tracking_metric_params);
  for (const auto& param : tracking_metric_params.entries())
    out += fmt::format("      {:<16} = {:<10} {}\n", param.key, ParamList::format(param), param.doc);
  out += "\nTrack-before-detect scenarios (K image frames of J data cells; experiment [metrics]: GOSPA c, p, alpha):\n";
  describe(tbd_scenario_registry());
  const fs::path folder = experiments_folder();
  out += fmt::format("\nExperiments (in {}):\n", folder.string());
  std::set<fs::path> files;
  std::error_code error;
  for (const auto& file : fs::directory_iterator(folder, error)) {
    if (file.path().extension() == ".ini") files.insert(file.path());
  }
  for (const auto& file : files) {
    std::string description;
    try {
      description = load_experiment(file.string()).description;
    } catch (const InputError& problem) {
      description = fmt::format("(unreadable: {})", printable(problem.what()));
    }
    out += fmt::format("  {:<28} {}\n", file.filename().string(), description);
  }
  print_stdout(out);
  return 0;
}

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

int command_solve(int argc, char** argv) {
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
  const auto parsed = parse_command("solve", kSolveUsage, options, po::positional_options_description(), argc, argv);
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

Shard parse_shard(const std::string& text) {
  const auto shard = parse_shard_label(text);
  if (!shard) throw InputError(fmt::format("run: --shard '{}' must be K/N with 1 <= K <= N <= {}", text, kMaxShards));
  return *shard;
}

int command_run_options(int argc, char** argv, const std::string& command_line, std::string resume_line,
                        const MpiTransport* mpi) {
  po::options_description options("run options");
  RunOptions run;
  run.command_line = command_line;
  std::int64_t trials = 0, seed = 0;
  int threads = 0;
  std::string out, shard;
  options.add_options()
      ("experiment", po::value(&run.experiment_path)->required(), "experiment INI file")
      ("trials", po::value(&trials), "Monte Carlo trials per point (overrides the file)")
      ("threads", po::value(&threads), "OpenMP threads (default: all cores)")
      ("seed", po::value(&seed), "master seed (overrides the file)")
      ("out", po::value(&out), "output folder (overrides the file)")
      ("resume", po::bool_switch(&run.resume), "finish the run in the output folder")
      ("force", po::bool_switch(&run.force), "discard the run in the output folder")
      ("shard", po::value(&shard), "K/N: run shard K of N into its own folder (for `dabench merge`)")
      ("costs-from", po::value<std::string>(), "folder of a previous run of the same plan: start its longest units first");
  po::positional_options_description positional;
  positional.add("experiment", 1);
  const auto parsed = parse_command("run", kRunUsage, options, positional, argc, argv);
  if (!parsed) return 0;
  const po::variables_map& values = *parsed;
  if (run.resume && run.force) throw InputError("run: --resume and --force exclude each other");
  if (values.count("trials")) {
    if (trials < 1) throw InputError(fmt::format("run: --trials {} must be >= 1", trials));
    run.trials = trials;
  }
  if (values.count("threads")) {
    if (threads < 1) throw InputError(fmt::format("run: --threads {} must be >= 1", threads));
    run.threads = threads;
  }
  if (values.count("seed")) {
    if (seed < 0) throw InputError(fmt::format("run: --seed {} must be >= 0", seed));
    run.seed = static_cast<std::uint64_t>(seed);
  }
  if (values.count("out")) run.output = out;
  if (values.count("shard")) run.shard = parse_shard(shard);
  if (values.count("costs-from")) run.costs_from = values["costs-from"].as<std::string>();

  run.transport = mpi;
  const RunOutcome outcome = run_experiment(run);
  if (outcome.worker_rank) return 0;  // rank 0 reports
  if (mpi != nullptr) resume_line = fmt::format("mpirun -np {} {}", mpi->size(), resume_line);
  if (!outcome.write_error.empty()) {
    std::fprintf(stderr, "dabench: %s after %lld of %lld trials (whole rows kept); free space, then finish with: %s\n",
                 printable_line(outcome.write_error).c_str(), outcome.items_written, outcome.items_total, resume_line.c_str());
    return 1;
  }
  if (outcome.interrupted) {
    std::fprintf(stderr, "dabench: interrupted after %lld of %lld trials; finish with: %s\n",
                 outcome.items_written, outcome.items_total, resume_line.c_str());
    return 130;
  }
  std::string files = "trials.csv";
  for (const std::string& file : outcome.item_files) files += ", " + file;
  std::fprintf(stderr, "dabench: %lld trials done; results in %s/ (%s, summary.csv, meta.json)\n",
               outcome.items_total, printable_line(outcome.output).c_str(), files.c_str());
  return 0;
}

// Under mpirun, MPI is initialised first (and finalised last); only rank 0 prints errors of
// the options, the experiment or the output folder, and an unexpected failure ends every rank
// of the job.
int command_run(int argc, char** argv, const std::string& command_line, const std::string& resume_line) {
  const std::unique_ptr<MpiTransport> mpi = MpiTransport::open_if_launched();
  if (mpi == nullptr) return command_run_options(argc, argv, command_line, resume_line, nullptr);
  try {
    return command_run_options(argc, argv, command_line, resume_line, mpi.get());
  } catch (const InputError& error) {
    // Rank 0 reports it and exits 2; a worker exiting non-zero first would make mpirun kill
    // rank 0 before it prints.
    if (mpi->rank() != 0) return 0;
    throw;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "dabench: rank %d: internal error: %s\n", mpi->rank(), printable(error.what()).c_str());
    mpi->abort(1);
  }
}

int command_merge(int argc, char** argv, const std::string& command_line) {
  po::options_description options("merge options");
  MergeOptions merge;
  merge.command_line = command_line;
  options.add_options()
      ("output", po::value(&merge.output), "folder of the merged run")
      ("shards", po::value(&merge.shards)->multitoken(), "the shard folders")
      ("force", po::bool_switch(&merge.force), "replace a run in the output folder")
      ("allow-mixed", po::bool_switch(&merge.allow_mixed), "merge shards written by different builds (recorded in meta.json)");
  po::positional_options_description positional;
  positional.add("output", 1).add("shards", -1);
  if (!parse_command("merge", kMergeUsage, options, positional, argc, argv)) return 0;
  if (merge.output.empty() || merge.shards.empty()) throw InputError("merge: give the output folder, then the shard folders");
  const MergeOutcome outcome = merge_shards(merge);
  std::string files = "trials.csv";
  for (const std::string& file : outcome.item_files) files += ", " + file;
  std::fprintf(stderr, "dabench: merged %d shards, %lld trials; results in %s/ (%s, summary.csv, meta.json)\n",
               outcome.shards, outcome.items, printable_line(merge.output).c_str(), files.c_str());
  return 0;
}

// The items of a comma-separated option value; an empty item is an error naming the command's option.
std::vector<std::string> comma_list(const std::string& text, const char* command, const char* option) {
  std::vector<std::string> items;
  std::size_t at = 0;
  while (at <= text.size()) {
    const std::size_t end = std::min(text.find(',', at), text.size());
    items.push_back(text.substr(at, end - at));
    if (items.back().empty()) throw InputError(fmt::format("{}: {} '{}' has an empty item", command, option, text));
    at = end + 1;
  }
  return items;
}

std::vector<long long> parse_workers(const std::string& text) {
  std::vector<long long> workers;
  for (const std::string& word : comma_list(text, "schedule", "--workers")) {
    char* stop = nullptr;
    const long long value = std::strtoll(word.c_str(), &stop, 10);
    if (*stop != '\0' || value < 1 || value > 1000000) {
      throw InputError(fmt::format("schedule: --workers '{}' must be a list of counts from 1 to 1000000, e.g. 16,64,256", text));
    }
    workers.push_back(value);
  }
  return workers;
}

int command_schedule(int argc, char** argv) {
  po::options_description options("schedule options");
  std::string folder, workers_text, format;
  long long trials = -1;
  options.add_options()
      ("run", po::value(&folder)->required(), "folder of a finished run")
      ("trials", po::value(&trials), "only the first N trials of each point")
      ("workers", po::value(&workers_text)->default_value("1,2,16,64,256"), "worker counts, comma-separated")
      ("format", po::value(&format)->default_value("table"), "table or csv");
  po::positional_options_description positional;
  positional.add("run", 1);
  const auto parsed = parse_command("schedule", kScheduleUsage, options, positional, argc, argv);
  if (!parsed) return 0;
  if (format != "table" && format != "csv") throw InputError(fmt::format("schedule: --format must be table or csv, not '{}'", format));
  const std::vector<long long> workers = parse_workers(workers_text);
  if (parsed->count("trials") && trials < 1) throw InputError(fmt::format("schedule: --trials {} must be >= 1", trials));
  require_complete_run(folder, "schedule");
  const RunCosts costs = read_run_costs(folder, trials);
  const double total = std::accumulate(costs.unit_seconds.begin(), costs.unit_seconds.end(), 0.0);
  const double longest = *std::max_element(costs.unit_seconds.begin(), costs.unit_seconds.end());
  std::string out;
  if (format == "csv") {
    out = "workers,units,total_s,longest_unit_s,bound_s,wall_s,work_fraction,blocks_wall_s,blocks_work_fraction,"
          "known_wall_s,known_work_fraction\n";
  } else {
    out = fmt::format("{}{}: {} units ({} items x {}), {:.4g} s of algorithm time, longest unit {:.4g} s\n"
                      "{:>8} {:>11} {:>11} {:>9} {:>10} {:>15} {:>10} {:>14}\n",
                      costs.source, costs.from_means ? " (means per point and algorithm)" : "", costs.unit_seconds.size(),
                      costs.items(), costs.parts, total, longest, "workers",
                      "bound_s", "wall_s", "fraction", "wall/bound", "8-item blocks_s", "fraction", "costs known_s");
  }
  for (const long long w : workers) {
    const double bound = schedule_lower_bound(costs, w);
    const SchedulePrediction now = simulate_work_queue(costs, w);
    const SchedulePrediction blocks = simulate_item_blocks(costs, w);
    const SchedulePrediction known = simulate_work_queue(costs, w, true);
    if (format == "csv") {
      out += fmt::format("{},{},{},{},{},{},{},{},{},{},{}\n", w, costs.unit_seconds.size(), total, longest, bound,
                         now.wall_seconds, now.work_fraction, blocks.wall_seconds, blocks.work_fraction, known.wall_seconds,
                         known.work_fraction);
    } else {
      out += fmt::format("{:>8} {:>11.4g} {:>11.4g} {:>9.3f} {:>10.3f} {:>15.4g} {:>10.3f} {:>14.4g}\n", w, bound,
                         now.wall_seconds, now.work_fraction, now.wall_seconds / bound, blocks.wall_seconds,
                         blocks.work_fraction, known.wall_seconds);
    }
  }
  print_stdout(out);
  return 0;
}

// "a,b,c" → {"a", "b", "c"}; an empty item is an error naming the option.
int command_compare(int argc, char** argv) {
  po::options_description options("compare options");
  std::vector<std::string> runs;
  std::string algorithms, metrics, format;
  options.add_options()
      ("runs", po::value(&runs)->multitoken(), "one run folder, or two of the same plan")
      ("algorithms", po::value(&algorithms)->required(), "A,B (one run) or A (two runs): SPECs as in trials.csv (bp:delta=1e-9,check_every=10,exact is two)")
      ("metric", po::value(&metrics), "metric columns, comma-separated (default: the kind's error and time)")
      ("format", po::value(&format)->default_value("table"), "table or csv");
  po::positional_options_description positional;
  positional.add("runs", -1);
  const auto parsed = parse_command("compare", kCompareUsage, options, positional, argc, argv);
  if (!parsed) return 0;
  if (runs.empty() || runs.size() > 2) throw InputError("compare: give one run folder, or two runs of the same plan");
  if (format != "table" && format != "csv") throw InputError(fmt::format("compare: --format must be table or csv, not '{}'", format));
  CompareOptions compare;
  compare.run_a = runs[0];
  if (runs.size() == 2) compare.run_b = runs[1];
  // SPECs hold commas too ("bp:delta=1e-9,check_every=10"): an item with '=' and no ':' goes on
  // the SPEC before it.
  for (const std::string& item : comma_list(algorithms, "compare", "--algorithms")) {
    const bool continues = item.find('=') != std::string::npos && item.find(':') == std::string::npos;
    if (continues && !compare.algorithms.empty()) {
      compare.algorithms.back() += "," + item;
    } else {
      compare.algorithms.push_back(item);
    }
  }
  if (parsed->count("metric")) compare.metrics = comma_list(metrics, "compare", "--metric");
  const Comparison comparison = compare_runs(compare);
  print_stdout((format == "csv" ? comparison_csv(comparison) : comparison_table(comparison)));
  return 0;
}

}  // namespace

int cli_main(int argc, char** argv) {
  hold_closed_standard_streams();
  retain_freed_heap_memory();
  const std::string command = argc > 1 ? argv[1] : "";
  try {
    if (command == "list") return command_list(argc - 1, argv + 1);
    if (command == "solve") return command_solve(argc - 1, argv + 1);
    if (command == "run") {
      return command_run(argc - 1, argv + 1, joined_command_line(argc, argv), resume_command_line(argc, argv));
    }
    if (command == "merge") return command_merge(argc - 1, argv + 1, joined_command_line(argc, argv));
    if (command == "schedule") return command_schedule(argc - 1, argv + 1);
    if (command == "compare") return command_compare(argc - 1, argv + 1);
    if (command == "-h" || command == "--help" || command == "help") {
      if (argc > 2) throw InputError(fmt::format("{}: unexpected argument '{}' (for a command's usage: dabench COMMAND --help)", command, argv[2]));
      print_stdout(program_usage());
      return 0;
    }
    if (command == "--version") {
      if (argc > 2) throw InputError(fmt::format("--version: unexpected argument '{}'", argv[2]));
      print_stdout(version_line());
      return 0;
    }
    throw InputError(command.empty() ? "missing command (list, solve, run, merge, schedule or compare; see dabench --help)"
                                     : fmt::format("unknown command '{}' (list, solve, run, merge, schedule or compare; see dabench --help)", command));
  } catch (const WriteError& error) {  // README: exit 1 when a write fails
    std::fprintf(stderr, "dabench: %s\n", printable_line(error.what()).c_str());
    return 1;
  } catch (const InputError& error) {
    std::fprintf(stderr, "dabench: %s\n", printable_line(error.what()).c_str());
    return 2;
  } catch (const std::filesystem::filesystem_error& error) {
    // The system's refusal of a path (too long, not a folder, ...): the path and the reason,
    // not the library's "filesystem error: ..." wording.
    std::fprintf(stderr, "dabench: %s\n",
                 printable_line(fmt::format("{}: {}", error.path1().string(), error.code().message())).c_str());
    return 2;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "dabench: internal error: %s\n", printable_line(error.what()).c_str());
    return 1;
  }
}

}  // namespace dabench
