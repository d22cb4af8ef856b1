#pragma once
// The interface of track-before-detect trackers (tbd-bp-supplement): one frame at a time, so
// that the harness times each step (the supplement's Fig. 4 is runtime per step). A tracker
// sees the TbdProblem only, never the truth. One tracker object serves one thread for a run.
#include <vector>

#include "harness/core/solve_report.hpp"
#include "harness/tbd/problem.hpp"

namespace dabench {

// One weighted position sample of a potential object's belief (for figures).
struct TbdBeliefSample {
  int label = -1;
  double existence = 0.0;
  double x = 0.0, y = 0.0;
  double weight = 0.0;  // normalised over the object's samples
};

class TbdTracker {
 public:
  virtual ~TbdTracker() = default;
  // Starts a run on `problem` (which outlives the run's step() calls): forgets every object,
  // and seeds the tracker's random stream from problem.trial_key.
  virtual void start(const TbdProblem& problem) = 0;
  // Processes frame k (k = 0, 1, ... in order: prediction, update) and replaces `estimates`
  // with the objects it reports at k. Iterative trackers add their iterations to `report`.
  virtual void step(int k, std::vector<TbdEstimate>& estimates, SolveReport& report) = 0;
  // The beliefs of every object the tracker holds after the last step (particle trackers: their
  // particles; Gaussian ones may give their means). Optional: the default gives none.
  virtual void beliefs(std::vector<TbdBeliefSample>& samples) const { samples.clear(); }
};

}  // namespace dabench
