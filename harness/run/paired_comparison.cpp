#include "harness/run/paired_comparison.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <set>
#include <utility>

#include <boost/math/distributions/students_t.hpp>
#include <fmt/format.h>

#include "harness/core/csv.hpp"
#include "harness/core/errors.hpp"
#include "harness/core/special_values.hpp"
#include "harness/core/input_file.hpp"
#include "harness/core/json.hpp"
#include "harness/run/problem_kind.hpp"
#include "harness/run/run_meta.hpp"

namespace dabench {
namespace {

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
int column_of(const std::vector<std::string>& header, const std::string& name) {
  const auto it = std::find(header.begin(), header.end(), name);
  return it == header.end() ? -1 : static_cast<int>(it - header.begin());
}

// One sweep point's rows of the compared algorithms: per (algorithm, metric) index, the
// (trial, value) pairs in file order (value NaN when empty).
struct PointRows {
  long long point = -1;
  std::string fields;  // its leading fields (point, parameters) as written
  std::vector<std::vector<std::pair<long long, double>>> values;
};

// `values` by trial (a trial given twice keeps its last value, as a map would): dabench writes
// them in trial order, so this is usually a check.
void by_trial(std::vector<std::pair<long long, double>>& values) {
  const auto trial_less = [](const auto& x, const auto& y) { return x.first < y.first; };
  if (std::is_sorted(values.begin(), values.end(), [](const auto& x, const auto& y) { return x.first <= y.first; })) return;
  std::stable_sort(values.begin(), values.end(), trial_less);
  std::vector<std::pair<long long, double>> last;
  for (std::size_t k = 0; k < values.size(); ++k) {
    if (k + 1 < values.size() && values[k + 1].first == values[k].first) continue;
    last.push_back(values[k]);
  }
  values = std::move(last);
}

// FOLDER/trials.csv, which must exist.
std::string trials_file(const std::string& folder) {
  std::string path = (std::filesystem::path(folder) / "trials.csv").string();
  if (!std::filesystem::is_regular_file(path)) throw InputError(fmt::format("compare: {}: no trials.csv (a run folder?)", folder));
  return path;
}

// A run's trials.csv read point by point (its rows are in point order, as dabench writes them),
// so that memory holds one point's values of the compared algorithms, not the run's.
class PointStream {
 public:
  PointStream(const std::string& folder, std::vector<std::string> algorithms, const std::vector<std::string>& metrics)
      : path_(trials_file(folder)), algorithms_(std::move(algorithms)) {
    check_input_file(path_, "trials file", kMaxTrialsBytes);
    in_.open(path_, std::ios::binary);
    std::string line;
    if (!std::getline(in_, line) || !split_csv_line(line, header_)) {
      throw InputError(fmt::format("compare: {}: not a dabench trials.csv (no header)", path_));
    }
    trial_ = column_of(header_, "trial");
    algorithm_ = column_of(header_, "algorithm");
    if (column_of(header_, "point") != 0 || trial_ < 1 || algorithm_ < 0) {
      throw InputError(fmt::format("compare: {}: not a dabench trials.csv (point, trial, algorithm columns)", path_));
    }
    for (int c = 0; c < trial_; ++c) point_header_ += (c ? "," : "") + header_[static_cast<std::size_t>(c)];
    for (const std::string& metric : metrics) {
      const int c = column_of(header_, metric);
      if (c < 0 || c <= algorithm_) {
        throw InputError(fmt::format("compare: {}: no metric column '{}' (columns after 'algorithm')", path_, metric));
      }
      metric_columns_.push_back(c);
    }
    has_row_ = read_row();
  }

  const std::string& point_header() const { return point_header_; }
  std::size_t slot(std::size_t algorithm, std::size_t metric) const { return algorithm * metric_columns_.size() + metric; }

  // The next point's rows; false after the last. InputError for a malformed row, rows out of
  // point order, or (at the end) a compared algorithm without rows.
  bool next_point(PointRows& rows) {
    if (!has_row_) {
      check_algorithms_found();
      return false;
    }
    rows.point = point_;
    rows.fields = leading_;
    rows.values.resize(algorithms_.size() * metric_columns_.size());
    for (auto& values : rows.values) values.clear();
    while (has_row_ && point_ == rows.point) {
      const auto wanted = std::find(algorithms_.begin(), algorithms_.end(), fields_[static_cast<std::size_t>(algorithm_)]);
      if (wanted != algorithms_.end()) {
        const auto a = static_cast<std::size_t>(wanted - algorithms_.begin());
        for (std::size_t k = 0; k < metric_columns_.size(); ++k) {
          const std::string& field = fields_[static_cast<std::size_t>(metric_columns_[k])];
          rows.values[slot(a, k)].emplace_back(trial_index_, field.empty() ? kNaN : std::strtod(field.c_str(), nullptr));
        }
      }
      const long long previous = point_;
      has_row_ = read_row();
      if (has_row_ && point_ < previous) {
        throw InputError(fmt::format("compare: {}:{}: point {} after point {}: rows are not in point order (as dabench "
                                     "writes them)", path_, line_, point_, previous));
      }
    }
    return true;
  }

