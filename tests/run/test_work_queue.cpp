// The work queue (harness/run/work_queue.hpp): every unit is handed out exactly once; in order,
// chunks are 8 items long while much remains and single units at the end; longest first, untimed
// classes go first, then the class with the longest mean, within the window of items.
#include <catch2/catch.hpp>

#include <vector>

#include "harness/run/work_queue.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench;

namespace {

std::vector<WorkChunk> drain(WorkQueue& queue) {
  std::vector<WorkChunk> chunks;
  while (const auto chunk = queue.take()) chunks.push_back(*chunk);
  return chunks;
}

WorkQueueOptions longest_first(int parts, long long workers, std::vector<int> item_points, int points) {
  WorkQueueOptions options;
  options.order = WorkOrder::longest_first;
  options.parts = parts;
  options.workers = workers;
  options.item_points = std::move(item_points);
  options.points = points;
  return options;
}

}  // namespace

TEST_CASE("work queue: in order, guided chunks cover the units once, shrinking to single units", "[run][schedule]") {
  WorkQueueOptions options;
  options.workers = 2;
  WorkQueue queue(5, 1005, options);
  const std::vector<WorkChunk> chunks = drain(queue);
  long long next = 5;
  for (const WorkChunk& chunk : chunks) {
    CHECK(chunk.begin == next);
    CHECK(chunk.end > chunk.begin);
    CHECK(chunk.end - chunk.begin <= kMaxChunkItems);
    next = chunk.end;
  }
  CHECK(next == 1005);
  CHECK(chunks.front().end - chunks.front().begin == kMaxChunkItems);  // much remains: the old 8-item blocks
  CHECK(chunks.back().end - chunks.back().begin == 1);                 // the last chunks: one unit each
  // ⌈remaining / (4 × workers)⌉ from 64 units down.
  WorkQueue small(0, 20, options);
  CHECK(small.take()->end == 3);  // ⌈20 / 8⌉
  CHECK(small.take()->end == 6);  // ⌈17 / 8⌉
  WorkQueue done(7, 7, options);
  CHECK_FALSE(done.take());
}

TEST_CASE("work queue: in order, chunks of items with several units each", "[run][schedule]") {
  WorkQueueOptions options;
  options.parts = 3;
  options.workers = 1;
  WorkQueue queue(0, 3 * 100, options);
  CHECK(queue.take()->end == 3 * kMaxChunkItems);
}

TEST_CASE("work queue: longest first times each class, then runs the longest class first", "[run][schedule]") {
  // One point, 4 items of 2 parts: part 1 is 5 times part 0.
  WorkQueue queue(0, 8, longest_first(2, 1, {0, 0, 0, 0}, 1));
  CHECK(queue.take()->begin == 0);  // nothing timed: unit order
  queue.finished(0, 1.0);
  CHECK(queue.take()->begin == 1);  // part 1 not timed yet: first
  queue.finished(1, 5.0);
  std::vector<long long> order;
  while (const auto chunk = queue.take()) {
    CHECK(chunk->end == chunk->begin + 1);
    order.push_back(chunk->begin);
  }
  CHECK(order == std::vector<long long>{3, 5, 7, 2, 4, 6});
}

TEST_CASE("work queue: longest first stays within the window of items, and resumes past handed-out items", "[run][schedule]") {
  // 1 worker: a window of kWindowPerWorker = 4 items from the first item with a unit not handed
  // out. Items 0..9, point 1 from item 5 on, timed 10 times point 0.
  std::vector<int> points = {0, 0, 0, 0, 0, 1, 1, 1, 1, 1};
  WorkQueue queue(0, 10, longest_first(1, 1, points, 2));
  std::vector<long long> order;
  while (const auto chunk = queue.take()) {
    order.push_back(chunk->begin);
    queue.finished(chunk->begin, points[static_cast<std::size_t>(chunk->begin)] == 1 ? 10.0 : 1.0);
  }
  // 5 enters the window [2, 6) untimed and goes first; 6 enters [3, 7) as the longest class, 7
  // enters [4, 8); 8 and 9 wait until item 4 is handed out.
  CHECK(order == std::vector<long long>{0, 1, 5, 2, 6, 3, 7, 4, 8, 9});
  // --resume: units before the first are written already.
  WorkQueue resumed(6, 10, longest_first(1, 1, points, 2));
  CHECK(resumed.take()->begin == 6);
  CHECK(resumed.take()->begin == 7);
}

TEST_CASE("work queue: longest first by a previous run's unit times", "[run][schedule]") {
  WorkQueueOptions options = longest_first(2, 2, {0, 0, 0}, 1);
  options.unit_predictions = {1, 9, 2, 3, 8, 0.5};
  WorkQueue queue(0, 6, options);
  std::vector<long long> order;
  while (const auto chunk = queue.take()) order.push_back(chunk->begin);
  CHECK(order == std::vector<long long>{1, 4, 3, 2, 0, 5});
}

}  // namespace DABENCH_TEST_FILE
