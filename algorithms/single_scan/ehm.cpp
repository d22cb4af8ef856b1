#include "algorithms/single_scan/ehm.hpp"

#include <algorithm>
#include <climits>
#include <cfenv>
#include <cmath>
#include <limits>

#include "harness/core/special_values.hpp"
#include "harness/single_scan/registry.hpp"

namespace dabench {

std::string EhmOptions::validate() const {
  if (!(threshold >= 0.0)) return "threshold must be >= 0";
  if (max_nodes < 1 || max_nodes > 2000000000) return "max_nodes must be in [1, 2e9]";
  if (order < 0 || order > 3) return "order must be 0 (auto), 1 (greedy), 2 (bfs) or 3 (input)";
  return {};
}

namespace {

constexpr int kMaxWords = 8;     // key spaces up to 512 shared measurements
// The most a product below the normal range loses (its error bound: backward_pass).
constexpr double kSubnormal = std::numeric_limits<double>::denorm_min();
constexpr int kDirectBits = 22;  // key spaces up to this size use a direct-address index (16 MB)

inline std::uint64_t fmix64(std::uint64_t x) {
  x ^= x >> 33;
  x *= 0xff51afd7ed558ccdULL;
  x ^= x >> 33;
  x *= 0xc4ceb9fe1a85ec53ULL;
  x ^= x >> 33;
  return x;
}

template <int W>
inline std::uint64_t hash_key(const std::uint64_t* key) {
  std::uint64_t h = key[0];
  for (int w = 1; w < W; ++w) h = (h * 0x9e3779b97f4a7c15ULL) ^ key[w];
  return fmix64(h);
}

template <int W>
inline bool same_key(const std::uint64_t* a, const std::uint64_t* b) {
  for (int w = 0; w < W; ++w) {
    if (a[w] != b[w]) return false;
  }
  return true;
}

inline bool has_bit(const std::uint64_t* key, int bit) { return (key[bit >> 6] >> (bit & 63)) & 1U; }
inline void set_key_bit(std::uint64_t* key, int bit) { key[bit >> 6] |= std::uint64_t{1} << (bit & 63); }

}  // namespace

// ---------------------------------------------------------------------------------------------
// Hash table of the layer being built: slots hold node ids; a slot is live only if its stamp is
// the current generation, so starting a new layer costs nothing.

template <int W>
std::int32_t Ehm::find_or_insert(const std::uint64_t* key) {
  std::uint64_t h = hash_key<W>(key) & mask_;
  while (true) {
    Slot& slot = slots_[h];
    if (slot.stamp != generation_) {
      if (++nodes_total_ > options_.max_nodes) return -1;
      const auto id = static_cast<std::int32_t>(keys_.size() / W);
      slot = {generation_, id};
      keys_.insert(keys_.end(), key, key + W);
      return id;
    }
    if (same_key<W>(keys_.data() + static_cast<std::size_t>(slot.node) * W, key)) return slot.node;
    h = (h + 1) & mask_;
  }
}

template <int W>
void Ehm::grow_table(std::int32_t layer_first) {
  const std::uint64_t capacity = (mask_ + 1) * 2;
  if (slots_.size() < capacity) slots_.resize(capacity, Slot{0, 0});
  if (generation_ == UINT32_MAX) {
    for (Slot& s : slots_) s.stamp = 0;
    generation_ = 0;
  }
  ++generation_;
  mask_ = capacity - 1;
  const auto end = static_cast<std::int32_t>(keys_.size() / W);
  for (std::int32_t id = layer_first; id < end; ++id) {
    std::uint64_t h = hash_key<W>(keys_.data() + static_cast<std::size_t>(id) * W) & mask_;
    while (slots_[h].stamp == generation_) h = (h + 1) & mask_;
    slots_[h] = {generation_, id};
  }
}

// ---------------------------------------------------------------------------------------------

void Ehm::solve(const SingleScanProblem& problem, MarginalTable& marginals, SolveReport& report) {
  report.reset();
  stats_ = EhmStats{};
  graph_.build(problem, options_.threshold);
  graph_.find_clusters();
  const int n = graph_.targets();
  const int m = graph_.measurements();
  marginals.reshape_zero(n, m);
  local_id_.assign(m, -1);  // clusters use disjoint measurements: one reset per solve suffices
  nodes_total_ = 0;
  stats_.clusters = graph_.clusters();
  for (int c = 0; c < graph_.clusters(); ++c) {
    const char* reason = solve_cluster(graph_.cluster_start(c), graph_.cluster_start(c + 1), marginals);
    if (reason[0] != '\0') {
      report.skipped = reason;
      stats_.nodes = nodes_total_;
      return;
    }
  }
  stats_.nodes = nodes_total_;
}

// A cluster of one target: p(a = j) = ψ(j) / (1 + Σ ψ) (write_normalized_row).
void Ehm::solve_single(int target, MarginalTable& marginals) {
  const RowNormalizer z = write_normalized_row(graph_, target, graph_.edge_weights(), marginals.row(target));
  stats_.log_partition += std::log(z.largest) + std::log(z.total);
  ++nodes_total_;
  stats_.max_layer_width = std::max(stats_.max_layer_width, 1);
  stats_.largest_cluster = std::max(stats_.largest_cluster, 1);
}

const char* Ehm::solve_cluster(int first, int last, MarginalTable& marginals) {
  const int size = last - first;
  if (size == 1) {
    solve_single(graph_.cluster_targets()[first], marginals);
    return "";
  }
  cluster_size_ = size;
  stats_.largest_cluster = std::max(stats_.largest_cluster, size);
  targets_.assign(graph_.cluster_targets().begin() + first, graph_.cluster_targets().begin() + last);

  // Shared measurements (gated by >= 2 targets) get local ids; exclusive ones fold into choice 0.
  shared_ = 0;
  gate_begin_.resize(size + 1);
  gate_meas_.clear();
  gate_edge_.clear();
  gate_weight_.clear();
  stay_weight_.resize(size);
  exclusive_sum_.resize(size);
  row_scale_.resize(size);
  for (int li = 0; li < size; ++li) {
    const int t = targets_[li];
    double largest = 1.0;
    for (int e = graph_.row_begin(t); e < graph_.row_end(t); ++e) largest = std::max(largest, graph_.edge_weight(e));
    double exclusive = 0.0;
    gate_begin_[li] = static_cast<int>(gate_meas_.size());
    for (int e = graph_.row_begin(t); e < graph_.row_end(t); ++e) {
      const int j = graph_.edge_measurement(e);
      const double w = graph_.edge_weight(e) / largest;
      if (graph_.measurement_degree(j) >= 2) {
        if (local_id_[j] < 0) local_id_[j] = shared_++;
        gate_meas_.push_back(local_id_[j]);
        gate_edge_.push_back(e);
        gate_weight_.push_back(w);
      } else {
        exclusive += w;
      }
    }
    row_scale_[li] = largest;
    exclusive_sum_[li] = exclusive;
    stay_weight_[li] = 1.0 / largest + exclusive;
  }
  gate_begin_[size] = static_cast<int>(gate_meas_.size());

  // Measurement → gating targets (local ids, targets ascending).
  meas_begin_.assign(shared_ + 1, 0);
  for (const int j : gate_meas_) ++meas_begin_[j + 1];
  for (int j = 0; j < shared_; ++j) meas_begin_[j + 1] += meas_begin_[j];
  meas_targets_.resize(gate_meas_.size());
  count_.assign(meas_begin_.begin(), meas_begin_.end() - 1);
  for (int li = 0; li < size; ++li) {
    for (int g = gate_begin_[li]; g < gate_begin_[li + 1]; ++g) meas_targets_[count_[gate_meas_[g]]++] = li;
  }

  choose_order();
  stats_.estimated_nodes += cluster_estimate_;
  // The estimate bounds the plain-EHM net from above and is within a factor 0.6-1 of the
  // nodes built on the grids that finish; refuse up front only far past the cap.
  if (cluster_estimate_ > kEstimateMargin * static_cast<double>(options_.max_nodes)) return "work_estimate";
  position_.resize(size);
  for (int p = 0; p < size; ++p) position_[order_[p]] = p;
  build_tree();
  const int bits = build_tables();
  stats_.max_key_bits = std::max(stats_.max_key_bits, bits);
  if (bits <= 64) return run_net<1>(marginals);
  if (bits <= 128) return run_net<2>(marginals);
  if (bits <= 256) return run_net<4>(marginals);
  if (bits <= 64 * kMaxWords) return run_net<kMaxWords>(marginals);
  return "key_width";
}

// Estimated net size of a target order. After k targets the frontier F_k is the set of shared
// measurements gated by one of them and by a later target (plain EHM's key space); the layer
// holds at most 2^|F_k| used-sets, and at most Π_i (1 + f_i) over the processed targets i, f_i
// = how many frontier measurements i gates (each target uses at most one). The estimate is
// Σ_k min of the two (the product term is skipped on clusters above 400 targets, where its
// O(K²·gate) cost would matter). Returns it, and the widest frontier in `widest`.
double Ehm::order_cost(const std::vector<int>& order, int& widest) {
  const int size = cluster_size_;
  count_.resize(shared_);
  for (int j = 0; j < shared_; ++j) count_[j] = meas_begin_[j + 1] - meas_begin_[j];
  touched_.assign(shared_, 0);
  const bool product = size <= 400;
  int frontier = 0;
  double cost = 0.0;
  widest = 0;
  for (int k = 0; k < size; ++k) {
    const int li = order[k];
    for (int g = gate_begin_[li]; g < gate_begin_[li + 1]; ++g) {
      const int j = gate_meas_[g];
      frontier -= static_cast<int>(touched_[j] && count_[j] > 0);
      --count_[j];
      touched_[j] = 1;
      frontier += static_cast<int>(count_[j] > 0);
    }
    widest = std::max(widest, frontier);
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
  int widest = 0;
  if (options_.order != 0) {
    if (options_.order == 1) {
      prefix_targets_.clear();
      order_greedy(prefix_targets_);
    } else if (options_.order == 2) {
      order_bfs();
    } else {
      input();
    }
    cluster_estimate_ = order_cost(order_, widest);
    return;
  }
  order_bfs();
  best_order_ = order_;
  double best = order_cost(order_, widest);
  auto consider = [&] {
    const double cost = order_cost(order_, widest);
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
  cluster_estimate_ = order_cost(order_, widest);
  if (cluster_estimate_ < best) return;
  cluster_estimate_ = best;
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

// Tree of tracks over positions (parent position < child position).
void Ehm::build_tree() {
  const int size = cluster_size_;
  parent_.assign(size, -1);
  if (!options_.tree) {
    for (int p = 1; p < size; ++p) parent_[p] = p - 1;
  } else {
    // EHM2: from the last target back, a target adopts every subtree sharing a gated measurement.
    uf_.resize(size);
    mark2_.assign(shared_, -1);  // owner: a position of the subtree that gates the measurement
    auto find = [&](int x) {
      while (uf_[x] != x) {
        uf_[x] = uf_[uf_[x]];
        x = uf_[x];
      }
      return x;
    };
    for (int p = size - 1; p >= 0; --p) {
      uf_[p] = p;
      const int li = order_[p];
      for (int g = gate_begin_[li]; g < gate_begin_[li + 1]; ++g) {
        const int j = gate_meas_[g];
        if (mark2_[j] >= 0) {
          const int root = find(mark2_[j]);
          if (root != p) {
            parent_[root] = p;
            uf_[root] = p;
          }
        }
        mark2_[j] = p;
      }
    }
  }
  child_begin_.assign(size + 1, 0);
  for (int p = 0; p < size; ++p) {
    if (parent_[p] >= 0) ++child_begin_[parent_[p] + 1];
  }
  for (int p = 0; p < size; ++p) child_begin_[p + 1] += child_begin_[p];
  child_list_.resize(child_begin_[size]);
  count_.assign(child_begin_.begin(), child_begin_.end() - 1);
  for (int p = 0; p < size; ++p) {
    if (parent_[p] >= 0) child_list_[count_[parent_[p]]++] = p;
  }
  // Preorder intervals: subtree sizes bottom-up (children have larger positions), then tin top-down.
  tout_.assign(size, 1);
  for (int p = size - 1; p >= 0; --p) {
    if (parent_[p] >= 0) tout_[parent_[p]] += tout_[p];
  }
  tin_.assign(size, 0);
  int next_root = 0;
  for (int p = 0; p < size; ++p) {
    if (parent_[p] < 0) {
      tin_[p] = next_root;
      next_root += tout_[p];
    }
    int next = tin_[p] + 1;
    for (int k = child_begin_[p]; k < child_begin_[p + 1]; ++k) {
      tin_[child_list_[k]] = next;
      next += tout_[child_list_[k]];
    }
  }
  for (int p = 0; p < size; ++p) tout_[p] += tin_[p];
}

// Key spaces K(c) = D(c) ∩ (K(p) ∪ gate(p)) for every child c of p, and the per-position
// choice, test, set and remap tables of the net. Returns max |K|.
int Ehm::build_tables() {
  const int size = cluster_size_;
  key_begin_.assign(size, 0);
  key_size_.assign(size, 0);
  key_list_.clear();
  choice_begin_.resize(size + 1);
  choice_weight_.clear();
  choice_test_.clear();
  set_begin_.resize(size + 1);
  set_bit_.clear();
  remap_begin_.resize(size + 1);
  remap_bit_.clear();
  mark_.assign(shared_, -1);
  mark2_.assign(shared_, -1);
  auto in_subtree = [&](int j, int c) {  // j ∈ D(c)
    for (int k = meas_begin_[j]; k < meas_begin_[j + 1]; ++k) {
      const int q = tin_[position_[meas_targets_[k]]];
      if (q >= tin_[c] && q < tout_[c]) return true;
    }
    return false;
  };
  int widest = 0;
  for (int p = 0; p < size; ++p) {
    const int li = order_[p];
    const int kb = key_begin_[p], ks = key_size_[p];
    widest = std::max(widest, ks);
    for (int b = 0; b < ks; ++b) mark_[key_list_[kb + b]] = b;
    choice_begin_[p] = static_cast<int>(choice_weight_.size());
    choice_weight_.push_back(stay_weight_[li]);
    choice_test_.push_back(-1);
    for (int g = gate_begin_[li]; g < gate_begin_[li + 1]; ++g) {
      choice_weight_.push_back(gate_weight_[g]);
      choice_test_.push_back(mark_[gate_meas_[g]]);
    }
    set_begin_[p] = static_cast<int>(set_bit_.size());
    remap_begin_[p] = static_cast<int>(remap_bit_.size());
    for (int k = child_begin_[p]; k < child_begin_[p + 1]; ++k) {
      const int c = child_list_[k];
      key_begin_[c] = static_cast<int>(key_list_.size());
      for (int b = 0; b < ks; ++b) {
        const int j = key_list_[kb + b];
        if (in_subtree(j, c)) key_list_.push_back(j);
      }
      for (int g = gate_begin_[li]; g < gate_begin_[li + 1]; ++g) {
        const int j = gate_meas_[g];
        if (mark_[j] < 0 && in_subtree(j, c)) key_list_.push_back(j);
      }
      key_size_[c] = static_cast<int>(key_list_.size()) - key_begin_[c];
      for (int b = 0; b < key_size_[c]; ++b) mark2_[key_list_[key_begin_[c] + b]] = b;
      for (int b = 0; b < ks; ++b) remap_bit_.push_back(mark2_[key_list_[kb + b]]);
      set_bit_.push_back(-1);
      for (int g = gate_begin_[li]; g < gate_begin_[li + 1]; ++g) set_bit_.push_back(mark2_[gate_meas_[g]]);
      for (int b = 0; b < key_size_[c]; ++b) mark2_[key_list_[key_begin_[c] + b]] = -1;
    }
    for (int b = 0; b < ks; ++b) mark_[key_list_[kb + b]] = -1;
  }
  choice_begin_[size] = static_cast<int>(choice_weight_.size());
  set_begin_[size] = static_cast<int>(set_bit_.size());
  remap_begin_[size] = static_cast<int>(remap_bit_.size());
  return widest;
}

// ---------------------------------------------------------------------------------------------
// The net (header, Method 2-3): build_net lays out the layers top-down, backward_pass computes β
// bottom-up, forward_pass computes α top-down and the targets' rows with it.

template <int W>
const char* Ehm::run_net(MarginalTable& marginals) {
  if (!build_net<W>()) return "work_limit";
  std::feclearexcept(FE_UNDERFLOW);  // write_row applies the underflow bound only once it is raised
  // Every layer's factor enters Z exactly once (β_root = Π of the factors below it) when the
  // cluster's tree has one root, which a connected cluster always has.
  stats_.log_partition += backward_pass<W>();
  for (int li = 0; li < cluster_size_; ++li) stats_.log_partition += std::log(row_scale_[li]);
  return forward_pass<W>(marginals) ? "" : "numerical";
}

// The layers and their links, top-down: a root layer holds one node (nothing used yet); the layer
// of child c of p holds the keys (S ∪ {j}) ∩ K(c) over p's nodes S and p's choices j allowed by S.
// edges_ holds, per node of p, per choice, per child slot, the child node it leads to (-1: j ∈ S).
// Returns false past the work limit.
template <int W>
bool Ehm::build_net() {
  const int size = cluster_size_;
  keys_.clear();
  edges_.clear();
  layer_begin_.assign(2 * size, 0);  // [2p] = first node, [2p+1] = node count
  edge_begin_.assign(size, 0);
  const std::int64_t edge_limit = 16 * options_.max_nodes;
  for (int p = 0; p < size; ++p) {
    if (parent_[p] < 0) {
      if (++nodes_total_ > options_.max_nodes) return false;
      layer_begin_[2 * p] = static_cast<std::int64_t>(keys_.size() / W);
      layer_begin_[2 * p + 1] = 1;
      keys_.insert(keys_.end(), W, std::uint64_t{0});
    }
    const std::int64_t nodes = layer_begin_[2 * p + 1];
    stats_.max_layer_width = std::max(stats_.max_layer_width, static_cast<int>(nodes));
    const int choices = choice_begin_[p + 1] - choice_begin_[p];
    const int children = child_begin_[p + 1] - child_begin_[p];
    edge_begin_[p] = static_cast<std::int64_t>(edges_.size());
    if (children == 0) continue;
    const std::int64_t edge_count = nodes * choices * children;
    if (static_cast<std::int64_t>(edges_.size()) + edge_count > edge_limit) return false;
    edges_.resize(edges_.size() + static_cast<std::size_t>(edge_count));
    for (int ci = 0; ci < children; ++ci) {
      const int c = child_list_[child_begin_[p] + ci];
      const bool built = key_size_[c] <= kDirectBits ? build_child_direct<W>(p, ci) : build_child_hashed<W>(p, ci);
      if (!built) return false;
    }
  }
  stats_.edges += static_cast<std::int64_t>(edges_.size());
  return true;
}

// The layer of child slot ci of p when K(child) has at most kDirectBits bits: a direct-address
// index (key → node), no hashing or key compares; keys fit in word 0.
template <int W>
bool Ehm::build_child_direct(int p, int ci) {
  const std::int64_t first = layer_begin_[2 * p], nodes = layer_begin_[2 * p + 1];
  const int cb = choice_begin_[p], choices = choice_begin_[p + 1] - cb;
  const int children = child_begin_[p + 1] - child_begin_[p];
  const int c = child_list_[child_begin_[p] + ci];
  const int* remap = remap_bit_.data() + remap_begin_[p] + ci * key_size_[p];
  const int* sets = set_bit_.data() + set_begin_[p] + ci * choices;
  const auto child_first = static_cast<std::int32_t>(keys_.size() / W);
  std::int32_t* out = edges_.data() + edge_begin_[p] + ci;
  const std::size_t span = std::size_t{1} << key_size_[c];
  if (direct_.size() < span) direct_.resize(span, -1);
  std::uint64_t state[W];
  for (std::int64_t s = 0; s < nodes; ++s) {
    std::copy_n(keys_.data() + static_cast<std::size_t>(first + s) * W, W, state);
    std::uint64_t base0 = 0;
    for (std::uint64_t bits = state[0]; bits != 0; bits &= bits - 1) {
      const int to = remap[__builtin_ctzll(bits)];
      if (to >= 0) base0 |= std::uint64_t{1} << to;
    }
    for (int w = 1; w < W; ++w) {
      for (std::uint64_t bits = state[w]; bits != 0; bits &= bits - 1) {
        const int to = remap[w * 64 + __builtin_ctzll(bits)];
        if (to >= 0) base0 |= std::uint64_t{1} << to;
      }
    }
    for (int ch = 0; ch < choices; ++ch, out += children) {
      const int test = choice_test_[cb + ch];
      if (test >= 0 && has_bit(state, test)) {
        *out = -1;
        continue;
      }
      const std::uint64_t k0 = sets[ch] >= 0 ? base0 | (std::uint64_t{1} << sets[ch]) : base0;
      std::int32_t id = direct_[k0];
      if (id < 0) {
        if (++nodes_total_ > options_.max_nodes) {
          for (auto id2 = static_cast<std::size_t>(child_first); id2 < keys_.size() / W; ++id2) direct_[keys_[id2 * W]] = -1;
          return false;
        }
        id = static_cast<std::int32_t>(keys_.size() / W);
        direct_[k0] = id;
        keys_.push_back(k0);
        for (int w = 1; w < W; ++w) keys_.push_back(0);
      }
      *out = id;
    }
  }
  for (auto id = static_cast<std::size_t>(child_first); id < keys_.size() / W; ++id) direct_[keys_[id * W]] = -1;
  layer_begin_[2 * c] = child_first;
  layer_begin_[2 * c + 1] = static_cast<std::int64_t>(keys_.size() / W) - child_first;
  return true;
}

// The layer of child slot ci of p for wider key spaces: the hash table, a fresh generation,
// sized for about twice the parent's layer and grown as the layer fills.
template <int W>
bool Ehm::build_child_hashed(int p, int ci) {
  const std::int64_t first = layer_begin_[2 * p], nodes = layer_begin_[2 * p + 1];
  const int cb = choice_begin_[p], choices = choice_begin_[p + 1] - cb;
  const int children = child_begin_[p + 1] - child_begin_[p];
  const int c = child_list_[child_begin_[p] + ci];
  const int* remap = remap_bit_.data() + remap_begin_[p] + ci * key_size_[p];
  const int* sets = set_bit_.data() + set_begin_[p] + ci * choices;
  const auto child_first = static_cast<std::int32_t>(keys_.size() / W);
  std::int32_t* out = edges_.data() + edge_begin_[p] + ci;
  if (generation_ == UINT32_MAX) {
    for (Slot& s : slots_) s.stamp = 0;
    generation_ = 0;
  }
  ++generation_;
  std::uint64_t capacity = 16;
  while (capacity < 4 * static_cast<std::uint64_t>(nodes) && capacity < (std::uint64_t{1} << 24)) capacity *= 2;
  if (slots_.size() < capacity) slots_.resize(capacity, Slot{0, 0});
  mask_ = capacity - 1;
  std::uint64_t state[W], key[W], base[W];
  for (std::int64_t s = 0; s < nodes; ++s) {
    std::copy_n(keys_.data() + static_cast<std::size_t>(first + s) * W, W, state);
    std::fill_n(base, W, std::uint64_t{0});
    for (int w = 0; w < W; ++w) {
      for (std::uint64_t bits = state[w]; bits != 0; bits &= bits - 1) {
        const int to = remap[w * 64 + __builtin_ctzll(bits)];
        if (to >= 0) set_key_bit(base, to);
      }
    }
    for (int ch = 0; ch < choices; ++ch, out += children) {
      const int test = choice_test_[cb + ch];
      if (test >= 0 && has_bit(state, test)) {
        *out = -1;
        continue;
      }
      std::copy_n(base, W, key);
      if (sets[ch] >= 0) set_key_bit(key, sets[ch]);
      const std::int32_t id = find_or_insert<W>(key);
      if (id < 0) return false;
      *out = id;
      const auto layer_nodes = static_cast<std::uint64_t>(keys_.size() / W) - static_cast<std::uint64_t>(child_first);
      if (layer_nodes * 2 > mask_ + 1) grow_table<W>(child_first);
    }
  }
  layer_begin_[2 * c] = child_first;
  layer_begin_[2 * c + 1] = static_cast<std::int64_t>(keys_.size() / W) - child_first;
  return true;
}

// The weight of a choice is at most this: a gated ψ over the row scale is ≤ 1, the folded
// choice (the miss and the exclusive measurements) ≤ 1 + their count.
double Ehm::layer_weight_bound(int p) const {
  const int cb = choice_begin_[p], ce = choice_begin_[p + 1];
  return std::max(1.0, *std::max_element(choice_weight_.begin() + cb, choice_weight_.begin() + ce));
}

// β bottom-up (Method 3), each layer scaled to max 1. Returns Σ over layers of log(max): log Z
// of the normalised, row-scaled problem.
// Underflow: stored β's are ≤ 1 and a weight ≤ w̄ (layer_weight_bound), so a term w Π_c β_c whose
// factors carry errors ε_c is off by at most w̄ Σ_c ε_c plus one smallest subnormal per
// multiplication; a node sums `choices` terms, and the layer's scale multiplies the bound by
// 1 / max. beta_error_[p] is that bound for every node of p (infinite where the layer is all 0).
template <int W>
double Ehm::backward_pass() {
  beta_.resize(keys_.size() / W);
  beta_error_.assign(cluster_size_, 0.0);
  double log_scale_sum = 0.0;
  for (int p = cluster_size_ - 1; p >= 0; --p) {
    const std::int64_t first = layer_begin_[2 * p], nodes = layer_begin_[2 * p + 1];
    const int cb = choice_begin_[p], choices = choice_begin_[p + 1] - cb;
    const int children = child_begin_[p + 1] - child_begin_[p];
    const double* weight = choice_weight_.data() + cb;
    double largest = 0.0;
    if (children == 0) {  // a leaf: Σ of the choices its key allows
      const int* test = choice_test_.data() + cb;
      for (std::int64_t s = 0; s < nodes; ++s) {
        const std::uint64_t* node_key = keys_.data() + static_cast<std::size_t>(first + s) * W;
        double sum = 0.0;
        for (int ch = 0; ch < choices; ++ch) {
          if (test[ch] < 0 || !has_bit(node_key, test[ch])) sum += weight[ch];
        }
        beta_[first + s] = sum;
        largest = std::max(largest, sum);
      }
    } else {
      const std::int32_t* link = edges_.data() + edge_begin_[p];
      for (std::int64_t s = 0; s < nodes; ++s) {
        double sum = 0.0;
        for (int ch = 0; ch < choices; ++ch, link += children) {
          if (link[0] < 0) continue;
          double product = weight[ch];
          for (int ci = 0; ci < children; ++ci) product *= beta_[link[ci]];
          sum += product;
        }
        beta_[first + s] = sum;
        largest = std::max(largest, sum);
      }
    }
    double child_error = 0.0;
    for (int k = child_begin_[p]; k < child_begin_[p + 1]; ++k) child_error += beta_error_[child_list_[k]];
    const double raw_error = choices * (layer_weight_bound(p) * child_error + (children + 1) * kSubnormal);
    beta_error_[p] = largest > 0.0 ? raw_error / largest : kInfinity;
    if (largest > 0.0) {
      const double inverse = 1.0 / largest;
      for (std::int64_t s = 0; s < nodes; ++s) beta_[first + s] *= inverse;
      log_scale_sum += std::log(largest);
    }
  }
  return log_scale_sum;
}

// α top-down (Method 3), each child layer scaled to max 1 once complete, and every target's row.
// α's underflow bound (as β's): a child node gathers at most nodes × choices terms of the parent
// layer, each α_p w Π_{c' ≠ c} β_c' with α_p ≤ 1.
template <int W>
bool Ehm::forward_pass(MarginalTable& marginals) {
  const int size = cluster_size_;
  int widest_choices = 1, widest_children = 0;
  for (int p = 0; p < size; ++p) {
    widest_choices = std::max(widest_choices, choice_begin_[p + 1] - choice_begin_[p]);
    widest_children = std::max(widest_children, child_begin_[p + 1] - child_begin_[p]);
  }
  row_accumulator_.resize(widest_choices);
  child_beta_.resize(widest_children + 1);
  prefix_.resize(widest_children + 1);
  alpha_.assign(keys_.size() / W, 0.0);
  alpha_error_.assign(size, 0.0);
  for (int p = 0; p < size; ++p) {
    if (parent_[p] < 0) alpha_[layer_begin_[2 * p]] = 1.0;
  }
  for (int p = 0; p < size; ++p) {
    forward_layer<W>(p);
    const int children = child_begin_[p + 1] - child_begin_[p];
    const double terms = static_cast<double>(layer_begin_[2 * p + 1]) * (choice_begin_[p + 1] - choice_begin_[p]);
    double child_error = 0.0;
    for (int k = child_begin_[p]; k < child_begin_[p + 1]; ++k) child_error += beta_error_[child_list_[k]];
    for (int k = child_begin_[p]; k < child_begin_[p + 1]; ++k) {
      const int c = child_list_[k];
      const std::int64_t cf = layer_begin_[2 * c], cn = layer_begin_[2 * c + 1];
      double largest = 0.0;
      for (std::int64_t s = 0; s < cn; ++s) largest = std::max(largest, alpha_[cf + s]);
      const double raw_error =
          terms * (layer_weight_bound(p) * (alpha_error_[p] + child_error - beta_error_[c]) + (children + 1) * kSubnormal);
      alpha_error_[c] = largest > 0.0 ? raw_error / largest : kInfinity;
      if (largest > 0.0) {
        const double inverse = 1.0 / largest;
        for (std::int64_t s = 0; s < cn; ++s) alpha_[cf + s] *= inverse;
      }
    }
    if (!write_row(p, marginals)) return false;
  }
  return true;
}

// One layer of the forward pass: row_accumulator_[choice] = Σ_S α_p(S) ψ(choice) Π_c β_c(…)
// (the unnormalised row of p's target), and α_c(…) += α_p(S) ψ(choice) Π_{c' ≠ c} β_c'(…) for
// every child c. Leaves, one child (a path) and several children (products by prefix and suffix).
template <int W>
void Ehm::forward_layer(int p) {
  const std::int64_t first = layer_begin_[2 * p], nodes = layer_begin_[2 * p + 1];
  const int cb = choice_begin_[p], choices = choice_begin_[p + 1] - cb;
  const int children = child_begin_[p + 1] - child_begin_[p];
  const double* weight = choice_weight_.data() + cb;
  double* acc = row_accumulator_.data();
  std::fill_n(acc, choices, 0.0);
  if (children == 0) {
    const int* test = choice_test_.data() + cb;
    for (std::int64_t s = 0; s < nodes; ++s) {
      const double a = alpha_[first + s];
      const std::uint64_t* node_key = keys_.data() + static_cast<std::size_t>(first + s) * W;
      for (int ch = 0; ch < choices; ++ch) {
        if (test[ch] < 0 || !has_bit(node_key, test[ch])) acc[ch] += a * weight[ch];
      }
    }
  } else if (children == 1) {
    const std::int32_t* link = edges_.data() + edge_begin_[p];
    for (std::int64_t s = 0; s < nodes; ++s) {
      const double a = alpha_[first + s];
      for (int ch = 0; ch < choices; ++ch, ++link) {
        if (link[0] < 0) continue;
        const double aw = a * weight[ch];
        acc[ch] += aw * beta_[link[0]];
        alpha_[link[0]] += aw;
      }
    }
  } else {
    const std::int32_t* link = edges_.data() + edge_begin_[p];
    double* pre = prefix_.data();
    double* b = child_beta_.data();
    for (std::int64_t s = 0; s < nodes; ++s) {
      const double a = alpha_[first + s];
      for (int ch = 0; ch < choices; ++ch, link += children) {
        if (link[0] < 0) continue;
        const double aw = a * weight[ch];
        pre[0] = 1.0;
        for (int ci = 0; ci < children; ++ci) {
          b[ci] = beta_[link[ci]];
          pre[ci + 1] = pre[ci] * b[ci];
        }
        acc[ch] += aw * pre[children];
        double suffix = 1.0;
        for (int ci = children - 1; ci >= 0; --ci) {
          alpha_[link[ci]] += aw * pre[ci] * suffix;
          suffix *= b[ci];
        }
      }
    }
  }
}

// The row of p's target from row_accumulator_: choice 0 splits into the miss and the exclusive
// measurements in proportion to their weights (undoing the row scale).
// Refused (false) where a product of this cluster's net has underflowed (the processor's flag)
// and the row's sum is not 1e12 times what underflow can have taken from it (the layer's nodes
// × (α's and the children's β's bounds, weighted, plus a subnormal a product)), so every
// probability written is within 1e-12 of the row computed without underflow. The bounds are
// loose (every product is charged a loss); without underflow there is no loss to bound.
bool Ehm::write_row(int p, MarginalTable& marginals) {
  const int choices = choice_begin_[p + 1] - choice_begin_[p];
  const double* acc = row_accumulator_.data();
  const int li = order_[p];
  const int t = targets_[li];
  double sum = 0.0;
  for (int ch = 0; ch < choices; ++ch) sum += acc[ch];
  const int children = child_begin_[p + 1] - child_begin_[p];
  double error = alpha_error_[p];
  for (int k = child_begin_[p]; k < child_begin_[p + 1]; ++k) error += beta_error_[child_list_[k]];
  const double row_error = static_cast<double>(layer_begin_[2 * p + 1]) * choices *
                           (layer_weight_bound(p) * error + (children + 1) * kSubnormal);
  if (!std::isfinite(sum) || (std::fetestexcept(FE_UNDERFLOW) && !(sum > 1e12 * row_error))) return false;
  const double inverse = 1.0 / sum;
  double* row = marginals.row(t);
  const double stay = acc[0] * inverse / stay_weight_[li];
  row[0] = stay / row_scale_[li];
  if (exclusive_sum_[li] > 0.0) {
    for (int e = graph_.row_begin(t); e < graph_.row_end(t); ++e) {
      const int j = graph_.edge_measurement(e);
      if (graph_.measurement_degree(j) < 2) row[j + 1] = stay * (graph_.edge_weight(e) / row_scale_[li]);
    }
  }
  for (int g = gate_begin_[li], ch = 1; g < gate_begin_[li + 1]; ++g, ++ch) {
    row[graph_.edge_measurement(gate_edge_[g]) + 1] = acc[ch] * inverse;
  }
  return true;
}

DABENCH_REGISTER_SINGLE_SCAN(Ehm);

}  // namespace dabench
