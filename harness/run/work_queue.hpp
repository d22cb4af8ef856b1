#pragma once
// Which work units a worker (a thread of this process, or a thread of another rank) runs next.
//
// A unit is one item (point, trial) of a single-scan run, whose algorithms are measured against
// the reference solved on the same draw; for the other kinds, whose algorithms are independent
// given the draw, it is one (item, algorithm), so one slow algorithm does not hold a worker while
// others wait. Units are numbered in item order: unit = local item × parts + part. Rows are
// written in unit order whatever the order the units ran in (harness/core/ordered_writer.hpp),
// so the files do not depend on the schedule.
//
// Two orders (WorkOrder):
//   in_order      chunks of consecutive units, ⌈remaining / (kChunksPerWorker × workers)⌉ units
//                 but at most kMaxChunkItems items' worth and at least one unit: light studies
//                 keep blocks of 8 items (the writer, not scheduling, limits them), and the
//                 chunks shrink to single units as the run ends, so no worker idles while another
//                 finishes a long block (guided scheduling).
//   longest_first one unit at a time: of the units not yet handed out among the next
//                 kWindowPerWorker × workers items, the one predicted to take longest: by its
//                 own time in a previous run of the same plan when one is given (`dabench run
//                 --costs-from`), else by the mean time of the finished units of its class
//                 (point, part), a class not timed yet counting as longest, so that each
//                 class's first unit runs early and times it (ties: the lowest unit). The window
//                 bounds the rows waiting to be written in order, and what an interrupted run loses.
// Thread-safe.
#include <mutex>
#include <optional>
#include <vector>

namespace dabench {

enum class WorkOrder { in_order, longest_first };

struct WorkChunk {
  long long begin = 0;  // units [begin, end)
  long long end = 0;
};

struct WorkQueueOptions {
  WorkOrder order = WorkOrder::in_order;
  int parts = 1;                  // units per item
  long long workers = 1;          // threads that take chunks (all ranks')
  // Per item of this process (local numbering), its point: the class of a unit is (point, part).
  std::vector<int> item_points;   // needed for longest_first only
  int points = 1;
  // longest_first: each unit's time in a previous run (all units, in unit order), or empty.
  std::vector<double> unit_predictions;
};

constexpr long long kChunksPerWorker = 4;
constexpr long long kMaxChunkItems = 8;
constexpr long long kWindowPerWorker = 4;

class WorkQueue {
 public:
  // Units [first_unit, total_units) are still to run (first_unit: --resume's whole items × parts).
  WorkQueue(long long first_unit, long long total_units, WorkQueueOptions options);

  std::optional<WorkChunk> take();  // nothing once every unit was handed out
  void finished(long long unit, double seconds);  // a unit's time, for longest_first's predictions

 private:
  std::optional<WorkChunk> take_in_order();
  std::optional<WorkChunk> take_longest();
  int unit_class(long long unit) const;

  WorkQueueOptions options_;
  long long total_units_;
  long long next_;           // in_order: the first unit not handed out
  long long first_item_;     // longest_first: items before it are fully handed out
  std::vector<char> taken_;  // longest_first: per unit from first_unit_ on
  long long first_unit_;
  std::vector<double> class_seconds_;
  std::vector<long long> class_count_;
  std::mutex mutex_;
};

}  // namespace dabench
