#include "harness/run/paired_comparison.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <utility>

#include <boost/math/distributions/students_t.hpp>
#include <fmt/format.h>

#include "harness/core/csv.hpp"
#include "harness/core/errors.hpp"
#include "harness/core/input_file.hpp"
#include "harness/core/json.hpp"
#include "harness/run/run_meta.hpp"

namespace dabench {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr std::size_t kExactLimit = 50;  // scipy's: the exact distribution up to 50 differences
constexpr std::uintmax_t kMaxTrialsBytes = std::uintmax_t{4} << 30;

// Average ranks (1-based) of `values`; `tied` is set when two are equal; tie_term = Σ t(t² − 1).
std::vector<double> average_ranks(const std::vector<double>& values, bool& tied, double& tie_term) {
  std::vector<std::size_t> order(values.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return values[a] < values[b]; });
  std::vector<double> ranks(values.size());
  tied = false;
  tie_term = 0.0;
  for (std::size_t first = 0; first < order.size();) {
    std::size_t last = first;
    while (last < order.size() && values[order[last]] == values[order[first]]) ++last;
    const double rank = 0.5 * static_cast<double>(first + 1 + last);  // mean of first+1 .. last
    for (std::size_t k = first; k < last; ++k) ranks[order[k]] = rank;
    const auto t = static_cast<double>(last - first);
    if (t > 1) {
      tied = true;
      tie_term += t * (t * t - 1.0);
    }
    first = last;
  }
  return ranks;
}

// P(R+ = s) for s = 0 .. n(n+1)/2 under the null: subsets of {1..n} by their sum, over 2^n.
std::vector<double> signed_rank_pmf(std::size_t n) {
  std::vector<double> counts(n * (n + 1) / 2 + 1, 0.0);
  counts[0] = 1.0;
  for (std::size_t k = 1; k <= n; ++k) {
    for (std::size_t s = counts.size() - 1; s >= k; --s) counts[s] += counts[s - k];
  }
  const double total = std::ldexp(1.0, static_cast<int>(n));
  for (double& c : counts) c /= total;
  return counts;
}

}  // namespace

double wilcoxon_signed_rank_p(const std::vector<double>& differences) {
  std::vector<double> d;
  for (const double x : differences) {
    if (x != 0.0) d.push_back(x);
  }
  if (d.empty()) return kNaN;
  std::vector<double> magnitude(d.size());
  for (std::size_t k = 0; k < d.size(); ++k) magnitude[k] = std::fabs(d[k]);
  bool tied = false;
  double tie_term = 0.0;
  const std::vector<double> ranks = average_ranks(magnitude, tied, tie_term);
  double r_plus = 0.0, r_minus = 0.0;
  for (std::size_t k = 0; k < d.size(); ++k) (d[k] > 0 ? r_plus : r_minus) += ranks[k];
  const auto n = static_cast<double>(d.size());
  const bool zeros = d.size() != differences.size();
  if (d.size() <= kExactLimit && !tied && !zeros) {
    const std::vector<double> pmf = signed_rank_pmf(d.size());
    const auto r = static_cast<std::size_t>(r_plus);
    if (r == (pmf.size() - 1) / 2) return 1.0;  // the centre of the distribution
    const double below = std::accumulate(pmf.begin(), pmf.begin() + static_cast<std::ptrdiff_t>(r) + 1, 0.0);
    const double above = std::accumulate(pmf.begin() + static_cast<std::ptrdiff_t>(r), pmf.end(), 0.0);
    return std::clamp(2.0 * std::min(below, above), 0.0, 1.0);
  }
  const double mean = n * (n + 1.0) * 0.25;
  const double sd = std::sqrt((n * (n + 1.0) * (2.0 * n + 1.0) - 0.5 * tie_term) / 24.0);
  const double z = (std::min(r_plus, r_minus) - mean) / sd;
  return std::erfc(std::fabs(z) / std::sqrt(2.0));
}

