#include "algorithms/single_scan/junction_tree.hpp"

#include <algorithm>
#include <bit>
#include <cfenv>
#include <cmath>
#include <new>

#include "harness/single_scan/registry.hpp"

namespace dabench {

std::string JtOptions::validate() const {
  if (!(threshold >= 0.0) || !std::isfinite(threshold)) return "threshold must be finite and >= 0";
  if (threshold_on < 0 || threshold_on > 3) return "threshold_on must be 0, 1, 2 or 3";
  if (memory_mb < 1 || memory_mb > (std::int64_t{1} << 40)) return "memory_mb must be in [1, 2^40]";
  return {};
}

namespace {

constexpr std::uint64_t kSaturated = std::numeric_limits<std::uint64_t>::max();

inline std::uint64_t saturating_multiply(std::uint64_t a, std::uint64_t b) {
  std::uint64_t product = 0;
  return __builtin_mul_overflow(a, b, &product) ? kSaturated : product;
}
inline std::uint64_t saturating_add(std::uint64_t a, std::uint64_t b) {
  std::uint64_t sum = 0;
  return __builtin_add_overflow(a, b, &sum) ? kSaturated : sum;
}

// Calls f(bit) for each set bit of a bitset of `words` words, in increasing order.
template <class F>
inline void for_each_bit(const std::uint64_t* bits, int words, F&& f) {
  for (int w = 0; w < words; ++w) {
    std::uint64_t word = bits[w];
    while (word != 0) {
      f(w * 64 + std::countr_zero(word));
      word &= word - 1;
    }
  }
}

inline void set_bit(std::uint64_t* bits, int b) { bits[b >> 6] |= std::uint64_t{1} << (b & 63); }
inline void clear_bit(std::uint64_t* bits, int b) { bits[b >> 6] &= ~(std::uint64_t{1} << (b & 63)); }
inline bool test_bit(const std::uint64_t* bits, int b) { return (bits[b >> 6] >> (b & 63)) & 1; }

// Below this a clique table entry risks losing precision to subnormals: recompute in logs.
constexpr double kTiny = 1e-250;
// Below this a collected separator entry (scaled to max 1) may have lost more than 1e-12 of its
// parts to underflow (each part under 2^-1074): the distribute pass's ratio would multiply the loss.
constexpr double kSeparatorFloor = 1e-290;

}  // namespace

// ---------------------------------------------------------------------------------------------
// Triangulation and clique tree.

void JunctionTreeBuilder::reset(int vars, const int* domain) {
  vars_ = vars;
  words_ = (vars + 63) / 64;
  domain_.assign(domain, domain + vars);
  adjacency_.assign(static_cast<std::size_t>(vars) * words_, 0);
}

void JunctionTreeBuilder::add_edge(int a, int b) {
  set_bit(row(adjacency_, a), b);
  set_bit(row(adjacency_, b), a);
}

bool JunctionTreeBuilder::eliminate(EliminationRule rule, std::uint64_t max_clique_entries) {
  const int n = vars_;
  const int words = words_;
  work_.assign(adjacency_.begin(), adjacency_.end());  // elimination leaves the graph intact
  candidate_cliques_.assign(static_cast<std::size_t>(n) * words, 0);
  alive_.assign(words, 0);
  for (int v = 0; v < n; ++v) set_bit(alive_.data(), v);
  candidate_order_.clear();
  const bool by_fill = rule == EliminationRule::min_fill || rule == EliminationRule::min_fill_by_index;

  for (int step = 0; step < n; ++step) {
    int best = -1;
    std::int64_t best_fill = 0;
    std::uint64_t best_weight = 0, best_weighted_fill = 0;
    for_each_bit(alive_.data(), words, [&](int v) {
      const std::uint64_t* nb = row(work_, v);
      std::int64_t twice_fill = 0;  // each missing neighbour pair counted from both ends
      std::uint64_t twice_weighted_fill = 0;
      std::uint64_t weight = static_cast<std::uint64_t>(domain_[v]);  // Π domain of the clique formed
      bool worse = false;
      for_each_bit(nb, words, [&](int u) {
        if (worse) return;
        weight = saturating_multiply(weight, static_cast<std::uint64_t>(domain_[u]));
        const std::uint64_t* nu = row(work_, u);
        int missing = 0;
        for (int w = 0; w < words; ++w) missing += std::popcount(nb[w] & ~nu[w]);
        twice_fill += missing - 1;  // u itself is in nb but not in nu
        if (rule == EliminationRule::weighted_min_fill) {
          std::uint64_t partners = 0;  // Σ domain over the neighbours u is not yet joined to
          for_each_bit(nb, words, [&](int x) {
            if (x != u && !test_bit(nu, x)) partners += static_cast<std::uint64_t>(domain_[x]);
          });
          twice_weighted_fill =
              saturating_add(twice_weighted_fill, saturating_multiply(partners, static_cast<std::uint64_t>(domain_[u])));
        }
        if (by_fill && best >= 0 && twice_fill > 2 * best_fill) worse = true;
      });
      if (worse) return;
      const std::int64_t fill = twice_fill / 2;
      const std::uint64_t weighted_fill = twice_weighted_fill / 2;
      bool better = best < 0;
      if (!better) {
        switch (rule) {
          case EliminationRule::min_fill:
            better = fill < best_fill || (fill == best_fill && weight < best_weight);
            break;
          case EliminationRule::min_fill_by_index:
            better = fill < best_fill;
            break;
          case EliminationRule::min_weight:
            better = weight < best_weight;
            break;
          case EliminationRule::weighted_min_fill:
            better = weighted_fill < best_weighted_fill || (weighted_fill == best_weighted_fill && weight < best_weight);
            break;
        }
      }
      if (better) {
        best = v;
        best_fill = fill;
        best_weight = weight;
        best_weighted_fill = weighted_fill;
      }
    });
    if (best_weight > max_clique_entries) return false;
    std::uint64_t* nb = row(work_, best);
    std::uint64_t* clique = row(candidate_cliques_, step);
    for (int w = 0; w < words; ++w) clique[w] = nb[w];
    set_bit(clique, best);
    for_each_bit(nb, words, [&](int u) {
      std::uint64_t* nu = row(work_, u);
      for (int w = 0; w < words; ++w) nu[w] |= nb[w];
      clear_bit(nu, u);
      clear_bit(nu, best);
    });
    for (int w = 0; w < words; ++w) nb[w] = 0;
    clear_bit(alive_.data(), best);
    candidate_order_.push_back(best);
  }
  return true;
}

std::uint64_t JunctionTreeBuilder::find_maximal_cliques() {
  // An elimination clique is contained only in earlier ones (the later ones lack its
  // eliminated variable).
  const int n = vars_;
  const int words = words_;
  candidate_maximal_.clear();
  std::uint64_t total = 0;
  for (int t = 0; t < n; ++t) {
    const std::uint64_t* ct = row(candidate_cliques_, t);
    bool contained = false;
    for (int s = 0; s < t && !contained; ++s) {
      const std::uint64_t* cs = row(candidate_cliques_, s);
      bool subset = true;
      for (int w = 0; w < words && subset; ++w) subset = (ct[w] & ~cs[w]) == 0;
      contained = subset;
    }
    if (contained) continue;
    candidate_maximal_.push_back(t);
    std::uint64_t entries = 1;
    for_each_bit(ct, words, [&](int v) { entries = saturating_multiply(entries, static_cast<std::uint64_t>(domain_[v])); });
    total = saturating_add(total, entries);
  }
  return total;
}

bool JunctionTreeBuilder::build(std::uint64_t max_total_entries) {
  const int words = words_;
  clique_begin_.assign(1, 0);
  clique_vars_.clear();
  parent_.clear();
  clique_entries_.clear();

  // 1-2. Elimination orders by each rule in turn (the later ones only for large tables); keep
  // the one whose maximal cliques have the fewest entries in all.
  constexpr EliminationRule kRules[] = {EliminationRule::min_fill, EliminationRule::min_fill_by_index,
                                        EliminationRule::min_weight, EliminationRule::weighted_min_fill};
  bool found = false;
  total_clique_entries_ = kSaturated;
  for (const EliminationRule rule : kRules) {
    if (found && total_clique_entries_ <= kTryOtherRulesAbove) break;
    const std::uint64_t bound = std::min(max_total_entries, total_clique_entries_);
    if (!eliminate(rule, bound)) continue;
    const std::uint64_t total = find_maximal_cliques();
    if (total > bound || (found && total >= total_clique_entries_)) continue;
    found = true;
    total_clique_entries_ = total;
    rule_ = rule;
    elim_cliques_.swap(candidate_cliques_);
    elimination_order_.swap(candidate_order_);
    maximal_.swap(candidate_maximal_);
  }
  if (!found) return false;

  // 3. Maximum-weight spanning tree (Prim from the first maximal clique; ties to the lowest
  // index), weight = shared variables. Cliques are renumbered in the order Prim adds them.
  const int q = static_cast<int>(maximal_.size());
  key_.assign(q, -1);
  key_parent_.assign(q, -1);
  new_index_.assign(q, -1);
  in_tree_.assign(q, 0);
  for (int added = 0; added < q; ++added) {
    int pick = 0;
    if (added > 0) {
      pick = -1;
      for (int a = 0; a < q; ++a) {
        if (!in_tree_[a] && (pick < 0 || key_[a] > key_[pick])) pick = a;
      }
    }
    in_tree_[pick] = 1;
    new_index_[pick] = added;
    parent_.push_back(added == 0 ? -1 : new_index_[key_parent_[pick]]);
    const std::uint64_t* cp = row(elim_cliques_, maximal_[pick]);
    std::uint64_t entries = 1;
    for_each_bit(cp, words, [&](int v) {
      clique_vars_.push_back(v);
      entries = saturating_multiply(entries, static_cast<std::uint64_t>(domain_[v]));
    });
    clique_begin_.push_back(static_cast<int>(clique_vars_.size()));
    clique_entries_.push_back(entries);
    for (int a = 0; a < q; ++a) {
      if (in_tree_[a]) continue;
      const std::uint64_t* ca = row(elim_cliques_, maximal_[a]);
      int shared = 0;
      for (int w = 0; w < words; ++w) shared += std::popcount(cp[w] & ca[w]);
      if (shared > key_[a]) {
        key_[a] = shared;
        key_parent_[a] = pick;
      }
    }
  }
  return true;
}

// ---------------------------------------------------------------------------------------------
// The solver.

void JunctionTree::log_multiply(double factor) {
  int exponent = 0;
  log_mantissa_ *= std::frexp(factor, &exponent);  // factor ∈ [0.5, 1) · 2^exponent
  log_exponent_ += exponent;
  if (log_mantissa_ < 1e-200) {
    log_mantissa_ = std::frexp(log_mantissa_, &exponent);
    log_exponent_ += exponent;
  }
}

// Depth-first walk over the consistent configurations of the clique set up by setup_pass():
// level `level` down to 0 (level 0 has stride 1), skipping a measurement another level already
// took. Keeps the table index, one index per channel (separator tables) and the product (or
// log sum) of the level potentials; calls leaf(index, channel indexes, weight) at level 0.
template <JunctionTree::Weights kWeights, class Leaf>
void JunctionTree::walk(int level, std::size_t index, const std::size_t* in, double weight, Leaf& leaf) {
  const int domain = level_domain_[level];
  const int* measurement = level_measurement_[level];
  const double* potential = level_potential_[level];
  const std::size_t stride = level_stride_[level];
  const int channels = channels_;
  const std::size_t* channel_stride = level_channel_stride_.data() + static_cast<std::size_t>(level) * channels;
  std::size_t* out = channel_index_.data() + static_cast<std::size_t>(level) * channels;
  for (int s = 0; s < domain; ++s) {
    if (s > 0 && used_[measurement[s]]) continue;
    for (int ch = 0; ch < channels; ++ch) out[ch] = in[ch] + static_cast<std::size_t>(s) * channel_stride[ch];
    state_[level] = s;
    double w = 0.0;
    if constexpr (kWeights == Weights::product) w = weight * potential[s];
    if constexpr (kWeights == Weights::log_sum) w = weight + potential[s];
    if (level == 0) {
      leaf(index + static_cast<std::size_t>(s), out, w);
    } else {
      if (s > 0) used_[measurement[s]] = 1;
      walk<kWeights>(level - 1, index + static_cast<std::size_t>(s) * stride, out, w, leaf);
      if (s > 0) used_[measurement[s]] = 0;
    }
  }
}

// Channels: collect = [children's separators..., own parent separator]; distribute = [own
// parent separator, children's scratch...]. Level potentials are the node potentials of the
// variables this clique owns (collect) and 1 elsewhere.
void JunctionTree::setup_pass(int clique, bool collect) {
  const int levels = builder_.clique_size(clique);
  const int* vars = builder_.clique_vars(clique);
  const int base = level_base_[clique];
  const int child_count = children_begin_[clique + 1] - children_begin_[clique];
  const bool has_parent = clique > 0;
  channels_ = child_count + (has_parent ? 1 : 0);
  level_domain_.resize(levels);
  level_measurement_.resize(levels);
  level_potential_.resize(levels);
  level_stride_.resize(levels);
  state_.resize(levels);
  level_channel_stride_.resize(static_cast<std::size_t>(levels) * channels_);
  channel_index_.assign(static_cast<std::size_t>(levels + 1) * channels_, 0);
  channel_table_.resize(channels_);
  const int parent_channel = collect ? child_count : 0;
  const int first_child_channel = collect || !has_parent ? 0 : 1;
  for (int l = 0; l < levels; ++l) {
    const int v = vars[l];
    level_domain_[l] = domain_[v];
    level_measurement_[l] = state_measurement_.data() + state_begin_[v];
    const bool owns = owner_clique_[v] == clique;
    level_potential_[l] = owns ? state_potential_.data() + state_begin_[v] : ones_.data();
    level_stride_[l] = level_stride_all_[base + l];
    std::size_t* cs = level_channel_stride_.data() + static_cast<std::size_t>(l) * channels_;
    if (has_parent) cs[parent_channel] = child_side_stride_[base + l];
    for (int k = 0; k < child_count; ++k) {
      const int child = children_[children_begin_[clique] + k];
      cs[first_child_channel + k] = parent_side_stride_[parent_side_begin_[child] + l];
    }
  }
  if (has_parent) channel_table_[parent_channel] = pool_.get() + separator_offset_[clique];
  std::size_t scratch = scratch_offset_;
  for (int k = 0; k < child_count; ++k) {
    const int child = children_[children_begin_[clique] + k];
    if (collect) {
      channel_table_[first_child_channel + k] = pool_.get() + separator_offset_[child];
    } else {
      channel_table_[first_child_channel + k] = pool_.get() + scratch;
      scratch += separator_size_[child];
    }
  }
}

void JunctionTree::collect(int clique) {
  setup_pass(clique, true);
  const int levels = builder_.clique_size(clique);
  const int child_count = channels_ - (clique > 0 ? 1 : 0);
  double* table = pool_.get() + clique_offset_[clique];
  double* up = clique > 0 ? channel_table_[child_count] : nullptr;
  const std::size_t up_size = clique > 0 ? separator_size_[clique] : 0;
  if (up != nullptr) std::fill(up, up + up_size, 0.0);
  double* const* messages = channel_table_.data();
  double largest = 0.0;
  double total = 0.0;
  auto leaf = [&](std::size_t index, const std::size_t* channel, double weight) {
    double t = weight;
    for (int k = 0; k < child_count; ++k) t *= messages[k][channel[k]];
    table[index] = t;
    if (up != nullptr) up[channel[child_count]] += t;
    largest = std::max(largest, t);
    total += t;
  };
  std::feclearexcept(FE_UNDERFLOW);
  walk<Weights::product>(levels - 1, 0, channel_index_.data() + static_cast<std::size_t>(levels) * channels_, 1.0, leaf);
  // A product that underflowed may hold mass that the distribute pass scales back up: redo the
  // clique relative to its largest entry.
  if (largest < kTiny || std::fetestexcept(FE_UNDERFLOW)) {
    collect_log_domain(clique);
    return;
  }
  if (up == nullptr) {
    log_multiply(total);
    return;
  }
  const double scale = *std::max_element(up, up + up_size);  // > 0: some t > 0 reached it
  const double inverse = 1.0 / scale;
  for (std::size_t s = 0; s < up_size; ++s) up[s] *= inverse;
  log_multiply(scale);
}

// The same clique in the log domain (rare: only when the product of potentials and messages
// falls below kTiny): pass 1 stores log t and finds its maximum, pass 2 exponentiates relative
// to it and sums into the parent's separator.
void JunctionTree::collect_log_domain(int clique) {
  if (!have_log_potential_) {
    state_log_potential_.resize(state_potential_.size());
    for (std::size_t k = 0; k < state_potential_.size(); ++k) state_log_potential_[k] = std::log(state_potential_[k]);
    have_log_potential_ = true;
  }
  setup_pass(clique, true);
  const int levels = builder_.clique_size(clique);
  for (int l = 0; l < levels; ++l) {
    const int v = builder_.clique_vars(clique)[l];
    level_potential_[l] = owner_clique_[v] == clique ? state_log_potential_.data() + state_begin_[v] : zeros_.data();
  }
  const int child_count = channels_ - (clique > 0 ? 1 : 0);
  double* table = pool_.get() + clique_offset_[clique];
  double* up = clique > 0 ? channel_table_[child_count] : nullptr;
  const std::size_t up_size = clique > 0 ? separator_size_[clique] : 0;
  double* const* messages = channel_table_.data();
  const std::size_t* start = channel_index_.data() + static_cast<std::size_t>(levels) * channels_;
  double shift = -std::numeric_limits<double>::infinity();
  auto log_leaf = [&](std::size_t index, const std::size_t* channel, double log_weight) {
    double lt = log_weight;
    for (int k = 0; k < child_count; ++k) lt += std::log(messages[k][channel[k]]);
    table[index] = lt;
    shift = std::max(shift, lt);
  };
  walk<Weights::log_sum>(levels - 1, 0, start, 0.0, log_leaf);
  if (!std::isfinite(shift)) shift = 0.0;
  if (up != nullptr) std::fill(up, up + up_size, 0.0);
  double total = 0.0;
  auto exp_leaf = [&](std::size_t index, const std::size_t* channel, double) {
    const double t = std::exp(table[index] - shift);
    table[index] = t;
    if (up != nullptr) up[channel[child_count]] += t;
    total += t;
  };
  walk<Weights::none>(levels - 1, 0, start, 0.0, exp_leaf);
  log_extra_ += shift;
  if (up == nullptr) {
    log_multiply(total);
    return;
  }
  const double scale = *std::max_element(up, up + up_size);
  const double inverse = 1.0 / scale;
  for (std::size_t s = 0; s < up_size; ++s) up[s] *= inverse;
  log_multiply(scale);
}

void JunctionTree::distribute(int clique) {
  setup_pass(clique, false);
  const int levels = builder_.clique_size(clique);
  const bool has_parent = clique > 0;
  const int first_child = has_parent ? 1 : 0;
  const int child_count = channels_ - first_child;
  for (int k = 0; k < child_count; ++k) {
    const int child = children_[children_begin_[clique] + k];
    std::fill(channel_table_[first_child + k], channel_table_[first_child + k] + separator_size_[child], 0.0);
  }
  const double* table = pool_.get() + clique_offset_[clique];
  const double* ratio = has_parent ? channel_table_[0] : nullptr;
  double* const* down = channel_table_.data() + first_child;
  const int owned_begin = owned_begin_[clique];
  const int owned_end = owned_begin_[clique + 1];
  const int* owned_var = owned_var_.data();
  const int* owner_level = owner_level_.data();
  const int* state_begin = state_begin_.data();
  const int* state = state_.data();
  double* marginal = marginal_.data();
  auto leaf = [&](std::size_t index, const std::size_t* channel, double) {
    double t = table[index];
    if (ratio != nullptr) t *= ratio[channel[0]];
    for (int k = 0; k < child_count; ++k) down[k][channel[first_child + k]] += t;
    for (int o = owned_begin; o < owned_end; ++o) {
      const int v = owned_var[o];
      marginal[state_begin[v] + state[owner_level[v]]] += t;
    }
  };
  walk<Weights::none>(levels - 1, 0, channel_index_.data() + static_cast<std::size_t>(levels) * channels_, 0.0, leaf);
  // Hugin update of each child's separator: ratio = (new / max new) / old, with 0/0 = 0.
  for (int k = 0; k < child_count; ++k) {
    const int child = children_[children_begin_[clique] + k];
    const std::size_t size = separator_size_[child];
    const double* fresh = down[k];
    double* old = pool_.get() + separator_offset_[child];
    const double largest = *std::max_element(fresh, fresh + size);
    const double inverse = largest > 0.0 ? 1.0 / largest : 0.0;
    for (std::size_t s = 0; s < size; ++s) {
      // A consistent separator state has a positive old value in exact arithmetic (every target can
      // miss), so one near or below the subnormals with a positive new value lost its mass to underflow.
      if (old[s] < kSeparatorFloor && fresh[s] > 0.0) underflow_lost_mass_ = true;
      old[s] = old[s] > 0.0 ? fresh[s] * inverse / old[s] : 0.0;
    }
  }
}

void JunctionTree::load_cluster(int first, int last) {
  const int count = last - first;
  cluster_target_.assign(graph_.cluster_targets().begin() + first, graph_.cluster_targets().begin() + last);
  state_begin_.resize(count + 1);
  state_measurement_.clear();
  state_potential_.clear();
  state_variable_.clear();
  have_log_potential_ = false;
  domain_.resize(count);
  int widest = 1;
  for (int v = 0; v < count; ++v) {
    const int i = cluster_target_[v];
    state_begin_[v] = static_cast<int>(state_measurement_.size());
    state_measurement_.push_back(-1);
    state_potential_.push_back(1.0);
    state_variable_.push_back(v);
    const double row_threshold = per_row_threshold_ ? row_threshold_[i] : 0.0;
    double largest = 1.0;
    for (int e = graph_.row_begin(i); e < graph_.row_end(i); ++e) {
      const double w = graph_.edge_weight(e);
      if (w < row_threshold) continue;
      state_measurement_.push_back(graph_.edge_measurement(e));
      state_potential_.push_back(w);
      state_variable_.push_back(v);
      largest = std::max(largest, w);
    }
    const int end = static_cast<int>(state_measurement_.size());
    domain_[v] = end - state_begin_[v];
    widest = std::max(widest, domain_[v]);
    if (largest > 1.0) {
      const double inverse = 1.0 / largest;
      for (int k = state_begin_[v]; k < end; ++k) state_potential_[k] *= inverse;
      log_multiply(largest);  // Z of ψ = Z of the scaled potentials · Π largest
    }
  }
  state_begin_[count] = static_cast<int>(state_measurement_.size());
  if (static_cast<int>(ones_.size()) < widest) {
    ones_.assign(widest, 1.0);
    zeros_.assign(widest, 0.0);
  }

  // Eq (39): an edge between two targets that keep a common measurement.
  builder_.reset(count, domain_.data());
  state_next_.resize(state_measurement_.size());
  touched_measurements_.clear();
  for (int k = 0; k < static_cast<int>(state_measurement_.size()); ++k) {
    const int j = state_measurement_[k];
    if (j < 0) continue;
    if (measurement_head_[j] < 0) touched_measurements_.push_back(j);
    state_next_[k] = measurement_head_[j];
    measurement_head_[j] = k;
  }
  for (const int j : touched_measurements_) {
    for (int a = measurement_head_[j]; a >= 0; a = state_next_[a]) {
      for (int b = state_next_[a]; b >= 0; b = state_next_[b]) builder_.add_edge(state_variable_[a], state_variable_[b]);
    }
    measurement_head_[j] = -1;
  }
}

bool JunctionTree::layout_tables() {
  const int cliques = builder_.cliques();
  const int vars = builder_.vars();
  level_base_.resize(cliques + 1);
  clique_offset_.resize(cliques);
  separator_offset_.assign(cliques, 0);
  separator_size_.assign(cliques, 0);
  std::uint64_t total = 0;
  int levels_total = 0;
  for (int c = 0; c < cliques; ++c) {
    level_base_[c] = levels_total;
    levels_total += builder_.clique_size(c);
  }
  level_base_[cliques] = levels_total;
  level_stride_all_.resize(levels_total);
  child_side_stride_.assign(levels_total, 0);
  parent_side_begin_.assign(cliques, 0);
  parent_side_stride_.clear();
  for (int c = 0; c < cliques; ++c) {
    std::size_t stride = 1;  // ≤ max_clique_entries: no overflow
    for (int l = 0; l < builder_.clique_size(c); ++l) {
      level_stride_all_[level_base_[c] + l] = stride;
      stride *= static_cast<std::size_t>(domain_[builder_.clique_vars(c)[l]]);
    }
    clique_offset_[c] = total;
    total = saturating_add(total, builder_.clique_entries(c));
  }
  largest_clique_states_ = std::max(largest_clique_states_, total);
  // Separators: both variable lists are ascending, so a merge gives each shared variable the
  // same stride on both sides (first shared variable fastest).
  for (int c = 1; c < cliques; ++c) {
    const int p = builder_.parent(c);
    const int* cv = builder_.clique_vars(c);
    const int* pv = builder_.clique_vars(p);
    const int cn = builder_.clique_size(c);
    const int pn = builder_.clique_size(p);
    parent_side_begin_[c] = static_cast<int>(parent_side_stride_.size());
    parent_side_stride_.resize(parent_side_stride_.size() + pn, 0);
    std::size_t* parent_side = parent_side_stride_.data() + parent_side_begin_[c];
    std::size_t stride = 1;
    for (int a = 0, b = 0; a < cn && b < pn;) {
      if (cv[a] < pv[b]) {
        ++a;
      } else if (cv[a] > pv[b]) {
        ++b;
      } else {
        child_side_stride_[level_base_[c] + a] = stride;
        parent_side[b] = stride;
        stride *= static_cast<std::size_t>(domain_[cv[a]]);
        ++a;
        ++b;
      }
    }
    separator_size_[c] = stride;
    separator_offset_[c] = total;
    total = saturating_add(total, stride);
  }
  children_begin_.assign(cliques + 1, 0);
  for (int c = 1; c < cliques; ++c) ++children_begin_[builder_.parent(c) + 1];
  for (int c = 0; c < cliques; ++c) children_begin_[c + 1] += children_begin_[c];
  children_.resize(cliques > 0 ? cliques - 1 : 0);
  cursor_.assign(children_begin_.begin(), children_begin_.end());
  for (int c = 1; c < cliques; ++c) children_[cursor_[builder_.parent(c)]++] = c;  // ascending
  std::uint64_t scratch = 0;
  for (int c = 0; c < cliques; ++c) {
    std::uint64_t sum = 0;
    for (int k = children_begin_[c]; k < children_begin_[c + 1]; ++k) sum = saturating_add(sum, separator_size_[children_[k]]);
    scratch = std::max(scratch, sum);
  }
  scratch_offset_ = total;
  total = saturating_add(total, scratch);
  largest_table_entries_ = std::max(largest_table_entries_, total);
  if (total > budget_entries_) return false;

  // Each variable's marginal (and node potential) comes from its smallest clique.
  owner_clique_.assign(vars, -1);
  owner_level_.assign(vars, 0);
  for (int c = 0; c < cliques; ++c) {
    for (int l = 0; l < builder_.clique_size(c); ++l) {
      const int v = builder_.clique_vars(c)[l];
      if (owner_clique_[v] < 0 || builder_.clique_entries(c) < builder_.clique_entries(owner_clique_[v])) {
        owner_clique_[v] = c;
        owner_level_[v] = l;
      }
    }
  }
  owned_begin_.assign(cliques + 1, 0);
  for (int v = 0; v < vars; ++v) ++owned_begin_[owner_clique_[v] + 1];
  for (int c = 0; c < cliques; ++c) owned_begin_[c + 1] += owned_begin_[c];
  owned_var_.resize(vars);
  cursor_.assign(owned_begin_.begin(), owned_begin_.end());
  for (int v = 0; v < vars; ++v) owned_var_[cursor_[owner_clique_[v]]++] = v;

  if (total > pool_capacity_) {
    pool_.reset();
    pool_capacity_ = 0;
    try {
      pool_ = std::make_unique_for_overwrite<double[]>(static_cast<std::size_t>(total));
    } catch (const std::bad_alloc&) {
      return false;
    }
    pool_capacity_ = static_cast<std::size_t>(total);
  }
  return true;
}

bool JunctionTree::solve_cluster(int first, int last, MarginalTable& marginals) {
  load_cluster(first, last);
  if (!builder_.build(budget_entries_)) {
    largest_table_entries_ = kSaturated;
    largest_clique_states_ = kSaturated;
    return false;
  }
  if (!layout_tables()) return false;
  const int cliques = builder_.cliques();
  marginal_.assign(state_measurement_.size(), 0.0);
  for (int c = cliques - 1; c >= 0; --c) collect(c);
  for (int c = 0; c < cliques; ++c) distribute(c);
  for (int v = 0; v < builder_.vars(); ++v) {
    double* out = marginals.row(cluster_target_[v]);
    const int begin = state_begin_[v];
    const int end = state_begin_[v + 1];
    double sum = 0.0;
    for (int k = begin; k < end; ++k) sum += marginal_[k];
    const double inverse = 1.0 / sum;
    out[0] = marginal_[begin] * inverse;
    for (int k = begin + 1; k < end; ++k) out[state_measurement_[k] + 1] = marginal_[k] * inverse;
  }
  return true;
}

// A cluster of one target: p(a_i = j) = ψ_i(j) / (1 + Σ_j' ψ_i(j')) over the kept weights.
void JunctionTree::solve_single(int target, MarginalTable& marginals) {
  const double row_threshold = per_row_threshold_ ? row_threshold_[target] : 0.0;
  const RowNormalizer z = write_normalized_row(graph_, target, graph_.edge_weights(), marginals.row(target), row_threshold);
  log_multiply(z.total);
  log_multiply(z.largest);
}

void JunctionTree::solve(const SingleScanProblem& problem, MarginalTable& marginals, SolveReport& report) {
  report.reset();
  log_partition_ = std::numeric_limits<double>::quiet_NaN();
  largest_table_entries_ = 0;
  largest_clique_states_ = 0;
  const int n = problem.targets();
  const int m = problem.measurements();
  const double tau = options_.threshold;
  double graph_threshold = tau;
  per_row_threshold_ = false;
  if (options_.threshold_on == 1 || options_.threshold_on == 3) {
    const double pd = problem.context.pd;
    const double lambda_fa = problem.context.lambda_fa;
    if (!(pd > 0.0 && pd < 1.0 && lambda_fa > 0.0 && std::isfinite(lambda_fa))) {
      report.skipped = "no_context";
      return;
    }
    graph_threshold = options_.threshold_on == 1 ? tau * pd / (lambda_fa * (1.0 - pd)) : tau / (1.0 - pd);
  } else if (options_.threshold_on == 2) {
    graph_threshold = 0.0;
    per_row_threshold_ = tau > 0.0;
  }
  graph_.build(problem, graph_threshold);
  graph_.find_clusters();
  if (per_row_threshold_) {
    row_threshold_.resize(n);
    for (int i = 0; i < n; ++i) {
      double sum = 1.0;
      for (int e = graph_.row_begin(i); e < graph_.row_end(i); ++e) sum += graph_.edge_weight(e);
      row_threshold_[i] = tau * sum;
    }
  }
  budget_entries_ = static_cast<std::uint64_t>(options_.memory_mb) * (std::uint64_t{1} << 20) / sizeof(double);
  used_.assign(m, 0);
  measurement_head_.assign(m, -1);
  marginals.reshape_zero(n, m);
  log_mantissa_ = 1.0;
  log_exponent_ = 0;
  log_extra_ = 0.0;
  underflow_lost_mass_ = false;
  for (int c = 0; c < graph_.clusters(); ++c) {
    const int first = graph_.cluster_start(c);
    const int last = graph_.cluster_start(c + 1);
    if (last - first == 1) {
      solve_single(graph_.cluster_targets()[first], marginals);
    } else if (!solve_cluster(first, last, marginals)) {
      report.skipped = "memory";
      return;
    }
  }
  if (underflow_lost_mass_) {
    report.skipped = "numerical";
    return;
  }
  log_partition_ = std::log(log_mantissa_) + static_cast<double>(log_exponent_) * std::log(2.0) + log_extra_;
}

DABENCH_REGISTER_SINGLE_SCAN_ALGORITHM(JunctionTree);

}  // namespace dabench
