// The net of one EHM cluster (ehm.hpp, Methods 2-3): its layers of used-measurement keys, built
// top-down through a direct-address index or a hash table, and the backward (β) and forward (α)
// passes that give the targets' rows.
#include <algorithm>
#include <cfenv>
#include <climits>
#include <cmath>
#include <limits>

#include "algorithms/single_scan/ehm.hpp"
#include "harness/core/special_values.hpp"

namespace dabench {

namespace {

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

// Hash table of the layer being built: slots hold node ids; a slot is live only if its stamp is
// the current generation, so starting a new layer costs nothing.

template <int W>
std::int32_t Ehm::find_or_insert(const std::uint64_t* key) {
  std::uint64_t h = hash_key<W>(key) & mask_;
  while (true) {
    Slot& slot = slots_[h];
    if (slot.stamp != generation_) {
      ++nodes_total_;
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

// The net (header, Method 2-3): build_net lays out the layers top-down, backward_pass computes β
// bottom-up, forward_pass computes α top-down and the targets' rows with it.

template <int W>
const char* Ehm::run_net(MarginalTable& marginals) {
  build_net<W>();
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
// Its size is within the bound checked before (net_bound), so nothing here counts against a limit.
template <int W>
void Ehm::build_net() {
  const int size = cluster_size_;
  keys_.clear();
  edges_.clear();
  layer_begin_.assign(2 * size, 0);  // [2p] = first node, [2p+1] = node count
  edge_begin_.assign(size, 0);
  for (int p = 0; p < size; ++p) {
    if (parent_[p] < 0) {
      ++nodes_total_;
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
    edges_.resize(edges_.size() + static_cast<std::size_t>(edge_count));
    for (int ci = 0; ci < children; ++ci) {
      const int c = child_list_[child_begin_[p] + ci];
      if (key_size_[c] <= kDirectBits) {
        build_child_direct<W>(p, ci);
      } else {
        build_child_hashed<W>(p, ci);
      }
    }
  }
  stats_.edges += static_cast<std::int64_t>(edges_.size());
}

// The layer of child slot ci of p when K(child) has at most kDirectBits bits: a direct-address
// index (key → node), no hashing or key compares; keys fit in word 0.
template <int W>
void Ehm::build_child_direct(int p, int ci) {
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
        ++nodes_total_;
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
}

// The layer of child slot ci of p for wider key spaces: the hash table, a fresh generation,
// sized for about twice the parent's layer and grown as the layer fills.
template <int W>
void Ehm::build_child_hashed(int p, int ci) {
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
      *out = find_or_insert<W>(key);
      const auto layer_nodes = static_cast<std::uint64_t>(keys_.size() / W) - static_cast<std::uint64_t>(child_first);
      if (layer_nodes * 2 > mask_ + 1) grow_table<W>(child_first);
    }
  }
  layer_begin_[2 * c] = child_first;
  layer_begin_[2 * c + 1] = static_cast<std::int64_t>(keys_.size() / W) - child_first;
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
  // (A target that must be detected, without exclusive measurements, has no stay choice.)
  const double stay = stay_weight_[li] > 0.0 ? acc[0] * inverse / stay_weight_[li] : 0.0;
  row[0] = must_detect_[t] ? 0.0 : stay / row_scale_[li];
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

// The key widths solve_cluster dispatches to (ehm.cpp).
template const char* Ehm::run_net<1>(MarginalTable&);
template const char* Ehm::run_net<2>(MarginalTable&);
template const char* Ehm::run_net<4>(MarginalTable&);
template const char* Ehm::run_net<Ehm::kMaxKeyWords>(MarginalTable&);

}  // namespace dabench