PairedStatistics paired_statistics(const std::vector<double>& differences) {
  PairedStatistics stats;
  stats.n = static_cast<long long>(differences.size());
  if (differences.empty()) {
    stats.mean_diff = stats.ci_low = stats.ci_high = stats.wilcoxon_p = kNaN;
    return stats;
  }
  const auto n = static_cast<double>(differences.size());
  stats.mean_diff = std::accumulate(differences.begin(), differences.end(), 0.0) / n;
  double squares = 0.0;
  long long below = 0, equal = 0;
  for (const double d : differences) {
    squares += (d - stats.mean_diff) * (d - stats.mean_diff);
    below += d < 0.0;
    equal += d == 0.0;
  }
  if (differences.size() > 1) {
    const boost::math::students_t t(n - 1.0);
    const double half = boost::math::quantile(boost::math::complement(t, 0.025)) * std::sqrt(squares / (n - 1.0) / n);
    stats.ci_low = stats.mean_diff - half;
    stats.ci_high = stats.mean_diff + half;
  } else {
    stats.ci_low = stats.ci_high = kNaN;
  }
  const double p = wilcoxon_signed_rank_p(differences);
  stats.wilcoxon_p = std::isnan(p) ? 1.0 : p;  // every difference 0: no evidence either way
  stats.a_better = static_cast<double>(below) / n;
  stats.ties = static_cast<double>(equal) / n;
  return stats;
}

std::vector<double> holm_adjust(const std::vector<double>& p_values) {
  std::vector<std::size_t> order;
  for (std::size_t k = 0; k < p_values.size(); ++k) {
    if (!std::isnan(p_values[k])) order.push_back(k);
  }
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return p_values[a] < p_values[b]; });
  std::vector<double> adjusted(p_values.size(), kNaN);
  double running = 0.0;
  const auto m = static_cast<double>(order.size());
  for (std::size_t rank = 0; rank < order.size(); ++rank) {
    running = std::max(running, std::min(1.0, (m - static_cast<double>(rank)) * p_values[order[rank]]));
    adjusted[order[rank]] = running;
  }
  return adjusted;
}

