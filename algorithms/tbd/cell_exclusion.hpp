#pragma once
// Object-to-cell exclusivity of TBD-MB (docs/models/track-before-detect.md §4.1 [R]: "each cell explained by at
// most one object", resolved with the sum-product algorithm). RECONSTRUCTION of a piece of
// Kropfreiter, Williams & Meyer (FUSION 2021), whose body was not available.
//
// Nodes are Bernoullis y_i = (x_i, r_i) held as weighted particles: prior existence r_i and,
// per particle p, a weight a_ip = w_ip ℓ_i(z | x_ip) (prior weight times the separable
// likelihood). An object at x covers the support S(x) = {cells whose centre lies within
// `radius` of x}; factor f_j(y_1, …, y_N) = 1 iff at most one present object covers cell j.
//
// Sum-product messages (binary "covers j" of each node, a function of y_i):
//   ν_{j→i}(y_i) = 1 if i does not cover j, else 1 / (1 + Σ_{i'≠i} π_{i'j}),
//   π_{ij} = b_{i\j}(covers j) / b_{i\j}(does not cover j),
// where b_{i\j} is node i's belief without ν_{j→i}:
//   b_i(x_ip, 1) ∝ r_i a_ip Π_{j∈S(x_ip)} ν_{j→i},   b_i(0) ∝ 1 − r_i.
// Since ν_{j→i} is one number for every particle covering j, π_{ij} = (C_ij / ν_{j→i}) /
// (T_i − C_ij + (1 − r_i)) with T_i = Σ_p r_i a_ip Π ν and C_ij its part over the particles
// covering j: a sweep costs O(Σ_i P_i |S|). Likelihood ratios reach e^{±500} in TBD, so π and
// ν are kept as logarithms and Σ_{i'≠i} is a log-sum-exp over the few nodes that reach cell j
// (no subtraction of totals); log π is capped at 700 (a node that must cover the cell).
// Schedule: serial, nodes in the order they were added, each against the others' newest π
// (a flooding schedule oscillates with period two when two certain objects share a cell).
// Sweeps stop when no belief changes by more than `tolerance` (|Δ r̃_i|, or the total variation
// of its particle weights) in a sweep, or after `max_sweeps`. (Messages π far beyond what any
// belief can feel, e^{−800} against e^{−745}, may still flip between underflow and not.)
// On a tree-shaped graph (any two nodes share at most one cell, no cycles) the beliefs are
// the exact marginals (tests/tbd/test_cell_exclusion.cpp checks this by enumeration).
#include <vector>

#include "harness/tbd/problem.hpp"

namespace dabench {

class CellExclusion {
 public:
  // Geometry of the supports; removes every node.
  void reset(const TbdSensor& sensor, double radius);
  // Adds node i (returned): `count` particles at (x, y) with log a_ip in `log_weight` (any
  // common shift), prior existence r ∈ (0, 1]. `pad`: the window is grown by this margin so
  // that log_message_at() also answers for positions up to `pad` outside the particles' box.
  int add(const double* x, const double* y, const double* log_weight, int count, double existence, double pad = 0.0);
  // Serial sweeps until converged or max_sweeps; returns the number of sweeps.
  int solve(int max_sweeps, double tolerance);
  bool converged() const { return converged_; }

  // After solve(): the belief's existence r̃_i, and its particle weights w_ip ℓ Π ν normalised
  // (written to `weights`, size count).
  double existence(int node) const;
  void posterior_weights(int node, std::vector<double>& weights) const;
  // Σ_{j∈S(x)} log ν_{j→i} at a position (cells outside node i's window: ν = 1).
  double log_message_at(int node, double px, double py) const;

 private:
  struct Node {
    int column_begin = 0, row_begin = 0, columns = 0, rows = 0;  // window of covered cells
    double log_absent = 0.0;          // log((1 − r)/r) − top: b(0) against the scaled weights
    std::vector<double> log_scaled;   // log a_ip − top, top = max_p log a_ip
    std::vector<int> cover_begin;     // particle p covers window cells cover[cover_begin[p] .. cover_begin[p+1])
    std::vector<int> cover;
    std::vector<double> log_pi;       // log π_ij per window cell
    std::vector<double> log_nu;       // log ν_{j→i} per window cell (at the node's last update)
    std::vector<double> covered;      // C_ij per window cell, on the node's last shift
    std::vector<double> particle;     // scratch: exp(log b_i(x_ip, 1) − shift)
    double total = 0.0, absent = 0.0; // T_i and b_i(0) on that shift
    double existence = -1.0;          // r̃_i at the node's last update
    std::vector<double> previous;     // its normalised particle weights then
  };
  struct Reach {  // node `node` reaches a frame cell as its window cell `cell`
    int node, cell;
  };

  // Window cells of the support of (px, py) — calls visit(window cell index).
  template <class Visit>
  void for_support(const Node& node, double px, double py, Visit&& visit) const;
  int global_cell(const Node& node, int window_cell) const;
  // Node i's ν from the others' π, its belief, then (if new_pi) its π; returns the change of
  // its belief since its last update (|Δ r̃| or the weights' total variation, the larger).
  double update(int node, bool new_pi);

  const TbdSensor* sensor_ = nullptr;
  double radius_ = 0.0;
  std::vector<Node> nodes_;  // [0, count_) in use; kept to reuse their buffers
  int count_ = 0;
  std::vector<std::vector<Reach>> reach_;  // per frame cell: the nodes whose window holds it
  bool converged_ = false;
};

}  // namespace dabench
