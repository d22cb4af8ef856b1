#include "algorithms/single_scan/correlation_decay.hpp"

#include <algorithm>

#include "harness/single_scan/registry.hpp"

namespace dabench {

std::string CorrelationDecayOptions::validate() const {
  if (depth < 1) return "depth must be >= 1";
  if (budget < 1) return "budget must be >= 1";
  if (memo_entries < 0) return "memo_entries must be >= 0";
  return {};
}

namespace {

// Memo entries are kept only where a second walk can reach the same state (see the header).
constexpr int kMemoMinLevel = 3;  // nodes removed before the node
constexpr int kMemoMinDepth = 2;  // remaining (clamped) depth t
constexpr std::size_t kMemoInitialCapacity = 1024;

inline std::uint64_t hash_key(const std::uint64_t* key, int words, std::uint64_t tag) {
  std::uint64_t h = tag * 0x9E3779B97F4A7C15ull;
  for (int w = 0; w < words; ++w) {
    h = (h ^ key[w]) * 0xBF58476D1CE4E5B9ull;
    h ^= h >> 31;
  }
  h ^= h >> 29;
  h *= 0x94D049BB133111EBull;
  h ^= h >> 32;
  return h;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Memo table.

void CorrelationDecay::Memo::reset(int words, std::int64_t max_entries) {
  max_entries_ = static_cast<std::size_t>(max_entries);
  if (words != words_) {
    words_ = words;
    extra_.assign(slots_.size() * static_cast<std::size_t>(words_ - 1), 0);
    for (Slot& slot : slots_) slot.stamp = 0;
    generation_ = 0;
  }
  if (++generation_ == 0) {  // the stamp wrapped: clear once, then start over
    for (Slot& slot : slots_) slot.stamp = 0;
    generation_ = 1;
  }
  size_ = 0;
}

bool CorrelationDecay::Memo::same_key(std::size_t slot, const std::uint64_t* key, std::uint64_t tag) const {
  if (slots_[slot].tag != tag || slots_[slot].key0 != key[0]) return false;
  const std::uint64_t* stored = extra_.data() + slot * static_cast<std::size_t>(words_ - 1);
  for (int w = 1; w < words_; ++w) {
    if (stored[w - 1] != key[w]) return false;
  }
  return true;
}

const double* CorrelationDecay::Memo::find(const std::uint64_t* key, std::uint64_t tag, std::uint64_t hash) const {
  if (slots_.empty()) return nullptr;
  for (std::size_t slot = hash & mask_;; slot = (slot + 1) & mask_) {
    if (slots_[slot].stamp != generation_) return nullptr;
    if (same_key(slot, key, tag)) return &slots_[slot].value;
  }
}

void CorrelationDecay::Memo::insert(const std::uint64_t* key, std::uint64_t tag, std::uint64_t hash, double value) {
  if (size_ >= max_entries_) return;  // full: stop memoising (still correct, only slower)
  if (2 * (size_ + 1) > slots_.size()) grow();
  std::size_t slot = hash & mask_;
  while (slots_[slot].stamp == generation_) slot = (slot + 1) & mask_;
  slots_[slot] = Slot{key[0], tag, value, generation_};
  std::copy(key + 1, key + words_, extra_.begin() + static_cast<std::ptrdiff_t>(slot * static_cast<std::size_t>(words_ - 1)));
  ++size_;
}

void CorrelationDecay::Memo::grow() {
  const std::size_t capacity = slots_.empty() ? kMemoInitialCapacity : 2 * slots_.size();
  std::vector<Slot> old_slots(capacity, Slot{});
  std::vector<std::uint64_t> old_extra(capacity * static_cast<std::size_t>(words_ - 1));
  old_slots.swap(slots_);
  old_extra.swap(extra_);
  mask_ = capacity - 1;
  const std::uint32_t live = generation_;
  generation_ = 1;
  size_ = 0;
  std::vector<std::uint64_t> key(static_cast<std::size_t>(words_));
  for (std::size_t slot = 0; slot < old_slots.size(); ++slot) {
    if (old_slots[slot].stamp != live) continue;
    key[0] = old_slots[slot].key0;
    std::copy_n(old_extra.begin() + static_cast<std::ptrdiff_t>(slot * static_cast<std::size_t>(words_ - 1)), words_ - 1, key.begin() + 1);
    insert(key.data(), old_slots[slot].tag, hash_key(key.data(), words_, old_slots[slot].tag), old_slots[slot].value);
  }
}

// ---------------------------------------------------------------------------------------------
// The recursion.

// Φ(·, ·, node, 1) = 1/(1 + Σ ψ over the node's neighbours still present), i.e. (40)/(41) with
// the children's Φ(·, ·, ·, 0) = 1 (ψ·1 is ψ exactly, as a call would give). A node alone in
// what remains gets 1/(1 + 0) = 1, the same bits as the clamp to t = 0 in phi().
template <bool kWide>
double CorrelationDecay::phi_one(int node) const {
  double s = 1.0;
  const int end = adj_begin_[node + 1];
  for (int k = adj_begin_[node]; k < end; ++k) {
    const int u = adj_node_[k];
    const std::uint64_t word = kWide ? removed_words_[u >> 6] : removed_;
    if (!((word >> (u & 63)) & 1u)) s += adj_weight_[k];
  }
  return 1.0 / s;
}

// Φ of local node `node` with `level` nodes already removed (the walk from the root, held in
// the removed set) and remaining depth t ≥ 1: eq (40) for a target, eq (41) for a measurement
// (the same expression on the bipartite adjacency).
template <bool kWide>
double CorrelationDecay::phi(int node, int t, int level) {
  if (++calls_ > options_.budget) return 1.0;  // abandoned: solve() reports skipped:budget
  // Exact for t ≥ |G| − 1 with identical operations (header): clamp.
  t = std::min(t, nodes_ - 1 - level);
  if (t <= 0) return 1.0;  // node alone in what remains: Φ = 1/(1 + 0)
  if (t == 1) return phi_one<kWide>(node);

  const std::uint64_t* key = kWide ? removed_words_.data() : &removed_;
  const bool memoise = use_memo_ && level >= kMemoMinLevel && t >= kMemoMinDepth;
  std::uint64_t tag = 0;
  std::uint64_t hash = 0;
  if (memoise) {
    tag = (static_cast<std::uint64_t>(node) << 32) | static_cast<std::uint32_t>(t);
    hash = hash_key(key, words_, tag);
    if (const double* hit = memo_.find(key, tag, hash)) {
      ++memo_hits_;
      return *hit;
    }
  }

  const std::uint64_t bit = std::uint64_t{1} << (node & 63);
  if constexpr (kWide) removed_words_[node >> 6] |= bit; else removed_ |= bit;
  double s = 1.0;
  const int end = adj_begin_[node + 1];
  for (int k = adj_begin_[node]; k < end; ++k) {
    const int u = adj_node_[k];
    const std::uint64_t word = kWide ? removed_words_[u >> 6] : removed_;
    if ((word >> (u & 63)) & 1u) continue;  // already on the walk: self-avoiding
    if (t == 2) {
      ++calls_;  // the child's evaluation at t = 1, done here without a call
      s += adj_weight_[k] * phi_one<kWide>(u);
    } else {
      s += adj_weight_[k] * phi<kWide>(u, t - 1, level + 1);
    }
  }
  if constexpr (kWide) removed_words_[node >> 6] &= ~bit; else removed_ &= ~bit;

  const double value = 1.0 / s;
  if (memoise && calls_ <= options_.budget) memo_.insert(key, tag, hash, value);
  return value;
}

void CorrelationDecay::build_cluster(int first, int last) {
  cluster_targets_ = last - first;
  cluster_target_.assign(graph_.cluster_targets().begin() + first, graph_.cluster_targets().begin() + last);
  cluster_measurement_.clear();
  int edges = 0;
  for (const int i : cluster_target_) {
    for (int e = graph_.row_begin(i); e < graph_.row_end(i); ++e) {
      const int j = graph_.edge_measurement(e);
      if (local_of_measurement_[j] < 0) {
        local_of_measurement_[j] = cluster_targets_ + static_cast<int>(cluster_measurement_.size());
        cluster_measurement_.push_back(j);
      }
      ++edges;
    }
  }
  nodes_ = cluster_targets_ + static_cast<int>(cluster_measurement_.size());

  // CSR over local nodes: a target's edges in increasing measurement order (the graph's
  // order), a measurement's in increasing target order (targets are visited in that order).
  adj_begin_.assign(nodes_ + 1, 0);
  for (int a = 0; a < cluster_targets_; ++a) {
    const int i = cluster_target_[a];
    adj_begin_[a + 1] = graph_.row_end(i) - graph_.row_begin(i);
    for (int e = graph_.row_begin(i); e < graph_.row_end(i); ++e) ++adj_begin_[local_of_measurement_[graph_.edge_measurement(e)] + 1];
  }
  for (int v = 0; v < nodes_; ++v) adj_begin_[v + 1] += adj_begin_[v];
  adj_node_.resize(2 * static_cast<std::size_t>(edges));
  adj_weight_.resize(2 * static_cast<std::size_t>(edges));
  fill_.assign(adj_begin_.begin(), adj_begin_.end() - 1);
  for (int a = 0; a < cluster_targets_; ++a) {
    const int i = cluster_target_[a];
    for (int e = graph_.row_begin(i); e < graph_.row_end(i); ++e) {
      const int b = local_of_measurement_[graph_.edge_measurement(e)];
      const double w = graph_.edge_weight(e);
      adj_node_[fill_[a]] = b;
      adj_weight_[fill_[a]++] = w;
      adj_node_[fill_[b]] = a;
      adj_weight_[fill_[b]++] = w;
    }
  }
  for (const int j : cluster_measurement_) local_of_measurement_[j] = -1;  // ready for the next cluster
}

// Marginals of every target of the current cluster (header: p_i0 = 1/s_i, p_ij = ψ_i(j)Φ_j/s_i).
template <bool kWide>
void CorrelationDecay::solve_cluster(MarginalTable& marginals) {
  words_ = kWide ? (nodes_ + 63) / 64 : 1;
  if constexpr (kWide) removed_words_.assign(words_, 0); else removed_ = 0;
  if (use_memo_) memo_.reset(words_, options_.memo_entries);
  const int t = std::min(options_.depth, nodes_ - 1);  // the root's clamp (see phi)
  for (int a = 0; a < cluster_targets_; ++a) {
    const int begin = adj_begin_[a];
    const int end = adj_begin_[a + 1];
    root_terms_.resize(static_cast<std::size_t>(end - begin));
    ++calls_;  // the root's own evaluation of (40)
    const std::uint64_t bit = std::uint64_t{1} << (a & 63);
    if constexpr (kWide) removed_words_[a >> 6] |= bit; else removed_ |= bit;
    double s = 1.0;
    for (int k = begin; k < end; ++k) {
      const double term = t == 1 ? adj_weight_[k] : adj_weight_[k] * phi<kWide>(adj_node_[k], t - 1, 1);
      root_terms_[k - begin] = term;
      s += term;
    }
    if constexpr (kWide) removed_words_[a >> 6] &= ~bit; else removed_ &= ~bit;
    if (calls_ > options_.budget) return;

    double* row = marginals.row(cluster_target_[a]);
    row[0] = 1.0 / s;
    for (int k = begin; k < end; ++k) row[cluster_measurement_[adj_node_[k] - cluster_targets_] + 1] = root_terms_[k - begin] / s;
  }
}

void CorrelationDecay::solve(const SingleScanProblem& problem, MarginalTable& marginals, SolveReport& report) {
  report.reset();
  graph_.build(problem);
  graph_.find_clusters();
  marginals.reshape_zero(graph_.targets(), graph_.measurements());
  local_of_measurement_.assign(graph_.measurements(), -1);
  use_memo_ = options_.memo && options_.memo_entries > 0;
  calls_ = 0;
  memo_hits_ = 0;
  for (int c = 0; c < graph_.clusters(); ++c) {
    build_cluster(graph_.cluster_start(c), graph_.cluster_start(c + 1));
    if (nodes_ <= 64) solve_cluster<false>(marginals); else solve_cluster<true>(marginals);
    if (calls_ > options_.budget) {
      report.skipped = "budget";
      return;
    }
  }
}

DABENCH_REGISTER_SINGLE_SCAN_ALGORITHM(CorrelationDecay);

}  // namespace dabench
