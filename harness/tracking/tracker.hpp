#pragma once
// The interface of trackers (jdt-vb-multipath-othr): the third kind of algorithm beside
// single-scan and multi-scan ones. A tracker takes a whole run (K scans of measurements and
// the known model) and returns tracks. It sees the TrackingProblem only, never the truth.
// As for the other kinds, one tracker object serves one thread for a whole run.
#include <vector>

#include "harness/core/solve_report.hpp"
#include "harness/tracking/problem.hpp"

namespace dabench {

class Tracker {
 public:
  virtual ~Tracker() = default;
  // Replaces `tracks` with the run's tracks unless report.skipped is set; iterative trackers
  // report iterations, convergence and their final objective (free_energy) in `report`.
  virtual void run(const TrackingProblem& problem, TrackSet& tracks, SolveReport& report) = 0;

  // Per-iteration history, for metrics versus iteration (Fig. 7). While set, an iterative
  // tracker appends to it, during run(), its track set before the first iteration (r = 0) and
  // after each iteration r = 1, 2, ...; trackers without iterations leave it alone. The caller
  // owns and clears it; nullptr (the default) records nothing and costs nothing.
  void record_iterations(std::vector<TrackSet>* history) { iteration_history_ = history; }

 protected:
  std::vector<TrackSet>* iteration_history() const { return iteration_history_; }

 private:
  std::vector<TrackSet>* iteration_history_ = nullptr;
};

}  // namespace dabench
