#include "harness/run/work_queue.hpp"

#include <algorithm>
#include <limits>

namespace dabench {

WorkQueue::WorkQueue(long long first_unit, long long total_units, WorkQueueOptions options)
    : options_(std::move(options)),
      total_units_(total_units),
      next_(first_unit),
      first_item_(first_unit / options_.parts),
      first_unit_(first_unit) {
  if (options_.order == WorkOrder::longest_first) {
    taken_.assign(static_cast<std::size_t>(std::max(0LL, total_units - first_unit)), 0);
    const auto classes = static_cast<std::size_t>(options_.points) * static_cast<std::size_t>(options_.parts);
    class_seconds_.assign(classes, 0.0);
    class_count_.assign(classes, 0);
  }
}

std::optional<WorkChunk> WorkQueue::take() {
  const std::lock_guard lock(mutex_);
  return options_.order == WorkOrder::in_order ? take_in_order() : take_longest();
}

std::optional<WorkChunk> WorkQueue::take_in_order() {
  const long long remaining = total_units_ - next_;
  if (remaining <= 0) return std::nullopt;
  const long long guided = (remaining + kChunksPerWorker * options_.workers - 1) / (kChunksPerWorker * options_.workers);
  const long long size = std::clamp(guided, 1LL, kMaxChunkItems * options_.parts);
  const WorkChunk chunk{next_, next_ + size};
  next_ = chunk.end;
  return chunk;
}

int WorkQueue::unit_class(long long unit) const {
  const long long item = unit / options_.parts;
  return options_.item_points[static_cast<std::size_t>(item)] * options_.parts + static_cast<int>(unit % options_.parts);
}

std::optional<WorkChunk> WorkQueue::take_longest() {
  const long long parts = options_.parts;
  const long long total_items = (total_units_ + parts - 1) / parts;
  const auto is_taken = [&](long long unit) { return unit < first_unit_ || taken_[static_cast<std::size_t>(unit - first_unit_)] != 0; };
  while (first_item_ < total_items) {  // skip items whose units are all handed out
    bool open = false;
    for (long long unit = first_item_ * parts; unit < std::min(total_units_, (first_item_ + 1) * parts) && !open; ++unit) {
      open = !is_taken(unit);
    }
    if (open) break;
    ++first_item_;
  }
  if (first_item_ >= total_items) return std::nullopt;
  const long long window_end = std::min(total_units_, (first_item_ + kWindowPerWorker * options_.workers) * parts);
  long long best = -1;
  double best_prediction = -1.0;
  for (long long unit = first_item_ * parts; unit < window_end; ++unit) {
    if (is_taken(unit)) continue;
    double prediction = 0.0;
    if (!options_.unit_predictions.empty()) {
      prediction = options_.unit_predictions[static_cast<std::size_t>(unit)];
    } else {
      const auto c = static_cast<std::size_t>(unit_class(unit));
      prediction = class_count_[c] == 0 ? std::numeric_limits<double>::infinity()
                                        : class_seconds_[c] / static_cast<double>(class_count_[c]);
    }
    if (prediction > best_prediction) {
      best = unit;
      best_prediction = prediction;
    }
  }
  taken_[static_cast<std::size_t>(best - first_unit_)] = 1;
  return WorkChunk{best, best + 1};
}

void WorkQueue::finished(long long unit, double seconds) {
  if (options_.order != WorkOrder::longest_first) return;
  const std::lock_guard lock(mutex_);
  const auto c = static_cast<std::size_t>(unit_class(unit));
  class_seconds_[c] += seconds;
  ++class_count_[c];
}

}  // namespace dabench
