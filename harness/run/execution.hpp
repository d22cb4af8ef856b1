#pragma once
// The work of a run as the runner sees it, whatever the problem kind: workers (one per thread,
// reused for every unit it runs) and the units of harness/run/work_queue.hpp, run into row texts
// for the ordered writer. Each kind's execution (kinds/<kind>_execution.hpp) implements it; the
// runner makes one call per unit, outside every algorithm's loops.
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace dabench {

struct RunWorker {
  virtual ~RunWorker() = default;
  std::vector<std::string> texts;  // per row file, in the writer's order (the item files, then trials.csv)
  double busy_seconds = 0.0;       // time in the algorithms
};

class RunExecution {
 public:
  virtual ~RunExecution() = default;
  virtual std::unique_ptr<RunWorker> make_worker() const = 0;
  // Runs unit `part` of item `item` into worker.texts: algorithm `part` on the item's draw, or,
  // for a kind whose algorithms share an item (RunPlan::parts() == 1), all of them.
  virtual void run_unit(RunWorker& worker, long long item, std::size_t part) const = 0;
};

}  // namespace dabench