 private:
  bool read_row() {
    std::string line;
    if (!std::getline(in_, line)) return false;
    ++line_;
    if (!split_csv_line(line, fields_)) throw InputError(fmt::format("compare: {}:{}: a quote is left open", path_, line_));
    if (fields_.size() != header_.size()) {
      throw InputError(fmt::format("compare: {}:{}: {} fields, the header has {}", path_, line_, fields_.size(), header_.size()));
    }
    seen_.insert(fields_[static_cast<std::size_t>(algorithm_)]);
    const auto index = [&](const std::string& field) {
      long long value = -1;
      const auto [stop, error] = std::from_chars(field.data(), field.data() + field.size(), value);
      if (error != std::errc() || stop != field.data() + field.size() || value < 0) {
        throw InputError(fmt::format("compare: {}:{}: '{}' is not a point or trial index", path_, line_, field));
      }
      return value;
    };
    const long long point = index(fields_[0]);
    trial_index_ = index(fields_[static_cast<std::size_t>(trial_)]);
    if (point != point_) {
      leading_.clear();
      for (int c = 0; c < trial_; ++c) {
        if (c > 0) leading_ += ',';
        append_csv_field(leading_, fields_[static_cast<std::size_t>(c)]);
      }
    }
    point_ = point;
    return true;
  }

  void check_algorithms_found() const {
    for (const std::string& name : algorithms_) {
      if (seen_.count(name)) continue;
      std::string known;
      for (const std::string& a : seen_) known += (known.empty() ? "" : ", ") + a;
      throw InputError(fmt::format("compare: {}: no rows of algorithm '{}' (it has: {})", path_, name, known));
    }
  }

  std::string path_;
  std::vector<std::string> algorithms_;
  std::ifstream in_;
  std::vector<std::string> header_, fields_;
  std::string point_header_, leading_;
  int trial_ = -1, algorithm_ = -1;
  std::vector<int> metric_columns_;
  std::set<std::string> seen_;
  bool has_row_ = false;
  long long point_ = -1, trial_index_ = -1, line_ = 1;
};

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
  static_cast<void>(trials_file(options.run_a));  // before meta.json: a folder that is no run says so
  const std::vector<std::string> metrics =
      options.metrics.empty() ? recorded_kind(options.run_a, "compare").compared_metrics() : options.metrics;
  Comparison comparison;
  PointStream a(options.run_a, options.algorithms, metrics);
  std::optional<PointStream> b;
  const std::string& name_a = options.algorithms[0];
  const std::string& name_b = two_runs ? options.algorithms[0] : options.algorithms[1];
  if (two_runs) {
    for (const char* key : {"fingerprint", "seed"}) {
      if (meta_field(options.run_a, key) != meta_field(options.run_b, key)) {
        throw InputError(fmt::format("compare: {} and {} are not runs of the same plan (their {} differ): their trials "
                                     "are not the same problems", options.run_a, options.run_b, key));
      }
    }
    b.emplace(options.run_b, options.algorithms, metrics);
    comparison.label_a = fmt::format("{} ({})", name_a, options.run_a);
    comparison.label_b = fmt::format("{} ({})", name_b, options.run_b);
  } else {
    comparison.label_a = name_a;
    comparison.label_b = name_b;
  }
  comparison.header = a.point_header();
  // Point by point (file order), then the rows metric by metric, as the table shows them.
  std::vector<std::vector<ComparisonRow>> by_metric(metrics.size());
  PointRows rows_a, rows_b;
  bool b_has_point = false;
  while (a.next_point(rows_a)) {
    bool paired = true;
    if (b) {  // run B's rows of the same point (none when it has no such point)
      while ((!b_has_point || rows_b.point < rows_a.point) && (b_has_point = b->next_point(rows_b))) {}
      paired = b_has_point && rows_b.point == rows_a.point;
    }
    for (std::size_t k = 0; k < metrics.size(); ++k) {
      auto& values_a = rows_a.values[a.slot(0, k)];
      std::vector<double> differences;  // in trial order
      if (paired) {
        auto& values_b = two_runs ? rows_b.values[b->slot(0, k)] : rows_a.values[a.slot(1, k)];
        by_trial(values_a);
        by_trial(values_b);
        auto match = values_b.begin();
        for (const auto& [trial, value_a] : values_a) {
          while (match != values_b.end() && match->first < trial) ++match;
          if (match == values_b.end() || match->first != trial) continue;
          if (std::isfinite(value_a) && std::isfinite(match->second)) differences.push_back(value_a - match->second);
        }
      }
      by_metric[k].push_back({rows_a.fields, metrics[k], paired_statistics(differences), kNaN});
    }
  }
  if (b) {
    while (b->next_point(rows_b)) {}  // (its algorithms checked to have rows)
  }
  for (std::vector<ComparisonRow>& rows : by_metric) {
    std::vector<double> p;
    for (const ComparisonRow& row : rows) p.push_back(row.stats.n > 0 ? row.stats.wilcoxon_p : kNaN);
    const std::vector<double> holm = holm_adjust(p);
    for (std::size_t r = 0; r < rows.size(); ++r) rows[r].holm_p = holm[r];
    comparison.rows.insert(comparison.rows.end(), rows.begin(), rows.end());
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
