#include "harness/core/summary.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>

#include <fmt/format.h>

#include "harness/core/atomic_file.hpp"
#include "harness/core/csv.hpp"
#include "harness/core/errors.hpp"
#include "harness/core/params.hpp"
#include "harness/core/spill_sort.hpp"

namespace dabench {

double percentile_sorted(const std::vector<double>& sorted, double fraction) {
  if (sorted.empty()) return std::numeric_limits<double>::quiet_NaN();
  const double position = fraction * static_cast<double>(sorted.size() - 1);
  const auto below = static_cast<std::size_t>(std::floor(position));
  const std::size_t above = std::min(below + 1, sorted.size() - 1);
  const double weight = position - static_cast<double>(below);
  return sorted[below] + weight * (sorted[above] - sorted[below]);
}

MetricSummary summarize(std::vector<double>& values) {
  MetricSummary s;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  s.count = static_cast<long long>(values.size());
  if (values.empty()) {
    s.mean = s.standard_error = s.median = s.p5 = s.p95 = nan;
    return s;
  }
  double sum = 0.0;
  for (double v : values) sum += v;
  s.mean = sum / static_cast<double>(values.size());
  if (values.size() > 1) {
    double squares = 0.0;
    for (double v : values) squares += (v - s.mean) * (v - s.mean);
    s.standard_error = std::sqrt(squares / static_cast<double>(values.size() - 1) / static_cast<double>(values.size()));
  } else {
    s.standard_error = nan;
  }
  std::sort(values.begin(), values.end());
  s.median = percentile_sorted(values, 0.5);
  s.p5 = percentile_sorted(values, 0.05);
  s.p95 = percentile_sorted(values, 0.95);
  return s;
}

namespace {

struct Group {
  std::vector<std::string> key_fields;  // point + parameters, then algorithm
  long long trials = 0, ok = 0, skipped = 0, failed = 0;
};

// One metric of one group, accumulated as summarize() computes it: the sum and the squares
// about the mean in file order; the quantiles from the values' sorted order (SpillSort).
struct MetricSlot {
  long long count = 0;
  double sum = 0.0, squares = 0.0;
  double median = 0.0, p5 = 0.0, p95 = 0.0;
};

std::string number(double value) { return std::isfinite(value) ? fmt::format("{}", value) : std::string(); }

// trials.csv row by row: its header's columns, and for each row its fields and line number.
class TrialRows {
 public:
  explicit TrialRows(const std::string& path) : path_(path), in_(path) {
    if (!in_) throw InputError(fmt::format("{}: cannot read", path_));
    if (!std::getline(in_, line_) || !split_csv_line(line_, header_)) throw InputError(fmt::format("{}: missing header", path_));
  }
  std::size_t column(const std::string& name) const {
    const auto it = std::find(header_.begin(), header_.end(), name);
    if (it == header_.end()) throw InputError(fmt::format("{}: no column '{}'", path_, name));
    return static_cast<std::size_t>(it - header_.begin());
  }
  const std::vector<std::string>& header() const { return header_; }
  bool next() {
    if (!std::getline(in_, line_)) return false;
    ++line_number_;
    if (!split_csv_line(line_, fields_) || fields_.size() != header_.size()) {
      throw InputError(fmt::format("{}:{}: malformed row", path_, line_number_));
    }
    return true;
  }
  const std::vector<std::string>& fields() const { return fields_; }
  // The row's value in `column`; false when empty (missing).
  bool value(std::size_t column, double& value) const {
    const std::string& text = fields_[column];
    if (text.empty()) return false;
    if (!parse_double(text, value)) throw InputError(fmt::format("{}:{}: '{}' is not a number", path_, line_number_, text));
    return true;
  }

