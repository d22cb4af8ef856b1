#include "algorithms/tbd/cell_exclusion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "algorithms/tbd/support_likelihood.hpp"
#include "harness/core/special_values.hpp"

namespace dabench {

namespace {

constexpr double kMaxLogOdds = 700.0;  // log π is capped here (a node that must cover the cell)

}  // namespace

void CellExclusion::reset(const TbdSensor& sensor, double radius) {
  sensor_ = &sensor;
  radius_ = radius;
  count_ = 0;
  reach_.resize(sensor.cells());
  for (std::vector<Reach>& nodes : reach_) nodes.clear();
  converged_ = false;
}

template <class Visit>
void CellExclusion::for_support(const Node& node, double px, double py, Visit&& visit) const {
  visit_support(*sensor_, radius_, px, py, node.column_begin, node.column_begin + node.columns, node.row_begin,
                node.row_begin + node.rows, [&](int column, int row) {
                  visit((row - node.row_begin) * node.columns + column - node.column_begin);
                });
}

int CellExclusion::global_cell(const Node& node, int window_cell) const {
  return (node.row_begin + window_cell / node.columns) * sensor_->columns + node.column_begin +
         window_cell % node.columns;
}

int CellExclusion::add(const double* x, const double* y, const double* log_weight, int count, double existence,
                       double pad) {
  if (count_ == static_cast<int>(nodes_.size())) nodes_.emplace_back();
  Node& node = nodes_[count_];
  const TbdSensor& s = *sensor_;

  double top = kMinusInfinity;
  double x_low = std::numeric_limits<double>::infinity(), x_high = -x_low, y_low = x_low, y_high = -x_low;
  for (int p = 0; p < count; ++p) {
    top = std::max(top, log_weight[p]);
    x_low = std::min(x_low, x[p]);
    x_high = std::max(x_high, x[p]);
    y_low = std::min(y_low, y[p]);
    y_high = std::max(y_high, y[p]);
  }
  const double reach = radius_ + pad;
  node.column_begin = std::max(0, static_cast<int>(std::ceil((x_low - reach - s.x_min) / s.cell_size - 0.5)));
  node.row_begin = std::max(0, static_cast<int>(std::ceil((y_low - reach - s.y_min) / s.cell_size - 0.5)));
  const int column_end =
      std::min(s.columns, static_cast<int>(std::floor((x_high + reach - s.x_min) / s.cell_size - 0.5)) + 1);
  const int row_end = std::min(s.rows, static_cast<int>(std::floor((y_high + reach - s.y_min) / s.cell_size - 0.5)) + 1);
  node.columns = std::max(0, column_end - node.column_begin);
  node.rows = std::max(0, row_end - node.row_begin);
  const int cells = node.columns * node.rows;
  node.log_pi.assign(cells, kMinusInfinity);
  node.log_nu.assign(cells, 0.0);
  node.covered.assign(cells, 0.0);
  for (int c = 0; c < cells; ++c) reach_[global_cell(node, c)].push_back({count_, c});

  // A node without mass (every a_ip = 0, or r = 0) is absent: b(0) = 1.
  const bool present = std::isfinite(top) && existence > 0.0;
  node.log_scaled.resize(count);
  node.particle.resize(count);
  node.cover_begin.resize(count + 1);
  node.cover.clear();
  for (int p = 0; p < count; ++p) {
    node.log_scaled[p] = present ? log_weight[p] - top : kMinusInfinity;
    node.cover_begin[p] = static_cast<int>(node.cover.size());
    if (cells > 0) for_support(node, x[p], y[p], [&](int c) { node.cover.push_back(c); });
  }
  node.cover_begin[count] = static_cast<int>(node.cover.size());
  node.log_absent = present ? std::log1p(-existence) - std::log(existence) - top : 0.0;
  node.total = 0.0;
  node.absent = 1.0;
  node.existence = -1.0;  // no belief yet: the first update always counts as a change
  node.previous.assign(count, 0.0);
  return count_++;
}

double CellExclusion::update(int index, bool new_pi) {
  Node& node = nodes_[index];
  const int cells = node.columns * node.rows;
  // log ν_{j→i} = −log(1 + Σ_{i'≠i} π_{i'j}).
  for (int c = 0; c < cells; ++c) {
    const std::vector<Reach>& others = reach_[global_cell(node, c)];
    double top = 0.0;
    for (const Reach& r : others) {
      if (r.node != index) top = std::max(top, nodes_[r.node].log_pi[r.cell]);
    }
    double sum = std::exp(-top);
    for (const Reach& r : others) {
      if (r.node != index) sum += std::exp(nodes_[r.node].log_pi[r.cell] - top);
    }
    node.log_nu[c] = -(top + std::log(sum));
    node.covered[c] = 0.0;
  }
  // Belief: log b(x_p, 1) = log a_p + Σ_{j∈S} log ν, on a common shift with b(0).
  const int count = static_cast<int>(node.log_scaled.size());
  double shift = node.log_absent;
  for (int p = 0; p < count; ++p) {
    double l = node.log_scaled[p];
    for (int e = node.cover_begin[p]; e < node.cover_begin[p + 1]; ++e) l += node.log_nu[node.cover[e]];
    node.particle[p] = l;
    shift = std::max(shift, l);
  }
  double total = 0.0;
  for (int p = 0; p < count; ++p) {
    const double v = node.particle[p] = std::exp(node.particle[p] - shift);
    total += v;
    for (int e = node.cover_begin[p]; e < node.cover_begin[p + 1]; ++e) node.covered[node.cover[e]] += v;
  }
  node.total = total;
  node.absent = std::exp(node.log_absent - shift);
  if (!new_pi) return 0.0;
  // The belief's change since the node's last update: the larger of |Δ r̃| and the total
  // variation of its weights.
  const double existence = total > 0.0 ? total / (total + node.absent) : 0.0;
  double change = std::abs(existence - node.existence);
  double variation = 0.0;
  for (int p = 0; p < count; ++p) {
    const double w = total > 0.0 ? node.particle[p] / total : 0.0;
    variation += std::abs(w - node.previous[p]);
    node.previous[p] = w;
  }
  node.existence = existence;
  change = std::max(change, 0.5 * variation);
  // π_ij = (C_ij / ν_{j→i}) / (b(0) + T − C_ij).
  for (int c = 0; c < cells; ++c) {
    double log_pi = kMinusInfinity;
    if (node.covered[c] > 0.0) {
      const double uncovered = std::max(0.0, node.absent + total - node.covered[c]);
      log_pi = std::min(kMaxLogOdds, std::log(node.covered[c]) - node.log_nu[c] - std::log(uncovered));
    }
    node.log_pi[c] = log_pi;
  }
  return change;
}

int CellExclusion::solve(int max_sweeps, double tolerance) {
  converged_ = false;
  int sweeps = 0;
  while (sweeps < max_sweeps && !converged_) {
    double change = 0.0;
    for (int i = 0; i < count_; ++i) change = std::max(change, update(i, true));
    ++sweeps;
    converged_ = change <= tolerance;
  }
  for (int i = 0; i < count_; ++i) update(i, false);  // beliefs from the final π
  return sweeps;
}

double CellExclusion::existence(int node) const {
  const Node& n = nodes_[node];
  return n.total > 0.0 ? n.total / (n.total + n.absent) : 0.0;
}

void CellExclusion::posterior_weights(int node, std::vector<double>& weights) const {
  const Node& n = nodes_[node];
  const int count = static_cast<int>(n.particle.size());
  weights.resize(count);
  for (int p = 0; p < count; ++p) weights[p] = n.total > 0.0 ? n.particle[p] / n.total : 0.0;
}

double CellExclusion::log_message_at(int node, double px, double py) const {
  const Node& n = nodes_[node];
  double sum = 0.0;
  if (n.columns * n.rows > 0) for_support(n, px, py, [&](int c) { sum += n.log_nu[c]; });
  return sum;
}

}  // namespace dabench
