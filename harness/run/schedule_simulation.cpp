#include "harness/run/schedule_simulation.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <numeric>
#include <queue>
#include <tuple>
#include <string_view>
#include <utility>

#include <fmt/format.h>

#include "harness/core/csv.hpp"
#include "harness/core/errors.hpp"
#include "harness/core/input_file.hpp"
#include "harness/run/run_meta.hpp"

namespace dabench {
namespace {

constexpr std::uintmax_t kMaxCostFileBytes = std::uintmax_t{4} << 30;

// The columns of a row's (point, trial) and its algorithm time (the kind's time column; in
// summary.csv, its mean, and the trial count standing for the trial).
struct TimeColumns {
  int point = -1, trial = -1;
  int time = -1, count = -1;  // count: the kind's count column, or -1
  double to_seconds = 1.0;
};

TimeColumns time_columns(const std::vector<std::string>& header, const ProblemKind& kind, bool summary,
                         const std::string& path) {
  const AlgorithmTimeColumn time = kind.time_column();
  const std::string suffix = summary ? "_mean" : "";
  const std::string time_name = std::string(time.column) + suffix;
  const std::string count_name = time.count_column.empty() ? "" : std::string(time.count_column) + suffix;
  TimeColumns columns;
  columns.to_seconds = time.to_seconds;
  for (std::size_t c = 0; c < header.size(); ++c) {
    const std::string& name = header[c];
    const int index = static_cast<int>(c);
    if (name == "point" && columns.point < 0) columns.point = index;
    if (name == (summary ? "trials" : "trial")) columns.trial = index;
    if (name == time_name) columns.time = index;
    if (!count_name.empty() && name == count_name) columns.count = index;
  }
  if (columns.point < 0 || columns.trial < 0 || columns.time < 0 || (!count_name.empty() && columns.count < 0)) {
    throw InputError(fmt::format("{}: no point, {} and {}{} columns (a {} run's)", path, summary ? "trials" : "trial",
                                 time_name, count_name.empty() ? "" : " and " + count_name, kind.name()));
  }
  return columns;
}

double field_number(const std::vector<std::string>& fields, int column) {
  if (column < 0 || column >= static_cast<int>(fields.size()) || fields[column].empty()) return 0.0;
  char* end = nullptr;
  const double value = std::strtod(fields[column].c_str(), &end);
  return end != nullptr && *end == '\0' && std::isfinite(value) && value > 0.0 ? value : 0.0;
}

double row_seconds(const std::vector<std::string>& fields, const TimeColumns& columns) {
  const double seconds = columns.to_seconds * field_number(fields, columns.time);
  return columns.count >= 0 ? seconds * field_number(fields, columns.count) : seconds;
}

// Event-driven list scheduling: the worker free first (then the lowest) takes what `next`
// gives it, until it gives nothing; `done` is told when a taken chunk ends, in time order.
template <class Next, class Done>
SchedulePrediction simulate(long long workers, double total_seconds, Next&& next, Done&& done) {
  using Event = std::pair<double, long long>;  // (time the worker frees, worker)
  std::priority_queue<Event, std::vector<Event>, std::greater<>> free_at;
  std::vector<std::optional<WorkChunk>> running(static_cast<std::size_t>(workers));
  for (long long w = 0; w < workers; ++w) free_at.push({0.0, w});
  double wall = 0.0;
  while (!free_at.empty()) {
    const auto [time, worker] = free_at.top();
    free_at.pop();
    auto& chunk = running[static_cast<std::size_t>(worker)];
    if (chunk) done(*chunk);
    double seconds = 0.0;
    chunk = next(seconds);
    wall = std::max(wall, time);
    if (chunk) free_at.push({time + seconds, worker});
  }
  return {wall, wall > 0.0 ? total_seconds / (wall * static_cast<double>(workers)) : 1.0};
}

}  // namespace

RunCosts read_run_costs(const std::string& folder, std::string_view command, long long trials) {
  namespace fs = std::filesystem;
  std::string path;
  for (const char* name : {"trials.csv", "runs.csv", "summary.csv"}) {
    path = (fs::path(folder) / name).string();
    if (fs::is_regular_file(path)) break;
    path.clear();
  }
  if (path.empty()) throw InputError(fmt::format("{}: no trials.csv, runs.csv or summary.csv (a run folder?)", folder));
  const ProblemKind& kind = recorded_kind(folder, command);
  const bool summary = fs::path(path).filename() == "summary.csv";
  const std::string text = read_input_file(path, "run file", kMaxCostFileBytes);
  RunCosts costs;
  costs.source = path;
  costs.kind = &kind;
  costs.from_means = summary;
  std::vector<std::string> fields;
  TimeColumns columns;
  // Rows in file order: (point, trial or trial count, seconds); an item is a run of equal keys.
  struct Row {
    int point;
    long long trial;
    double seconds;
  };
  std::vector<Row> rows;
  long long line = 0;
  for (std::size_t at = 0; at < text.size();) {
    std::size_t end = text.find('\n', at);
    if (end == std::string::npos) end = text.size();
    ++line;
    if (!split_csv_line(std::string_view(text).substr(at, end - at), fields)) {
      throw InputError(fmt::format("{}:{}: a quote is left open", path, line));
    }
    at = end + 1;
    if (line == 1) {
      columns = time_columns(fields, kind, summary, path);
      continue;
    }
    if (static_cast<int>(fields.size()) <= std::max(columns.point, columns.trial)) {
      throw InputError(fmt::format("{}:{}: {} fields, fewer than the header's columns", path, line, fields.size()));
    }
    rows.push_back({static_cast<int>(field_number(fields, columns.point)),
                    static_cast<long long>(field_number(fields, columns.trial)), row_seconds(fields, columns)});
  }
  if (costs.from_means) {  // one row per (point, algorithm): expand to the point's trials
    std::vector<Row> expanded;
    for (std::size_t first = 0; first < rows.size();) {
      std::size_t last = first;
      while (last < rows.size() && rows[last].point == rows[first].point) ++last;
      const long long count = trials >= 0 ? std::min(trials, rows[first].trial) : rows[first].trial;
      for (long long trial = 0; trial < count; ++trial) {
        for (std::size_t r = first; r < last; ++r) expanded.push_back({rows[r].point, trial, rows[r].seconds});
      }
      first = last;
    }
    rows = std::move(expanded);
  }
  // Items in run order (point, then trial; a report's file may be sorted otherwise), each
  // item's rows in file order (the algorithms' order).
  std::stable_sort(rows.begin(), rows.end(),
                   [](const Row& a, const Row& b) { return std::tie(a.point, a.trial) < std::tie(b.point, b.trial); });
  std::vector<double> item_rows;  // every kept item's rows' times, flattened
  long long rows_per_item = -1;
  for (std::size_t first = 0; first < rows.size();) {
    std::size_t last = first;
    while (last < rows.size() && rows[last].point == rows[first].point && rows[last].trial == rows[first].trial) ++last;
    const auto count = static_cast<long long>(last - first);
    if (rows_per_item < 0) rows_per_item = count;
    if (count != rows_per_item) {
      throw InputError(fmt::format("{}: item {},{} has {} rows, the first had {}", path, rows[first].point,
                                   rows[first].trial, count, rows_per_item));
    }
    if (trials < 0 || rows[first].trial < trials) {
      costs.item_points.push_back(rows[first].point);
      costs.points = std::max(costs.points, rows[first].point + 1);
      for (std::size_t r = first; r < last; ++r) item_rows.push_back(rows[r].seconds);
    }
    first = last;
  }
  if (costs.item_points.empty()) throw InputError(fmt::format("{}: no rows", path));
  costs.parts = costs.shared_items() ? 1 : static_cast<int>(rows_per_item);
  if (costs.shared_items()) {  // one unit per item: its rows together
    for (std::size_t item = 0; item < costs.item_points.size(); ++item) {
      const auto first = item_rows.begin() + static_cast<std::ptrdiff_t>(item * static_cast<std::size_t>(rows_per_item));
      costs.unit_seconds.push_back(std::accumulate(first, first + rows_per_item, 0.0));
    }
  } else {
    costs.unit_seconds = std::move(item_rows);
  }
  return costs;
}

SchedulePrediction simulate_work_queue(const RunCosts& costs, long long workers, bool known_costs) {
  WorkQueueOptions options;
  if (known_costs && !costs.shared_items()) options.unit_predictions = costs.unit_seconds;
  options.order = costs.shared_items() ? WorkOrder::in_order : WorkOrder::longest_first;
  options.parts = costs.parts;
  options.workers = workers;
  options.points = costs.points;
  options.item_points = costs.item_points;
  WorkQueue queue(0, static_cast<long long>(costs.unit_seconds.size()), std::move(options));
  const double total = std::accumulate(costs.unit_seconds.begin(), costs.unit_seconds.end(), 0.0);
  return simulate(
      workers, total,
      [&](double& seconds) {
        const auto chunk = queue.take();
        if (chunk) seconds = std::accumulate(costs.unit_seconds.begin() + chunk->begin, costs.unit_seconds.begin() + chunk->end, 0.0);
        return chunk;
      },
      [&](const WorkChunk& chunk) {
        for (long long unit = chunk.begin; unit < chunk.end; ++unit) queue.finished(unit, costs.unit_seconds[unit]);
      });
}

SchedulePrediction simulate_item_blocks(const RunCosts& costs, long long workers) {
  constexpr long long kBlockItems = 8;
  const long long units = static_cast<long long>(costs.unit_seconds.size());
  const long long block_units = kBlockItems * costs.parts;
  long long next = 0;
  const double total = std::accumulate(costs.unit_seconds.begin(), costs.unit_seconds.end(), 0.0);
  return simulate(
      workers, total,
      [&](double& seconds) -> std::optional<WorkChunk> {
        if (next >= units) return std::nullopt;
        const WorkChunk chunk{next, std::min(units, next + block_units)};
        next = chunk.end;
        seconds = std::accumulate(costs.unit_seconds.begin() + chunk.begin, costs.unit_seconds.begin() + chunk.end, 0.0);
        return chunk;
      },
      [](const WorkChunk&) {});
}

double schedule_lower_bound(const RunCosts& costs, long long workers) {
  const double total = std::accumulate(costs.unit_seconds.begin(), costs.unit_seconds.end(), 0.0);
  const double longest = *std::max_element(costs.unit_seconds.begin(), costs.unit_seconds.end());
  return std::max(total / static_cast<double>(workers), longest);
}

}  // namespace dabench
