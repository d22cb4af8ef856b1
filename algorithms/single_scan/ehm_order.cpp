// The order of EHM's targets (ehm.hpp, option `order`): the candidate orders and the
// estimate of the net each gives.
#include <algorithm>
#include <climits>
#include <cmath>

#include "algorithms/single_scan/ehm.hpp"

namespace dabench {

// Estimated net size of a target order. After k targets the frontier F_k is the set of shared
// measurements gated by one of them and by a later target (plain EHM's key space); the layer
// holds at most 2^|F_k| used-sets, and at most Π_i (1 + f_i) over the processed targets i, f_i
// = how many frontier measurements i gates (each target uses at most one). The estimate is
// Σ_k min of the two (the product term is skipped on clusters above 400 targets, where its
// O(K²·gate) cost would matter). It ranks the candidate orders; the work limit uses net_bound.
double Ehm::order_cost(const std::vector<int>& order) {
  const int size = cluster_size_;
  count_.resize(shared_);
  for (int j = 0; j < shared_; ++j) count_[j] = meas_begin_[j + 1] - meas_begin_[j];
  touched_.assign(shared_, 0);
  const bool product = size <= 400;
  int frontier = 0;
  double cost = 0.0;
  for (int k = 0; k < size; ++k) {
    const int li = order[k];
    for (int g = gate_begin_[li]; g < gate_begin_[li + 1]; ++g) {
      const int j = gate_meas_[g];
      frontier -= static_cast<int>(touched_[j] && count_[j] > 0);
      --count_[j];
      touched_[j] = 1;
      frontier += static_cast<int>(count_[j] > 0);
    }
    double log_width = std::min(frontier, 1000) * std::log(2.0);
    if (product) {
      double log_product = 0.0;
      for (int q = 0; q <= k; ++q) {
        int live = 0;
        for (int g = gate_begin_[order[q]]; g < gate_begin_[order[q] + 1]; ++g) live += count_[gate_meas_[g]] > 0;
        log_product += std::log1p(live);
      }
      log_width = std::min(log_width, log_product);
    }
    cost += std::exp(log_width);
  }
  return cost;
}

// order = 0: the cheapest (by order_cost) of the Cuthill–McKee order, greedy min-frontier orders
// started by their own rule, from both ends of the BFS's pseudo-peripheral diameter and after
// the "hub" targets, and the input order. order = 1, 2, 3: greedy, BFS, input only.
void Ehm::choose_order() {
  const int size = cluster_size_;
  auto input = [&] {
    order_.resize(size);
    for (int li = 0; li < size; ++li) order_[li] = li;
  };
  if (options_.order != 0) {
    if (options_.order == 1) {
      prefix_targets_.clear();
      order_greedy(prefix_targets_);
    } else if (options_.order == 2) {
      order_bfs();
    } else {
      input();
    }
    return;
  }
  order_bfs();
  best_order_ = order_;
  double best = order_cost(order_);
  auto consider = [&] {
    const double cost = order_cost(order_);
    if (cost < best) {
      best = cost;
      best_order_.swap(order_);
    }
  };
  const int ends[2] = {bfs_start_, order_.back()};
  prefix_targets_.clear();
  order_greedy(prefix_targets_);
  consider();
  for (const int start : ends) {
    prefix_targets_.assign(1, start);
    order_greedy(prefix_targets_);
    consider();
  }
  // Hubs first: targets gating far more shared measurements than is typical (e.g. tracks whose
  // gates grew after missed detections) each add at most one used measurement when processed
  // early, but keep their whole gate in the frontier when processed in sweep order.
  degree_.resize(size);
  for (int li = 0; li < size; ++li) degree_[li] = gate_begin_[li + 1] - gate_begin_[li];
  order_.assign(degree_.begin(), degree_.end());
  std::nth_element(order_.begin(), order_.begin() + size / 2, order_.end());
  const int median = order_[size / 2];
  prefix_targets_.clear();
  for (int li = 0; li < size; ++li) {
    if (degree_[li] >= std::max(2 * median, median + 4)) prefix_targets_.push_back(li);
  }
  if (!prefix_targets_.empty() && static_cast<int>(prefix_targets_.size()) < size) {
    std::stable_sort(prefix_targets_.begin(), prefix_targets_.end(), [&](int a, int b) { return degree_[a] > degree_[b]; });
    order_greedy(prefix_targets_);
    consider();
  }
  input();
  if (order_cost(order_) < best) return;
  order_.swap(best_order_);
}

// Greedy minimum frontier: the frontier is the set of shared measurements gated by a processed
// target and by an unprocessed one; take the target whose addition leaves it smallest.
void Ehm::order_greedy(const std::vector<int>& prefix) {
  const int size = cluster_size_;
  count_.resize(shared_);
  for (int j = 0; j < shared_; ++j) count_[j] = meas_begin_[j + 1] - meas_begin_[j];  // unprocessed gating targets
  touched_.assign(shared_, 0);
  done_.assign(size, 0);
  order_.clear();
  const auto forced = static_cast<int>(prefix.size());
  for (int step = 0; step < size; ++step) {
    int best = -1, best_delta = INT_MAX, best_touch = -1;
    for (int li = step < forced ? prefix[step] : 0; li < size; ++li) {
      if (done_[li]) continue;
      int delta = 0, touch = 0;
      for (int g = gate_begin_[li]; g < gate_begin_[li + 1]; ++g) {
        const int j = gate_meas_[g];
        const int remaining = count_[j];
        delta += static_cast<int>(remaining > 1) - static_cast<int>(touched_[j] && remaining > 0);
        touch += touched_[j];
      }
      if (delta < best_delta || (delta == best_delta && touch > best_touch)) {
        best = li;
        best_delta = delta;
        best_touch = touch;
      }
      if (step < forced) break;
    }
    done_[best] = 1;
    order_.push_back(best);
    for (int g = gate_begin_[best]; g < gate_begin_[best + 1]; ++g) {
      --count_[gate_meas_[g]];
      touched_[gate_meas_[g]] = 1;
    }
  }
}

// Cuthill–McKee: breadth-first from a pseudo-peripheral target, neighbours by increasing degree.
void Ehm::order_bfs() {
  const int size = cluster_size_;
  mark_.assign(size, -1);
  int stamp = 0;
  auto for_neighbours = [&](int li, auto&& visit) {
    ++stamp;
    mark_[li] = stamp;
    for (int g = gate_begin_[li]; g < gate_begin_[li + 1]; ++g) {
      const int j = gate_meas_[g];
      for (int k = meas_begin_[j]; k < meas_begin_[j + 1]; ++k) {
        const int q = meas_targets_[k];
        if (mark_[q] != stamp) {
          mark_[q] = stamp;
          visit(q);
        }
      }
    }
  };
  degree_.assign(size, 0);
  for (int li = 0; li < size; ++li) for_neighbours(li, [&](int) { ++degree_[li]; });

  // BFS levels from `start` into count_; returns the eccentricity.
  auto levels = [&](int start) {
    count_.assign(size, -1);
    queue_.clear();
    queue_.push_back(start);
    count_[start] = 0;
    int eccentricity = 0;
    for (std::size_t head = 0; head < queue_.size(); ++head) {
      const int u = queue_[head];
      for_neighbours(u, [&](int q) {
        if (count_[q] < 0) {
          count_[q] = count_[u] + 1;
          eccentricity = std::max(eccentricity, count_[q]);
          queue_.push_back(q);
        }
      });
    }
    return eccentricity;
  };
  int start = 0;
  for (int li = 1; li < size; ++li) {
    if (degree_[li] < degree_[start]) start = li;
  }
  int eccentricity = levels(start);
  for (int round = 0; round < 8; ++round) {
    int candidate = -1;
    for (int li = 0; li < size; ++li) {
      if (count_[li] == eccentricity && (candidate < 0 || degree_[li] < degree_[candidate])) candidate = li;
    }
    const int further = levels(candidate);
    if (further <= eccentricity) break;
    start = candidate;
    eccentricity = further;
  }

  bfs_start_ = start;
  order_.clear();
  done_.assign(size, 0);
  order_.push_back(start);
  done_[start] = 1;
  for (std::size_t head = 0; head < order_.size(); ++head) {
    const std::size_t from = order_.size();
    for_neighbours(order_[head], [&](int q) {
      if (!done_[q]) {
        done_[q] = 1;
        order_.push_back(q);
      }
    });
    std::sort(order_.begin() + static_cast<std::ptrdiff_t>(from), order_.end(), [&](int a, int b) {
      return degree_[a] != degree_[b] ? degree_[a] < degree_[b] : a < b;
    });
  }
}

}  // namespace dabench
