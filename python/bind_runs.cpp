// The handle behind dabench.run(): the run goes on a thread of its own, so that the Python
// thread that waits for it draws the progress bar and stays responsive. Ctrl-C stops the run as
// it stops `dabench run` (the trials in flight finish; resume=True completes it).
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>

#include <fmt/format.h>

#include "harness/core/errors.hpp"
#include "harness/run/runner.hpp"
#include "python/bindings.hpp"

namespace dabench::python {
namespace {

// One run at a time per process: a run owns the process's interrupt handling.
std::atomic<bool> g_run_in_progress{false};

class RunHandle {
 public:
  explicit RunHandle(RunOptions options) {
    if (g_run_in_progress.exchange(true)) throw InputError("run: another run is in progress in this process");
    options.draw_progress = false;
    options.on_progress = [this](long long done, long long total) {
      total_ = total;
      done_ = done;
    };
    thread_ = std::thread([this, options = std::move(options)] {
      try {
        outcome_ = run_experiment(options);
      } catch (...) {
        error_ = std::current_exception();
      }
      {
        const std::lock_guard lock(mutex_);
        finished_ = true;
      }
      finished_signal_.notify_all();
    });
  }
  RunHandle(const RunHandle&) = delete;
  RunHandle& operator=(const RunHandle&) = delete;
  ~RunHandle() {  // a handle dropped while its run goes on stops the run
    if (!thread_.joinable()) return;
    const py::gil_scoped_release release;
    while (!wait_released(0.05)) interrupt_run();
    thread_.join();
    g_run_in_progress = false;
  }

  // Whether the run has finished, after waiting up to `seconds`.
  bool wait(double seconds) {
    const py::gil_scoped_release release;
    return wait_released(seconds);
  }
  std::pair<long long, long long> progress() const { return {done_.load(), total_.load()}; }
  // Until the run has started its trials, the request is repeated: the caller calls again.
  void interrupt() { interrupt_run(); }

  // The outcome as a dict; the run's error (ValueError for bad input) raised here.
  py::dict result() {
    if (thread_.joinable()) {
      const py::gil_scoped_release release;
      thread_.join();
      g_run_in_progress = false;
    }
    if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
    py::dict out;
    out["output"] = outcome_.output;
    out["items_total"] = outcome_.items_total;
    out["items_written"] = outcome_.items_written;
    out["interrupted"] = outcome_.interrupted;
    out["write_error"] = outcome_.write_error;
    out["item_files"] = outcome_.item_files;
    return out;
  }

 private:
  bool wait_released(double seconds) {
    std::unique_lock lock(mutex_);
    return finished_signal_.wait_for(lock, std::chrono::duration<double>(seconds), [this] { return finished_; });
  }

  std::thread thread_;
  std::mutex mutex_;
  std::condition_variable finished_signal_;
  bool finished_ = false;
  std::atomic<long long> done_{0}, total_{0};
  RunOutcome outcome_;
  std::exception_ptr error_;
};

std::unique_ptr<RunHandle> start_run(const std::string& experiment, std::optional<std::int64_t> trials,
                                     std::optional<int> threads, std::optional<std::int64_t> seed,
                                     std::optional<std::string> out, bool resume, bool force,
                                     const std::string& command_line) {
  RunOptions run;
  run.experiment_path = experiment;
  run.command_line = command_line;
  if (resume && force) throw InputError("run: resume and force exclude each other");
  if (trials) {
    if (*trials < 1) throw InputError(fmt::format("run: trials {} must be >= 1", *trials));
    run.trials = *trials;
  }
  if (threads) {
    if (*threads < 1) throw InputError(fmt::format("run: threads {} must be >= 1", *threads));
    run.threads = *threads;
  }
  if (seed) {
    if (*seed < 0) throw InputError(fmt::format("run: seed {} must be >= 0", *seed));
    run.seed = static_cast<std::uint64_t>(*seed);
  }
  run.output = std::move(out);
  run.resume = resume;
  run.force = force;
  return std::make_unique<RunHandle>(std::move(run));
}

}  // namespace

bool run_in_progress() { return g_run_in_progress.load(); }

void bind_runs(py::module_& module) {
  py::class_<RunHandle>(module, "RunHandle")
      .def("wait", &RunHandle::wait, py::arg("seconds"))
      .def("progress", &RunHandle::progress)
      .def("interrupt", &RunHandle::interrupt)
      .def("result", &RunHandle::result);
  module.def("start_run", &start_run, py::arg("experiment"), py::arg("trials") = py::none(),
             py::arg("threads") = py::none(), py::arg("seed") = py::none(), py::arg("out") = py::none(),
             py::arg("resume") = false, py::arg("force") = false, py::arg("command_line") = "");
}

}  // namespace dabench::python