 private:
  std::string path_;
  std::ifstream in_;
  std::string line_;
  std::vector<std::string> header_, fields_;
  long long line_number_ = 1;
};

}  // namespace

void write_summary(const std::string& trials_path, const std::string& summary_path,
                   const std::vector<std::string>& metric_columns, std::size_t sort_buffer_values) {
  const std::size_t metrics = metric_columns.size();
  std::vector<Group> groups;
  std::vector<MetricSlot> slots;  // group g's metric k at g · metrics + k
  std::map<std::vector<std::string>, std::size_t> group_of_key;
  std::vector<std::string> header;
  std::vector<std::size_t> metric_index;
  std::size_t trial_column = 0;
  std::vector<std::string> key;
  // The row's group: point + parameters, then algorithm.
  const auto group_key = [&](const TrialRows& rows, std::size_t algorithm_column) -> const std::vector<std::string>& {
    const std::vector<std::string>& fields = rows.fields();
    key.assign(fields.begin(), fields.begin() + static_cast<long>(trial_column));
    key.push_back(fields[algorithm_column]);
    return key;
  };
  SpillSort sorted_values(std::filesystem::path(summary_path).parent_path().string(), sort_buffer_values);
  {  // Pass 1: groups, counts, sums; every value to the sort.
    TrialRows rows(trials_path);
    header = rows.header();
    trial_column = rows.column("trial");
    const std::size_t algorithm_column = rows.column("algorithm");
    const std::size_t status_column = rows.column("status");
    for (const auto& name : metric_columns) metric_index.push_back(rows.column(name));
    while (rows.next()) {
      auto [it, inserted] = group_of_key.try_emplace(group_key(rows, algorithm_column), groups.size());
      if (inserted) {
        groups.push_back(Group{key, 0, 0, 0, 0});
        slots.resize(slots.size() + metrics);
      }
      Group& group = groups[it->second];
      ++group.trials;
      const std::string& status = rows.fields()[status_column];
      if (status == "ok") ++group.ok;
      else if (status.rfind("skipped", 0) == 0) ++group.skipped;
      else ++group.failed;
      for (std::size_t k = 0; k < metrics; ++k) {
        double value = 0.0;
        if (!rows.value(metric_index[k], value)) continue;
        const std::size_t slot = it->second * metrics + k;
        ++slots[slot].count;
        slots[slot].sum += value;
        sorted_values.add(static_cast<std::uint32_t>(slot), value);
      }
    }
  }
  {  // Pass 2: squares about each mean, in file order.
    TrialRows rows(trials_path);
    const std::size_t algorithm_column = rows.column("algorithm");
    while (rows.next()) {
      const std::size_t group = group_of_key.at(group_key(rows, algorithm_column));
      for (std::size_t k = 0; k < metrics; ++k) {
        double value = 0.0;
        if (!rows.value(metric_index[k], value)) continue;
        MetricSlot& slot = slots[group * metrics + k];
        const double mean = slot.sum / static_cast<double>(slot.count);
        slot.squares += (value - mean) * (value - mean);
      }
    }
  }
  {  // The quantiles from each slot's values in sorted order (percentile_sorted's interpolation).
    std::uint32_t slot = 0;
    long long rank = -1;
    std::vector<double> needed;  // the values at the ranks below and above each quantile's position
    const auto positions = [](long long count) {
      std::vector<long long> ranks;
      for (const double fraction : {0.5, 0.05, 0.95}) {
        const double position = fraction * static_cast<double>(count - 1);
        const auto below = static_cast<long long>(std::floor(position));
        ranks.push_back(below);
        ranks.push_back(std::min(below + 1, count - 1));
      }
      return ranks;
    };
    std::vector<long long> ranks;
    const auto finish = [&] {
      MetricSlot& s = slots[slot];
      const double values[3][2] = {{needed[0], needed[1]}, {needed[2], needed[3]}, {needed[4], needed[5]}};
      double* targets[3] = {&s.median, &s.p5, &s.p95};
      const double fractions[3] = {0.5, 0.05, 0.95};
      for (int q = 0; q < 3; ++q) {
        const double position = fractions[q] * static_cast<double>(s.count - 1);
        const double weight = position - std::floor(position);
        *targets[q] = values[q][0] + weight * (values[q][1] - values[q][0]);
      }
    };
    sorted_values.for_each_sorted([&](const SpillSort::Record& record) {
      if (rank < 0 || record.slot != slot) {
        if (rank >= 0) finish();
        slot = record.slot;
        rank = 0;
        ranks = positions(slots[slot].count);
        needed.assign(ranks.size(), 0.0);
      }
      for (std::size_t r = 0; r < ranks.size(); ++r) {
        if (ranks[r] == rank) needed[r] = record.value;
      }
      ++rank;
    });
    if (rank >= 0) finish();
  }

  std::string out;
  for (std::size_t c = 0; c < trial_column; ++c) {
    append_csv_field(out, header[c]);
    out += ',';
  }
  out += "algorithm,trials,ok,skipped,failed";
  for (const auto& name : metric_columns) {
    out += fmt::format(",{0}_count,{0}_mean,{0}_se,{0}_median,{0}_p5,{0}_p95", name);
  }
  out += '\n';
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const Group& group = groups[g];
    for (std::size_t c = 0; c < group.key_fields.size(); ++c) {
      if (c > 0) out += ',';
      append_csv_field(out, group.key_fields[c]);
    }
    out += fmt::format(",{},{},{},{}", group.trials, group.ok, group.skipped, group.failed);
    for (std::size_t k = 0; k < metrics; ++k) {
      const MetricSlot& s = slots[g * metrics + k];
      const auto n = static_cast<double>(s.count);
      const double mean = s.count > 0 ? s.sum / n : nan;
      const double se = s.count > 1 ? std::sqrt(s.squares / (n - 1.0) / n) : nan;
      out += s.count == 0 ? fmt::format(",0,,,,,")
                          : fmt::format(",{},{},{},{},{},{}", s.count, number(mean), number(se), number(s.median),
                                        number(s.p5), number(s.p95));
    }
    out += '\n';
  }
  write_file_atomically(summary_path, out);
}

}  // namespace dabench
