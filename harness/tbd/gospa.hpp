#pragma once
// The GOSPA metric (generalised optimal sub-pattern assignment) of Rahman, García-Fernández &
// Svensson, "Generalized optimal sub-pattern assignment metric", FUSION 2017, between the true
// positions X and the estimated positions Y of one time step (2-D, metres). Definition 1: for
// |X| ≤ |Y|,
//
//   d_p^(c,α)(X, Y) = ( min_π Σ_{i=1}^{|X|} d^(c)(x_i, y_π(i))^p + (c^p/α)(|Y| − |X|) )^(1/p),
//
// π over the injections X → Y, d^(c)(x, y) = min(‖x − y‖, c), and d(X, Y) = d(Y, X) otherwise.
// It is a metric for c > 0, 1 ≤ p < ∞, 0 < α ≤ 2.
//
// For α = 2, Proposition 1 splits it into localisation, missed and false targets:
//
//   d_p^(c,2)(X, Y)^p = min_γ Σ_{(x,y)∈γ} ‖x − y‖^p + (c^p/2)(|X| − |γ|) + (c^p/2)(|Y| − |γ|),
//
// γ over the assignment sets of pairs (each point in at most one pair) with ‖x − y‖ < c. The
// optimal π gives an optimal γ: its pairs closer than c (a pair at distance ≥ c costs
// c^p = c^p/2 + c^p/2, a miss plus a false target). With several optima, any one is reported.
//
// Computed exactly: the min over π is a rectangular linear assignment on the |X|×|Y| matrix of
// d^(c)(x_i, y_j)^p (LinearAssignment, harness/core/linear_assignment.hpp; O(n_min² n_max)).
// Gospa keeps its workspace, so repeated calls allocate nothing once it has grown.
// The track-before-detect study (docs/models/track-before-detect.md §5.1) reports it per time step with the
// defaults below (its recommended c = 2 m, p = 1, α = 2) and also p = 2.
#include <vector>

#include <Eigen/Core>

#include "harness/core/linear_assignment.hpp"

namespace dabench {

struct GospaOptions {
  double cutoff = 2.0;  // c > 0, m: the most a pair can contribute to the distance
  double order = 1.0;   // p ≥ 1 (finite): the exponent of the sum
  double alpha = 2.0;   // α ∈ (0, 2]: cardinality penalty c^p/α per unmatched point

  void validate() const;  // InputError naming the field and the rule it broke
};

struct GospaResult {
  double distance = 0.0;       // d_p^(c,α)(X, Y), m
  // α = 2 only (Proposition 1), each in m^p, summing to distance^p; NaN for α ≠ 2:
  double localisation = 0.0;   // Σ_{(x,y)∈γ} ‖x − y‖^p
  double missed = 0.0;         // (c^p/2)(|X| − |γ|)
  double false_targets = 0.0;  // (c^p/2)(|Y| − |γ|)
  int missed_count = 0;        // |X| − |γ|  (−1 for α ≠ 2)
  int false_count = 0;         // |Y| − |γ|  (−1 for α ≠ 2)
};

class Gospa {
 public:
  // GOSPA between `truth` (X) and `estimates` (Y). Validates `options` (InputError); throws
  // std::invalid_argument if a point has a non-finite coordinate.
  GospaResult compute(const std::vector<Eigen::Vector2d>& truth, const std::vector<Eigen::Vector2d>& estimates,
                      const GospaOptions& options = {});

 private:
  std::vector<double> cost_;  // |X|×|Y| row-major: d^(c)(x_i, y_j)^p
  std::vector<int> column_of_row_;
  LinearAssignment assignment_;
};

}  // namespace dabench