namespace {

// One run's trials.csv: per (point, trial) and algorithm, the requested metrics.
struct RunTable {
  std::vector<std::string> header;
  std::string point_header;                          // "point,param,..." (the columns before trial)
  std::map<long long, std::string> point_fields;     // per point, its leading fields as written
  std::set<std::string> algorithms;
  // (algorithm, metric) → (point, trial) → value (NaN when empty).
  std::map<std::pair<std::string, std::string>, std::map<std::pair<long long, long long>, double>> values;
};

int column_of(const std::vector<std::string>& header, const std::string& name) {
  const auto it = std::find(header.begin(), header.end(), name);
  return it == header.end() ? -1 : static_cast<int>(it - header.begin());
}

RunTable read_run(const std::string& folder, const std::vector<std::string>& algorithms, std::vector<std::string>& metrics) {
  const std::string path = (std::filesystem::path(folder) / "trials.csv").string();
  if (!std::filesystem::is_regular_file(path)) throw InputError(fmt::format("compare: {}: no trials.csv (a run folder?)", folder));
  const std::string text = read_input_file(path, "trials file", kMaxTrialsBytes);
  RunTable table;
  std::vector<std::string> fields;
  int trial = -1, algorithm = -1;
  std::vector<int> metric_columns;
  std::size_t line = 0;
  for (std::size_t at = 0; at < text.size();) {
    std::size_t end = text.find('\n', at);
    if (end == std::string::npos) end = text.size();
    ++line;
    const std::string_view row = std::string_view(text).substr(at, end - at);
    at = end + 1;
    if (!split_csv_line(row, fields)) throw InputError(fmt::format("compare: {}:{}: a quote is left open", path, line));
    if (line == 1) {
      table.header = fields;
      trial = column_of(fields, "trial");
      algorithm = column_of(fields, "algorithm");
      if (column_of(fields, "point") != 0 || trial < 1 || algorithm < 0) {
        throw InputError(fmt::format("compare: {}: not a dabench trials.csv (point, trial, algorithm columns)", path));
      }
      for (int c = 0; c < trial; ++c) table.point_header += (c ? "," : "") + fields[static_cast<std::size_t>(c)];
      if (metrics.empty()) {
        for (const char* name : {"max_error", "mean_hpd", "gospa", "mospa_km"}) {
          if (column_of(fields, name) >= 0) metrics.push_back(name);
        }
        for (const char* name : {"time_us", "step_time_us", "tet_s"}) {
          if (column_of(fields, name) >= 0) metrics.push_back(name);
        }
      }
      for (const std::string& metric : metrics) {
        const int c = column_of(fields, metric);
        if (c < 0 || c <= algorithm) {
          throw InputError(fmt::format("compare: {}: no metric column '{}' (columns after 'algorithm')", path, metric));
        }
        metric_columns.push_back(c);
      }
      continue;
    }
    if (fields.size() != table.header.size()) {
      throw InputError(fmt::format("compare: {}:{}: {} fields, the header has {}", path, line, fields.size(), table.header.size()));
    }
    const std::string& name = fields[static_cast<std::size_t>(algorithm)];
    table.algorithms.insert(name);
    if (std::find(algorithms.begin(), algorithms.end(), name) == algorithms.end()) continue;
    const auto index = [&](const std::string& field) {
      long long value = -1;
      const auto [stop, error] = std::from_chars(field.data(), field.data() + field.size(), value);
      if (error != std::errc() || stop != field.data() + field.size() || value < 0) {
        throw InputError(fmt::format("compare: {}:{}: '{}' is not a point or trial index", path, line, field));
      }
      return value;
    };
    const long long point = index(fields[0]), trial_index = index(fields[static_cast<std::size_t>(trial)]);
    if (!table.point_fields.count(point)) {
      std::string leading;
      for (int c = 0; c < trial; ++c) {
        if (c > 0) leading += ',';
        append_csv_field(leading, fields[static_cast<std::size_t>(c)]);
      }
      table.point_fields[point] = leading;
    }
    for (std::size_t k = 0; k < metrics.size(); ++k) {
      const std::string& field = fields[static_cast<std::size_t>(metric_columns[k])];
      char* stop = nullptr;
      const double value = field.empty() ? kNaN : std::strtod(field.c_str(), &stop);
      table.values[{name, metrics[k]}][{point, trial_index}] = value;
    }
  }
  for (const std::string& name : algorithms) {
    if (!table.algorithms.count(name)) {
      std::string known;
      for (const std::string& a : table.algorithms) known += (known.empty() ? "" : ", ") + a;
      throw InputError(fmt::format("compare: {}: no rows of algorithm '{}' (it has: {})", path, name, known));
    }
  }
  return table;
}

std::string meta_field(const std::string& folder, const char* key) {
  const std::string path = (std::filesystem::path(folder) / "meta.json").string();
  const std::string meta = read_input_file(path, "run meta.json", kMaxMetaBytes);
  const auto value = json_value(meta, key);
  if (!value) throw InputError(fmt::format("compare: {}: no \"{}\"", path, key));
  return *value;
}

}  // namespace

