#include "harness/core/summary.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>

#include <fmt/format.h>

#include "harness/core/atomic_file.hpp"
#include "harness/core/csv.hpp"
#include "harness/core/errors.hpp"
#include "harness/core/params.hpp"

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
  std::vector<std::vector<double>> values;  // per metric
};

std::string number(double value) { return std::isfinite(value) ? fmt::format("{}", value) : std::string(); }

}  // namespace

void write_summary(const std::string& trials_path, const std::string& summary_path,
                   const std::vector<std::string>& metric_columns) {
  std::ifstream in(trials_path);
  if (!in) throw InputError(fmt::format("{}: cannot read", trials_path));
  std::string line;
  std::vector<std::string> header;
  if (!std::getline(in, line) || !split_csv_line(line, header)) {
    throw InputError(fmt::format("{}: missing header", trials_path));
  }
  const auto column = [&](const std::string& name) -> std::size_t {
    const auto it = std::find(header.begin(), header.end(), name);
    if (it == header.end()) throw InputError(fmt::format("{}: no column '{}'", trials_path, name));
    return static_cast<std::size_t>(it - header.begin());
  };
  const std::size_t trial_column = column("trial");
  const std::size_t algorithm_column = column("algorithm");
  const std::size_t status_column = column("status");
  std::vector<std::size_t> metric_index;
  for (const auto& name : metric_columns) metric_index.push_back(column(name));

  std::vector<Group> groups;
  std::map<std::vector<std::string>, std::size_t> group_of_key;
  std::vector<std::string> fields;
  long long line_number = 1;
  while (std::getline(in, line)) {
    ++line_number;
    if (!split_csv_line(line, fields) || fields.size() != header.size()) {
      throw InputError(fmt::format("{}:{}: malformed row", trials_path, line_number));
    }
    std::vector<std::string> key(fields.begin(), fields.begin() + static_cast<long>(trial_column));
    key.push_back(fields[algorithm_column]);
    auto [it, inserted] = group_of_key.try_emplace(key, groups.size());
    if (inserted) {
      groups.push_back(Group{key, 0, 0, 0, 0, std::vector<std::vector<double>>(metric_columns.size())});
    }
    Group& group = groups[it->second];
    ++group.trials;
    const std::string& status = fields[status_column];
    if (status == "ok") ++group.ok;
    else if (status.rfind("skipped", 0) == 0) ++group.skipped;
    else ++group.failed;
    for (std::size_t k = 0; k < metric_index.size(); ++k) {
      const std::string& text = fields[metric_index[k]];
      if (text.empty()) continue;
      double value = 0.0;
      if (!parse_double(text, value)) {
        throw InputError(fmt::format("{}:{}: '{}' is not a number", trials_path, line_number, text));
      }
      group.values[k].push_back(value);
    }
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
  for (Group& group : groups) {
    for (std::size_t c = 0; c < group.key_fields.size(); ++c) {
      if (c > 0) out += ',';
      append_csv_field(out, group.key_fields[c]);
    }
    out += fmt::format(",{},{},{},{}", group.trials, group.ok, group.skipped, group.failed);
    for (auto& values : group.values) {
      const MetricSummary s = summarize(values);
      out += fmt::format(",{},{},{},{},{},{}", s.count, number(s.mean), number(s.standard_error), number(s.median),
                         number(s.p5), number(s.p95));
    }
    out += '\n';
  }
  write_file_atomically(summary_path, out);
}

}  // namespace dabench
