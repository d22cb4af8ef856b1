#include "algorithms/single_scan/ehm.hpp"

#include <algorithm>
#include <cmath>

#include "harness/single_scan/registry.hpp"

namespace dabench {

std::string EhmOptions::validate() const {
  if (!(threshold >= 0.0)) return "threshold must be >= 0";
  if (max_nodes < 1 || max_nodes > 2000000000) return "max_nodes must be in [1, 2e9]";
  if (order < 0 || order > 3) return "order must be 0 (auto), 1 (greedy), 2 (bfs) or 3 (input)";
  return {};
}

void Ehm::solve(const SingleScanProblem& problem, MarginalTable& marginals, SolveReport& report) {
  report.reset();
  stats_ = EhmStats{};
  graph_.build(problem, options_.threshold);
  if (problem.has_must_detect_targets() && !must_detect_feasible(graph_, problem)) {
    report.skipped = "infeasible";
    return;
  }
  graph_.find_clusters();
  const int n = graph_.targets();
  const int m = graph_.measurements();
  must_detect_.resize(n);
  for (int i = 0; i < n; ++i) must_detect_[i] = problem.must_detect(i);
  marginals.reshape_zero(n, m);
  local_id_.assign(m, -1);  // set per cluster (prepare_cluster); clusters' measurements are disjoint
  nodes_total_ = 0;
  stats_.clusters = graph_.clusters();
  // The work limit (header): every net is bounded before any is built. With one cluster of
  // several targets its bound is taken where it is solved; with more, a first pass bounds them
  // all (keeping their orders), so a solve past the cap spends nothing on nets, unless a coarse
  // bound on the whole problem already keeps within the caps.
  int multi = 0;
  for (int c = 0; c < graph_.clusters(); ++c) {
    if (graph_.cluster_start(c + 1) - graph_.cluster_start(c) == 1) {
      ++stats_.node_bound;
    } else {
      ++multi;
    }
  }
  const bool bound_first = multi >= 2 && !surely_within_caps();
  auto refuse = [&](const char* reason) {
    report.skipped = reason;
    stats_.nodes = nodes_total_;
  };
  if (bound_first) {
    saved_order_.resize(n);
    const char* verdict = "";
    for (int c = 0; c < graph_.clusters(); ++c) {
      const int first = graph_.cluster_start(c), last = graph_.cluster_start(c + 1);
      if (last - first == 1) continue;
      const char* reason = prepare_cluster(first, last, false);
      if (reason[0] != '\0') return refuse(reason);
      if (add_to_bound()[0] != '\0') verdict = "work_estimate";  // go on: stats() get the whole bound
      std::copy(order_.begin(), order_.end(), saved_order_.begin() + first);
    }
    if (verdict[0] != '\0') return refuse(verdict);
  }
  for (int c = 0; c < graph_.clusters(); ++c) {
    const int first = graph_.cluster_start(c), last = graph_.cluster_start(c + 1);
    if (last - first == 1) {
      solve_single(graph_.cluster_targets()[first], marginals);
      continue;
    }
    const char* reason = prepare_cluster(first, last, bound_first);
    if (reason[0] == '\0' && !bound_first) reason = add_to_bound();
    if (reason[0] == '\0') reason = solve_cluster(marginals);
    if (reason[0] != '\0') return refuse(reason);
  }
  stats_.nodes = nodes_total_;
}

// A cluster of one target: p(a = j) = ψ(j) / (1 + Σ ψ) (write_normalized_row); ψ(j) / Σ ψ for a
// target that must be detected (it has a gated measurement: the problem is feasible).
void Ehm::solve_single(int target, MarginalTable& marginals) {
  if (must_detect_[target]) {
    double largest = 0.0, total = 0.0;
    for (int e = graph_.row_begin(target); e < graph_.row_end(target); ++e) largest = std::max(largest, graph_.edge_weight(e));
    for (int e = graph_.row_begin(target); e < graph_.row_end(target); ++e) total += graph_.edge_weight(e) / largest;
    double* row = marginals.row(target);
    for (int e = graph_.row_begin(target); e < graph_.row_end(target); ++e) {
      row[graph_.edge_measurement(e) + 1] = graph_.edge_weight(e) / largest / total;
    }
    stats_.log_partition += std::log(largest) + std::log(total);
  } else {
    const RowNormalizer z = write_normalized_row(graph_, target, graph_.edge_weights(), marginals.row(target));
    stats_.log_partition += std::log(z.largest) + std::log(z.total);
  }
  ++nodes_total_;
  stats_.max_layer_width = std::max(stats_.max_layer_width, 1);
  stats_.largest_cluster = std::max(stats_.largest_cluster, 1);
}

// The current cluster's gate tables, order (chosen, or the one saved by the bounding pass), tree
// and net tables. Returns "" or "key_width".
const char* Ehm::prepare_cluster(int first, int last, bool saved_order) {
  const int size = last - first;
  cluster_size_ = size;
  stats_.largest_cluster = std::max(stats_.largest_cluster, size);
  targets_.assign(graph_.cluster_targets().begin() + first, graph_.cluster_targets().begin() + last);

  // Shared measurements (gated by >= 2 targets) get local ids; exclusive ones fold into choice 0.
  // (The bounding pass may have numbered this cluster before: the same ids are given again.)
  for (int li = 0; li < size; ++li) {
    const int t = targets_[li];
    for (int e = graph_.row_begin(t); e < graph_.row_end(t); ++e) local_id_[graph_.edge_measurement(e)] = -1;
  }
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
    stay_weight_[li] = (must_detect_[t] ? 0.0 : 1.0 / largest) + exclusive;
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

  if (saved_order) {
    order_.assign(saved_order_.begin() + first, saved_order_.begin() + last);
  } else {
    choose_order();
  }
  position_.resize(size);
  for (int p = 0; p < size; ++p) position_[order_[p]] = p;
  build_tree();
  cluster_bits_ = build_tables();
  stats_.max_key_bits = std::max(stats_.max_key_bits, cluster_bits_);
  return cluster_bits_ <= 64 * kMaxKeyWords ? "" : "key_width";
}

// Adds the current cluster's bound to the solve's; "work_estimate" when the solve's nodes could
// pass max_nodes or this net's stored edges 16 × max_nodes.
const char* Ehm::add_to_bound() {
  const NetBound bound = net_bound();
  stats_.node_bound += bound.nodes;
  stats_.edge_bound += bound.edges;
  const auto cap = static_cast<double>(options_.max_nodes);
  return stats_.node_bound > cap || bound.edges > kEdgesPerNode * cap ? "work_estimate" : "";
}

const char* Ehm::solve_cluster(MarginalTable& marginals) {
  if (cluster_bits_ <= 64) return run_net<1>(marginals);
  if (cluster_bits_ <= 128) return run_net<2>(marginals);
  if (cluster_bits_ <= 256) return run_net<4>(marginals);
  return run_net<kMaxKeyWords>(marginals);
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

DABENCH_REGISTER_SINGLE_SCAN_ALGORITHM(Ehm);

}  // namespace dabench
