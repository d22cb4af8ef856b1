#include "harness/run/runner.hpp"

#include <omp.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <numeric>
#include <optional>
#include <set>
#include <thread>

#include <fmt/format.h>

#include "harness/core/atomic_file.hpp"
#include "harness/core/csv.hpp"
#include "harness/core/errors.hpp"
#include "harness/core/ordered_writer.hpp"
#include "harness/core/progress.hpp"
#include "harness/core/row_fields.hpp"
#include "harness/core/summary.hpp"
#include "harness/run/execution.hpp"
#include "harness/run/folder_lock.hpp"
#include "harness/run/mpi_transport.hpp"
#include "harness/run/rank_messages.hpp"
#include "harness/run/row_checksums.hpp"
#include "harness/run/run_folder.hpp"
#include "harness/run/run_meta.hpp"
#include "harness/run/run_plan.hpp"
#include "harness/run/schedule_simulation.hpp"
#include "harness/run/work_queue.hpp"

namespace dabench {

namespace {

using Clock = std::chrono::steady_clock;

// Set by the signal handler and by a failing rank's coordinator, read by every thread: a
// lock-free atomic (safe in a signal handler, and no data race between threads).
std::atomic<bool> g_interrupted{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the interrupt flag must be usable in a signal handler");
extern "C" void on_interrupt(int) { g_interrupted.store(true, std::memory_order_relaxed); }

// SIGINT, SIGTERM and SIGHUP set g_interrupted while this lives (mpirun passes Ctrl-C on as
// SIGTERM; a closed terminal or ssh session sends SIGHUP): the run stops with whole rows and
// meta.json "interrupted".
class InterruptHandlers {
 public:
  InterruptHandlers() {
    g_interrupted = false;
    for (std::size_t k = 0; k < kSignals.size(); ++k) previous_[k] = std::signal(kSignals[k], on_interrupt);
  }
  ~InterruptHandlers() {
    for (std::size_t k = 0; k < kSignals.size(); ++k) std::signal(kSignals[k], previous_[k]);
  }
  InterruptHandlers(const InterruptHandlers&) = delete;
  InterruptHandlers& operator=(const InterruptHandlers&) = delete;

 private:
  static constexpr std::array<int, 3> kSignals = {SIGINT, SIGTERM, SIGHUP};
  std::array<void (*)(int), 3> previous_{};
};

// A chunk's texts for the writer: one per row file, then the checksums.csv lines recording them.
std::vector<std::string> with_checksums(std::vector<std::string>&& texts, const std::vector<std::string>& names) {
  std::string lines;
  append_checksum_lines(lines, names, texts);
  texts.push_back(std::move(lines));
  return std::move(texts);
}

// Per unit of this process, its time in the run in `folder` (--costs-from), which must be of the
// same kind, points, trials and algorithms. InputError otherwise, or for a kind whose algorithms
// share an item (single scan).
std::vector<double> unit_predictions(const RunPlan& plan, const std::string& folder) {
  if (plan.kind->shares_items()) {
    throw InputError(fmt::format("run: --costs-from orders (item, algorithm) units longest first; {} items run in "
                                 "order (their algorithms share the item)", plan.kind->name()));
  }
  require_complete_run(folder, "run --costs-from");
  const RunCosts costs = read_run_costs(folder, "run --costs-from");
  if (costs.kind != plan.kind) {
    throw InputError(fmt::format("run: --costs-from {}: a {} run; this one is {}", folder, costs.kind->name(), plan.kind->name()));
  }
  if (costs.from_means || costs.items() != plan.items() || costs.parts != plan.parts()) {
    throw InputError(fmt::format("run: --costs-from {}: {} holds {} items of {} algorithms{}, this run {} of {}", folder,
                                 costs.source, costs.items(), costs.parts, costs.from_means ? " (means only)" : "",
                                 plan.items(), plan.parts()));
  }
  std::vector<double> predictions(static_cast<std::size_t>(plan.shard_items() * plan.parts()));
  for (std::size_t unit = 0; unit < predictions.size(); ++unit) {
    const long long item = plan.global_item(static_cast<long long>(unit) / plan.parts());
    predictions[unit] = costs.unit_seconds[static_cast<std::size_t>(item * plan.parts()) + unit % static_cast<std::size_t>(plan.parts())];
  }
  return predictions;
}

// The next chunk of units for a thread or rank that asks (harness/run/work_queue.hpp); none
// once interrupted.
std::optional<WorkChunk> take_chunk(WorkQueue& queue) {
  if (g_interrupted) return std::nullopt;
  return queue.take();
}

// The queue of this process's units [first_unit, total_units) for `workers` threads in all:
// single-scan items in order (their algorithms share the reference), the other kinds' (item,
// algorithm) units longest first, predicted by `predictions` (per unit of this process) if any.
WorkQueue make_work_queue(const RunPlan& plan, long long first_unit, long long workers, std::vector<double> predictions) {
  WorkQueueOptions options;
  options.unit_predictions = std::move(predictions);
  options.parts = plan.parts();
  options.workers = workers;
  options.order = plan.kind->shares_items() ? WorkOrder::in_order : WorkOrder::longest_first;
  if (options.order == WorkOrder::longest_first) {
    options.points = static_cast<int>(plan.point_params.size());
    options.item_points.resize(static_cast<std::size_t>(plan.shard_items()));
    for (long long local = 0; local < plan.shard_items(); ++local) {
      options.item_points[static_cast<std::size_t>(local)] = static_cast<int>(plan.global_item(local) / plan.trials);
    }
  }
  return WorkQueue(first_unit, plan.shard_items() * plan.parts(), std::move(options));
}

// Whether rank 0 of an mpirun job draws the progress line: Open MPI hands the ranks a pipe for
// stderr (never a terminal) and a pseudo-terminal for stdout, so stdout stands in for it;
// DABENCH_PROGRESS=0 or 1 decides instead (e.g. 0 for a batch job's log).
bool progress_under_mpirun() {
  if (const char* choice = std::getenv("DABENCH_PROGRESS")) return std::string(choice) != "0";
  return isatty(STDOUT_FILENO) != 0;
}

// Waiting for an MPI message by polling with growing sleeps (20 µs doubling to 1 ms): a
// blocking MPI probe or receive spins a core, which the computing threads need.
class IdleWait {
 public:
  void wait() {
    std::this_thread::sleep_for(sleep_);
    sleep_ = std::min(sleep_ * 2, std::chrono::microseconds(1000));
  }

 private:
  std::chrono::microseconds sleep_{20};
};

// The next message from `source` with `tag`, waited for by polling.
std::string receive_polling(const MpiTransport& mpi, int source, int tag) {
  IdleWait idle;
  while (true) {
    if (const auto envelope = mpi.probe(source, tag)) return mpi.receive(*envelope);
    idle.wait();
  }
}

// Runs a chunk's units into worker.texts (cleared first) and their times into unit_seconds.
void run_chunk(const RunExecution& execution, RunWorker& worker, const RunPlan& plan, WorkChunk chunk,
               std::vector<double>& unit_seconds) {
  for (std::string& text : worker.texts) text.clear();
  unit_seconds.clear();
  const long long parts = plan.parts();
  for (long long unit = chunk.begin; unit < chunk.end; ++unit) {
    const auto start = Clock::now();
    execution.run_unit(worker, plan.global_item(unit / parts), static_cast<std::size_t>(unit % parts));
    unit_seconds.push_back(std::chrono::duration<double>(Clock::now() - start).count());
  }
}

// Runs chunks from `queue` on this process's OpenMP threads (each with its own worker) and
// hands each chunk's texts to the ordered writer; draws `progress` unless null and tells
// `on_progress` unless empty (in items). Returns the threads' busy seconds.
double run_local_chunks(const RunExecution& execution, const RunPlan& plan, WorkQueue& queue, OrderedWriter& writer,
                        const std::vector<std::string>& names, std::atomic<long long>& units_finished, ProgressLine* progress,
                        const std::function<void(long long, long long)>& on_progress) {
  const long long parts = plan.parts();
  const long long total_units = plan.shard_items() * parts;
  double busy_seconds = 0.0;
#pragma omp parallel num_threads(plan.threads) reduction(+ : busy_seconds)
  {
    const std::unique_ptr<RunWorker> made = execution.make_worker();
    RunWorker& worker = *made;
    const std::size_t files = worker.texts.size();
    std::vector<double> unit_seconds;
    while (const auto chunk = take_chunk(queue)) {
      run_chunk(execution, worker, plan, *chunk, unit_seconds);
      for (long long unit = chunk->begin; unit < chunk->end; ++unit) queue.finished(unit, unit_seconds[unit - chunk->begin]);
      const long long written = writer.submit(chunk->begin, chunk->end, with_checksums(std::move(worker.texts), names));
      if (writer.failed()) g_interrupted = true;  // the first failed write stops the run
      worker.texts = std::vector<std::string>(files);
      const long long done = (units_finished += chunk->end - chunk->begin) / parts;
      if (progress != nullptr && (omp_get_thread_num() == 0 || written == total_units)) progress->update(done);
      if (on_progress) on_progress(done, plan.shard_items());
    }
    busy_seconds += worker.busy_seconds;
  }
  return busy_seconds;
}

// A worker rank's threads: each asks rank 0 for chunks (two requests in flight, so the answer
// to the next is there when it finishes a chunk), runs them and sends their rows and unit times
// back with its next request, until rank 0 answers "none" (then every later answer is none too).
// Threads call MPI one at a time (MPI_THREAD_SERIALIZED) and wait for answers by polling.
void serve_chunks(const RunExecution& execution, const RunPlan& plan, const MpiTransport& mpi) {
#pragma omp parallel num_threads(plan.threads)
  {
    if (omp_get_num_threads() != plan.threads) {  // rank 0 counts on plan.threads requesters
#pragma omp critical(dabench_mpi)
      {
        std::fprintf(stderr, "dabench: rank %d: OpenMP gave %d threads, not %d (OMP_THREAD_LIMIT?)\n", mpi.rank(),
                     omp_get_num_threads(), plan.threads);
        mpi.abort(1);
      }
    }
    const std::unique_ptr<RunWorker> made = execution.make_worker();
    RunWorker& worker = *made;
    const std::size_t files = worker.texts.size();
    const int tag = omp_get_thread_num();
    const auto send = [&](const ChunkResult& result) {
      const std::string message = encode(result);
#pragma omp critical(dabench_mpi)
      mpi.send(0, tag, message);
    };
    send(ChunkResult{});
    send(ChunkResult{});
    int in_flight = 2;
    while (in_flight > 0) {
      std::string answer;
      bool received = false;
      IdleWait idle;
      while (true) {
#pragma omp critical(dabench_mpi)
        if (const auto envelope = mpi.probe(0, tag)) {
          answer = mpi.receive(*envelope);
          received = true;
        }
        if (received) break;
        idle.wait();
      }
      --in_flight;
      const std::optional<WorkChunk> chunk = decode_chunk(answer);
      if (!chunk) continue;
      ChunkResult result;
      result.interrupted = g_interrupted.load();
      if (!result.interrupted) {  // else the chunk is left to --resume
        run_chunk(execution, worker, plan, *chunk, result.unit_seconds);
        result.chunk = chunk;
        result.texts = std::move(worker.texts);
        worker.texts = std::vector<std::string>(files);
      }
      result.busy_seconds = worker.busy_seconds;
      send(result);
      ++in_flight;
    }
  }
}

// Rank 0's main thread while its own threads run chunks (until local_done): answers the other
// ranks' requests for chunks from `queue`, hands their rows to the writer and their unit times
// to the queue, and draws the progress line for the whole job. Returns the remote threads' busy
// seconds.
double coordinate(const MpiTransport& mpi, long long remote_threads, WorkQueue& queue, long long parts,
                  OrderedWriter& writer, const std::vector<std::string>& names, std::atomic<long long>& units_finished,
                  ProgressLine& progress,
                  const std::atomic<bool>& local_done) {
  std::map<std::pair<int, int>, double> busy_seconds;  // by (rank, thread)
  long long stops_to_send = 2 * remote_threads;       // every remote thread stops after two "none"
  IdleWait idle;
  while (stops_to_send > 0 || !local_done.load()) {
    progress.update(units_finished.load() / parts);
    const auto envelope = mpi.probe(-1, -1);
    if (!envelope) {
      idle.wait();
      continue;
    }
    idle = IdleWait{};
    ChunkResult result = decode_chunk_result(mpi.receive(*envelope));
    if (result.interrupted) g_interrupted = true;  // one rank's Ctrl-C stops the job
    busy_seconds[{envelope->source, envelope->tag}] = result.busy_seconds;
    if (result.chunk) {
      const WorkChunk& chunk = *result.chunk;
      for (long long unit = chunk.begin; unit < chunk.end; ++unit) queue.finished(unit, result.unit_seconds[unit - chunk.begin]);
      units_finished += chunk.end - chunk.begin;
      writer.submit(chunk.begin, chunk.end, with_checksums(std::move(result.texts), names));
      if (writer.failed()) g_interrupted = true;
    }
    const auto next = take_chunk(queue);
    if (!next) --stops_to_send;
    mpi.send(envelope->source, envelope->tag, encode_chunk(next));
  }
  double total = 0.0;
  for (const auto& [thread, seconds] : busy_seconds) total += seconds;
  return total;
}

// Rank 0: every other rank's Hello (in rank order), the reasons it cannot run ("" if none).
std::vector<Hello> receive_hellos(const MpiTransport& mpi) {
  std::vector<Hello> hellos;
  for (int rank = 1; rank < mpi.size(); ++rank) hellos.push_back(decode_hello(receive_polling(mpi, rank, kHelloTag)));
  return hellos;
}

// A rank other than 0: reads the experiment, greets rank 0, waits for the start, then runs the
// chunks rank 0 hands it. Its InputErrors are reported by rank 0.
RunOutcome run_worker_rank(const RunOptions& options, const MpiTransport& mpi) {
  Hello hello;
  hello.host = host_name();
  std::optional<RunPlan> plan;
  try {
    plan.emplace(make_run_plan(options));
    hello.fingerprint = plan->fingerprint();
    hello.threads = plan->threads;
  } catch (const InputError& error) {
    hello.error = error.what();
  }
  mpi.send(0, kHelloTag, encode(hello));
  if (!hello.error.empty()) throw InputError(hello.error);
  const Start start = decode_start(receive_polling(mpi, 0, kStartTag));
  if (!start.error.empty()) throw InputError(start.error);

  const InterruptHandlers handlers;
  serve_chunks(*plan->kind->make_execution(*plan), *plan, mpi);
  RunOutcome outcome;
  outcome.items_total = plan->shard_items();
  outcome.output = plan->output;
  outcome.worker_rank = true;
  return outcome;
}

// Under MPI, rank 0 stops every worker rank that read the experiment with `error`; the error
// to throw on rank 0.
InputError stop_workers(const MpiTransport* mpi, const std::vector<Hello>& hellos, const std::string& error) {
  for (std::size_t k = 0; k < hellos.size(); ++k) {
    if (hellos[k].error.empty()) mpi->send(static_cast<int>(k) + 1, kStartTag, encode(Start{error}));
  }
  return InputError(error);
}

// Rank 0's plan, checked against every worker rank's reading of the experiment (their Hellos,
// into `hellos`), and the units' predicted costs of --costs-from (into `predictions`). An error
// of rank 0 or of any rank stops every rank.
RunPlan checked_plan(const RunOptions& options, std::vector<Hello>& hellos, std::vector<double>& predictions) {
  const MpiTransport* mpi = options.transport;
  std::optional<RunPlan> plan;
  std::string error;
  try {
    plan.emplace(make_run_plan(options));
  } catch (const InputError& plan_error) {
    if (mpi == nullptr) throw;
    error = plan_error.what();
  }
  if (mpi != nullptr) hellos = receive_hellos(*mpi);
  for (std::size_t k = 0; k < hellos.size() && error.empty(); ++k) {
    const Hello& hello = hellos[k];
    if (!hello.error.empty()) {
      error = fmt::format("rank {} ({}): {}", k + 1, hello.host, hello.error);
    } else if (hello.fingerprint != plan->fingerprint()) {
      error = fmt::format("rank {} ({}) read another experiment, seed or trials than rank 0 (different files on its host?)",
                          k + 1, hello.host);
    }
  }
  if (error.empty() && options.costs_from) {
    try {
      predictions = unit_predictions(*plan, *options.costs_from);
    } catch (const InputError& costs_error) {
      if (mpi == nullptr) throw;
      error = costs_error.what();
    }
  }
  if (!error.empty()) throw stop_workers(mpi, hellos, error);
  return std::move(*plan);
}

// meta.json's record of a run that starts: its command line, start time, hosts and, under MPI,
// each rank's host and threads.
RunRecord started_record(const RunOptions& options, const RunPlan& plan, const std::vector<Hello>& hellos) {
  RunRecord record;
  record.command_line = options.command_line;
  record.status = "running";
  record.start_time = utc_now();
  record.hosts = host_name();
  if (options.transport != nullptr) {
    record.rank_hosts.push_back(record.hosts);
    record.rank_threads.push_back(plan.threads);
    std::set<std::string> seen_hosts = {record.hosts};
    for (const Hello& hello : hellos) {
      record.rank_hosts.push_back(hello.host);
      record.rank_threads.push_back(hello.threads);
      if (seen_hosts.insert(hello.host).second) record.hosts += "," + hello.host;
    }
    record.processes = options.transport->size();
  }
  return record;
}

// What the writer left: items written, whether the run was cut short, the first failed write
// (with its file's path).
RunOutcome written_outcome(const RunPlan& plan, const OrderedWriter& writer, std::vector<std::string> names) {
  RunOutcome outcome;
  if (const auto failure = writer.failure()) {
    names.push_back(kChecksumsFile);  // the writer's last file
    const std::string path = (std::filesystem::path(plan.output) / names.at(failure->file)).string();
    outcome.write_error = fmt::format("{}: write failed ({})", path, std::strerror(failure->error));
  }
  outcome.items_total = plan.shard_items();
  outcome.items_written = writer.next() / plan.parts();
  outcome.interrupted = outcome.items_written < outcome.items_total;
  outcome.output = plan.output;
  for (const ItemFile& file : plan.item_files()) outcome.item_files.push_back(file.name);
  return outcome;
}

}  // namespace

void interrupt_run() { g_interrupted = true; }

RunOutcome run_experiment(const RunOptions& options) {
  const MpiTransport* mpi = options.transport;
  if (mpi != nullptr && mpi->rank() != 0) return run_worker_rank(options, *mpi);

  std::vector<Hello> hellos;
  std::vector<double> predictions;
  const RunPlan plan = checked_plan(options, hellos, predictions);
  RunRecord record = started_record(options, plan, hellos);
  // Held until the end: no other process reads or writes the folder meanwhile.
  std::optional<FolderLock> lock;
  OpenedRun opened;
  try {
    lock.emplace(plan.output, "run");
    opened = open_run_files(plan, options.resume, options.force, run_meta_json(plan, record));
  } catch (const InputError& open_error) {
    if (mpi == nullptr) throw;
    throw stop_workers(mpi, hellos, open_error.what());
  }
  const std::vector<std::FILE*>& files = opened.files;
  record.items_done = opened.items_done;
  record.resumed = opened.resumed;
  write_file_atomically(meta_path(plan), run_meta_json(plan, record));

  const long long total_items = plan.shard_items();
  const long long parts = plan.parts();
  const long long first_unit = opened.items_done * parts;
  for (std::size_t k = 0; k < hellos.size(); ++k) mpi->send(static_cast<int>(k) + 1, kStartTag, encode(Start{""}));
  long long workers = plan.threads;
  for (const Hello& hello : hellos) workers += hello.threads;
  WorkQueue queue = make_work_queue(plan, first_unit, workers, std::move(predictions));
  OrderedWriter writer(files, first_unit);
  ProgressLine progress(total_items, opened.items_done,
                        options.draw_progress && (mpi != nullptr ? progress_under_mpirun() : stderr_is_terminal()));

  const InterruptHandlers handlers;
  const auto wall_start = Clock::now();
  std::atomic<long long> units_finished{first_unit};
  const std::unique_ptr<RunExecution> execution_made = plan.kind->make_execution(plan);
  const RunExecution& execution = *execution_made;
  const double busy_seconds = [&] {
    if (mpi == nullptr) {
      return run_local_chunks(execution, plan, queue, writer, opened.names, units_finished, &progress, options.on_progress);
    }
    std::atomic<bool> local_done{false};
    double local_busy = 0.0;
    std::thread local([&] {
      local_busy = run_local_chunks(execution, plan, queue, writer, opened.names, units_finished, nullptr, options.on_progress);
      local_done = true;
    });
    long long remote_threads = 0;
    for (const Hello& hello : hellos) remote_threads += hello.threads;
    double remote_busy = 0.0;
    try {
      remote_busy = coordinate(*mpi, remote_threads, queue, parts, writer, opened.names, units_finished, progress, local_done);
    } catch (...) {
      g_interrupted = true;
      local.join();
      throw;
    }
    local.join();
    return local_busy + remote_busy;
  }();
  progress.finish();
  const double wall_seconds = std::chrono::duration<double>(Clock::now() - wall_start).count();
  for (std::FILE* file : files) std::fclose(file);

  RunOutcome outcome = written_outcome(plan, writer, opened.names);
  // A failed write of summary.csv or meta.json at the end is reported as a failed row write
  // is: every row stays, and --resume (with space freed) writes them again.
  const auto keep_first_write_error = [&outcome](const auto& write) {
    try {
      write();
    } catch (const WriteError& failed) {
      if (outcome.write_error.empty()) outcome.write_error = failed.what();
    }
  };
  if (!outcome.interrupted) {
    keep_first_write_error([&] { write_summary(trials_path(plan), summary_path(plan), plan.metric_columns()); });
  }
  record.status = outcome.interrupted || !outcome.write_error.empty() ? "interrupted" : "complete";
  record.items_done = outcome.items_written;
  record.end_time = utc_now();
  record.wall_seconds = wall_seconds;
  const double threads = std::accumulate(record.rank_threads.begin(), record.rank_threads.end(), 0.0);
  record.work_fraction =
      wall_seconds > 0.0 ? busy_seconds / (wall_seconds * (mpi != nullptr ? threads : plan.threads)) : std::nan("");
  // Left as it was, meta.json still holds the fingerprint and shard --resume checks.
  keep_first_write_error([&] { write_file_atomically(meta_path(plan), run_meta_json(plan, record)); });
  return outcome;
}

}  // namespace dabench