Comparison compare_runs(const CompareOptions& options) {
  const bool two_runs = !options.run_b.empty();
  if (two_runs ? options.algorithms.size() != 1 : options.algorithms.size() != 2) {
    throw InputError(two_runs ? "compare: two runs compare one algorithm: --algorithms A"
                              : "compare: one run compares two algorithms: --algorithms A,B");
  }
  require_complete_run(options.run_a, "compare");
  if (two_runs) require_complete_run(options.run_b, "compare");
  std::vector<std::string> metrics = options.metrics;
  Comparison comparison;
  RunTable a = read_run(options.run_a, options.algorithms, metrics);
  RunTable b;
  std::string name_a = options.algorithms[0], name_b = two_runs ? options.algorithms[0] : options.algorithms[1];
  if (two_runs) {
    for (const char* key : {"fingerprint", "seed"}) {
      if (meta_field(options.run_a, key) != meta_field(options.run_b, key)) {
        throw InputError(fmt::format("compare: {} and {} are not runs of the same plan (their {} differ): their trials "
                                     "are not the same problems", options.run_a, options.run_b, key));
      }
    }
    b = read_run(options.run_b, options.algorithms, metrics);
    comparison.label_a = fmt::format("{} ({})", name_a, options.run_a);
    comparison.label_b = fmt::format("{} ({})", name_b, options.run_b);
  } else {
    comparison.label_a = name_a;
    comparison.label_b = name_b;
  }
  const RunTable& other = two_runs ? b : a;
  comparison.header = a.point_header;
  for (const std::string& metric : metrics) {
    const auto& values_a = a.values[{name_a, metric}];
    const auto& values_b = other.values.at({name_b, metric});
    const std::size_t first = comparison.rows.size();
    for (const auto& [point, fields] : a.point_fields) {
      std::vector<double> differences;
      for (auto it = values_a.lower_bound({point, 0}); it != values_a.end() && it->first.first == point; ++it) {
        const auto match = values_b.find(it->first);
        if (match == values_b.end() || !std::isfinite(it->second) || !std::isfinite(match->second)) continue;
        differences.push_back(it->second - match->second);
      }
      comparison.rows.push_back({fields, metric, paired_statistics(differences), kNaN});
    }
    std::vector<double> p;
    for (std::size_t r = first; r < comparison.rows.size(); ++r) p.push_back(comparison.rows[r].stats.n > 0 ? comparison.rows[r].stats.wilcoxon_p : kNaN);
    const std::vector<double> holm = holm_adjust(p);
    for (std::size_t r = first; r < comparison.rows.size(); ++r) comparison.rows[r].holm_p = holm[r - first];
  }
  return comparison;
}

std::string comparison_csv(const Comparison& comparison) {
  std::string out = comparison.header + ",metric,a,b,n,mean_diff,ci_low,ci_high,wilcoxon_p,holm_p,a_better,ties\n";
  const auto number = [](double v) { return std::isfinite(v) ? fmt::format("{}", v) : std::string(); };
  for (const ComparisonRow& row : comparison.rows) {
    std::string line = row.point_fields + ",";
    append_csv_field(line, row.metric);
    line += ',';
    append_csv_field(line, comparison.label_a);
    line += ',';
    append_csv_field(line, comparison.label_b);
    const PairedStatistics& s = row.stats;
    out += line + fmt::format(",{},{},{},{},{},{},{},{}\n", s.n, number(s.mean_diff), number(s.ci_low), number(s.ci_high),
                              number(s.wilcoxon_p), number(row.holm_p), number(s.a_better), number(s.ties));
  }
  return out;
}

std::string comparison_table(const Comparison& comparison) {
  // Each point by its index and the parameters that vary over the points ("3 spacing=0.75").
  std::vector<std::string> names, fields;
  (void)split_csv_line(comparison.header, names);
  std::vector<std::vector<std::string>> points;
  for (const ComparisonRow& row : comparison.rows) {
    (void)split_csv_line(row.point_fields, fields);
    points.push_back(fields);
  }
  std::vector<std::size_t> varying;
  for (std::size_t c = 1; c < names.size(); ++c) {
    for (const auto& point : points) {
      if (c < point.size() && point[c] != points.front()[c]) {
        varying.push_back(c);
        break;
      }
    }
  }
  std::string out = fmt::format("A = {}, B = {}; d = A - B per trial\n{:<24} {:>12} {:>6} {:>12} {:>25} {:>10} {:>10} {:>8}\n",
                                comparison.label_a, comparison.label_b, "point", "metric", "n", "mean d",
                                "95% interval", "p", "Holm p", "A lower");
  for (std::size_t r = 0; r < comparison.rows.size(); ++r) {
    const ComparisonRow& row = comparison.rows[r];
    std::string point = points[r].empty() ? std::string() : points[r][0];
    for (const std::size_t c : varying) point += fmt::format(" {}={}", names[c], c < points[r].size() ? points[r][c] : "");
    const PairedStatistics& s = row.stats;
    out += fmt::format("{:<24} {:>12} {:>6} {:>12.4g} {:>25} {:>10.3g} {:>10.3g} {:>7.1f}%\n", point, row.metric, s.n,
                       s.mean_diff, fmt::format("[{:.4g}, {:.4g}]", s.ci_low, s.ci_high), s.wilcoxon_p, row.holm_p,
                       100.0 * s.a_better);
  }
  return out;
}

}  // namespace dabench
