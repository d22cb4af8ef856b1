// dabench run: an experiment file into its output folder, on this process's threads, or over
// the ranks of an mpirun job, or as one shard of several.
#include <cstdio>
#include <memory>

#include <fmt/format.h>

#include "apps/cli/command.hpp"
#include "harness/core/errors.hpp"
#include "harness/core/input_file.hpp"
#include "harness/run/mpi_transport.hpp"
#include "harness/run/runner.hpp"
#include "harness/run/shard_meta.hpp"

namespace dabench::cli {

namespace {

Shard parse_shard(const std::string& text) {
  const auto shard = parse_shard_label(text);
  if (!shard) throw InputError(fmt::format("run: --shard '{}' must be K/N with 1 <= K <= N <= {}", text, kMaxShards));
  return *shard;
}

int run_options(const Invocation& invocation, const MpiTransport* mpi) {
  po::options_description options("run options");
  RunOptions run;
  run.command_line = invocation.command_line;
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
  const auto parsed = parse_command(kRunCommand, options, positional, invocation);
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
  const std::string resume_line =
      mpi != nullptr ? fmt::format("mpirun -np {} {}", mpi->size(), invocation.resume_line) : invocation.resume_line;
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
int run_run(const Invocation& invocation) {
  const std::unique_ptr<MpiTransport> mpi = MpiTransport::open_if_launched();
  if (mpi == nullptr) return run_options(invocation, nullptr);
  try {
    return run_options(invocation, mpi.get());
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

}  // namespace

const Command kRunCommand{
    "run",
    "dabench run EXPERIMENT.ini [--trials N] [--threads T] [--seed S] [--out DIR] [--resume|--force] [--shard K/N] [--costs-from DIR]",
    "Runs an experiment file and writes trials.csv, summary.csv and meta.json (and the kind's\n"
    "per-trial files) into its output folder. Ctrl-C stops after the trials in flight.\n"
    "With --shard K/N, runs only shard K of N (blocks of 8 trials, round robin) into its own\n"
    "folder (default: the experiment's output + -shard-K-of-N); `dabench merge` joins them.\n"
    "With --costs-from DIR (a previous run of the same plan), the (trial, algorithm) units of a\n"
    "multi-scan, tracking or track-before-detect run start longest first by their times there.\n",
    run_run};

}  // namespace dabench::cli
