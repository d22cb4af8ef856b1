// Upper bounds on EHM's nets before anything is built (ehm.hpp, work limit): a coarse one for a
// whole problem from its gating graph, and one for the current cluster from its tree and key
// spaces.
#include <algorithm>
#include <cmath>

#include "algorithms/single_scan/ehm.hpp"

namespace dabench {

namespace {

// Σ_{s ≤ m} C(k, s): the subsets of at most m of k elements.
double subsets_up_to(int k, int m) {
  double term = 1.0, sum = 1.0;
  for (int s = 1; s <= std::min(k, m); ++s) {
    term = term * (k - s + 1) / s;
    sum += term;
  }
  return sum;
}

}  // namespace

// A cluster of K targets, target t gating g_t shared measurements (of ≥ 2 targets; at most
// Σ g_t / 2 of them), has layers of at most W = min(2^(Σ g_t / 2), Π_t (1 + g_t)) nodes, whatever
// its order and tree, so at most K·W nodes and W · max_t (1 + g_t) · (K - 1) stored edges; net_bound
// never exceeds these. True when the sums over the clusters keep within the caps.
bool Ehm::surely_within_caps() const {
  const auto cap = static_cast<double>(options_.max_nodes);
  double nodes = 0.0;
  for (int c = 0; c < graph_.clusters(); ++c) {
    const int first = graph_.cluster_start(c), last = graph_.cluster_start(c + 1);
    double product = 1.0;
    int gated = 0, widest = 0;
    for (int k = first; k < last; ++k) {
      const int t = graph_.cluster_targets()[k];
      int g = 0;
      for (int e = graph_.row_begin(t); e < graph_.row_end(t); ++e) g += graph_.measurement_degree(graph_.edge_measurement(e)) >= 2;
      product *= 1.0 + g;
      gated += g;
      widest = std::max(widest, g);
    }
    const double width = std::min(std::ldexp(1.0, std::min(gated / 2, 1023)), product);
    nodes += (last - first) * width;
    if (width * (1 + widest) * (last - first - 1) > kEdgesPerNode * cap) return false;
  }
  return nodes <= cap;
}

// The layer of position c holds the distinct sets S = (measurements used by c's ancestors) ∩ K(c),
// and each ancestor uses at most one measurement, so its node count N_c is at most each of
//   2^|K(c)|                      (every subset),
//   Σ_{s ≤ m} C(|K(c)|, s)         (m = the ancestors gating a measurement of K(c)),
//   Π_a (1 + |gate(a) ∩ K(c)|)     (over those ancestors a: one of its measurements, or none),
//   Π_a (1 + p_a) · Σ_{s ≤ m'} C(k', s)
//                                  (p_a = the measurements of K(c) that a alone of the ancestors
//                                  gates: at most one of them each; k' = those gated by two or
//                                  more ancestors, m' = the ancestors gating one of them),
//   N_p · choices(p)               (p the parent: one child key per node and choice).
// A root's layer has one node. build_net stores N_p · choices(p) · children(p) edges for p.
// Positions are visited top-down (a parent's position is smaller than its children's).
Ehm::NetBound Ehm::net_bound() {
  const int size = cluster_size_;
  NetBound bound;
  layer_bound_.resize(size);
  degree_.assign(size, 0);   // per position: measurements of K(c) it gates, for the c at hand
  private_.assign(size, 0);  // per position: those of them no other ancestor of c gates
  queue_.clear();           // the positions counted in degree_
  for (int c = 0; c < size; ++c) {
    double nodes = 1.0;
    const int p = parent_[c];
    if (p >= 0) {
      const int kb = key_begin_[c], ks = key_size_[c];
      int shared_by_ancestors = 0;  // measurements of K(c) gated by two or more ancestors
      for (int b = 0; b < ks; ++b) {
        const int j = key_list_[kb + b];
        int gating = 0, last = -1;
        for (int k = meas_begin_[j]; k < meas_begin_[j + 1]; ++k) {
          const int a = position_[meas_targets_[k]];
          if (tin_[a] < tin_[c] && tin_[c] < tout_[a]) {  // a is an ancestor of c
            if (degree_[a]++ == 0) queue_.push_back(a);
            ++gating;
            last = a;
          }
        }
        if (gating == 1) ++private_[last];
        shared_by_ancestors += gating >= 2;
      }
      double product = 1.0, private_product = 1.0;
      int sharing = 0;  // ancestors gating one of the measurements gated by two or more
      for (const int a : queue_) {
        product *= 1.0 + degree_[a];
        private_product *= 1.0 + private_[a];
        sharing += degree_[a] > private_[a];
        degree_[a] = 0;
        private_[a] = 0;
      }
      const auto ancestors = static_cast<int>(queue_.size());
      queue_.clear();
      const double choices = choice_begin_[p + 1] - choice_begin_[p];
      nodes = std::min({std::ldexp(1.0, ks), subsets_up_to(ks, ancestors), product,
                        private_product * subsets_up_to(shared_by_ancestors, sharing), layer_bound_[p] * choices});
    }
    layer_bound_[c] = nodes;
    bound.nodes += nodes;
  }
  for (int p = 0; p < size; ++p) {
    const double choices = choice_begin_[p + 1] - choice_begin_[p];
    bound.edges += layer_bound_[p] * choices * (child_begin_[p + 1] - child_begin_[p]);
  }
  return bound;
}

}  // namespace dabench
