#pragma once
// Fractional BP for the single-scan fractional free energy: Algorithm 1 of Williams & Lau,
// "multiscan-convex-variational" (eq 79; Appendix D, eqs 138-165).
//
//   minimise  Σ_{i,j>0} q_ij log(q_ij/w_ij) + α Σ_i q_i0 log(q_i0/w_i0) + β Σ_j q_0j log(q_0j/w_0j)
//             − γ Σ_{i,j>0} (1 − q_ij) log(1 − q_ij)                                        (138)
//   subject to Σ_{j=0..m} q_ij = 1 ∀i (139),  Σ_{i=0..n} q_ij = 1 ∀j (140),  0 ≤ q ≤ 1 (141).
//
// With κ = −1 − γ + α + β, y ≡ 1 initially, each iteration is a half-step x = r(y), eqs (160)-(162),
//   x_ij = e^κ C_j^{−(1−γ)} (C_j − w_ij y_ij)^{−γ},  x_i0 = y_i0^{1/α−1},  x_0j = 1/C_j,
//   C_j = w_0j y_0j + Σ_i w_ij y_ij,
// then a half-step y = s(x), eqs (163)-(165), the same with rows and columns exchanged:
//   y_ij = e^κ R_i^{−(1−γ)} (R_i − w_ij x_ij)^{−γ},  y_i0 = 1/R_i,  y_0j = x_0j^{1/β−1},
//   R_i = w_i0 x_i0 + Σ_j w_ij x_ij.
// At the fixed point the primal solution is q_ij = w_ij x_ij y_i0 = w_ij y_ij x_0j,
// q_i0 = w_i0 y_i0^{1/α}, q_0j = w_0j x_0j^{1/β} (eqs 153-155 with 158-159). With γ = 1 and
// α = β = 1 the iteration is the BP iteration of bp-marginal-association (remark after eq 165).
// Theorem 1: it converges to the unique minimiser when γ ∈ [0, 1), α = 1, β > 0.5 and w_i0,
// w_0j > 0 (case 3 of Appendix D); other α ∈ (0.5, ∞) ∩ [γ, ∞) are accepted as Algorithm 1's
// input allows, with convergence reported rather than guaranteed.
//
// Convergence test: after each full iteration, d = max |log(y_new / y_old)| over every y_ij,
// y_i0, y_0j (the metric of the contraction proof, Definition 4); stop when d < tolerance.
// Outputs are read off the last iteration so that each target's row sums to 1 exactly
// (q_ij = w_ij x_ij / R_i, q_i0 = w_i0 x_i0 / R_i); the columns then sum to 1 up to O(d), and
// the KKT residuals of eqs (145)-(147) are O(d): measured at about 2.4 × tolerance on random and
// grid problems for γ ∈ {0, 0.5, 0.95, 1}, so the default 1e-9 keeps them below 1e-8
// (tests/single_scan/test_fractional_bp.cpp checks this).
//
// Leave-one-out sums (C_j − w_ij y_ij, R_i − w_ij x_ij) are never formed by subtracting a term
// that dominates its sum: the largest term of each row and column is kept apart from the sum of
// the others, so huge odds (a pair 1e200 times likelier than its miss or false alarm) give
// accurate messages instead of cancellation to 0 or NaN.
//
// Sparse and allocation-free: only pairs with w_ij > 0 are stored (q_ij = 0 exactly where
// w_ij = 0, the convention of Appendix D), and buffers only grow across calls.
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "harness/core/matrix_types.hpp"
#include "harness/core/params.hpp"
#include "harness/single_scan/solver.hpp"

namespace dabench {

struct FractionalBpOptions {
  double gamma = 1.0;          // γ ∈ [0, 1]: weight of the −(1−q) log(1−q) terms (1 = Bethe / BP)
  double alpha = 1.0;          // α ∈ (0.5, ∞), α ≥ γ: coefficient of q_i0 log(q_i0/w_i0)
  double beta = 1.0;           // β ∈ (0.5, ∞), β ≥ γ: coefficient of q_0j log(q_0j/w_0j)
  double tolerance = 1e-9;     // stop when max |log(y_new/y_old)| < tolerance
  int max_iterations = 10000;  // cap; reaching it reports converged = false

  void bind(ParamList& params) {
    params.add("gamma", gamma, "γ in [0, 1]: fractional weight of the pairwise entropy terms (eq 138)");
    params.add("alpha", alpha, "α > 0.5, α >= γ: coefficient of the missed-detection entropy");
    params.add("beta", beta, "β > 0.5, β >= γ: coefficient of the false-alarm entropy");
    params.add("tolerance", tolerance, "stop when max |log y change| over one iteration is below this");
    params.add("max_iterations", max_iterations, "iteration cap (converged=0 if reached)");
  }
  // Empty if valid, else the field and the rule it broke (Algorithm 1's input conditions).
  std::string validate() const;
};

struct FractionalBpOutcome {
  int iterations = 0;
  bool converged = false;
  double objective = std::numeric_limits<double>::quiet_NaN();  // eq (138) at the returned q
};

// The iteration of Algorithm 1 on one problem; reusable (e.g. for block (t', 1) of the
// multi-scan Algorithm 2, Lemma 5, with α = 1). One object per thread.
class FractionalBpKernel {
 public:
  using WeightMatrix = Eigen::Ref<const RowMatrix>;                     // w_ij, n×m, i, j > 0
  using WeightVector = Eigen::Ref<const Vector, 0, Eigen::InnerStride<>>;  // strided views allowed

  // Solves (138)-(141) for w (n×m, entries ≥ 0 and finite), miss_weight w_i0 (size n) and
  // clutter_weight w_0j (size m), each side vector > 0 and finite or empty (= all ones).
  // Throws InputError naming the field for invalid options or weights.
  FractionalBpOutcome solve(WeightMatrix w, WeightVector miss_weight, WeightVector clutter_weight,
                            const FractionalBpOptions& options);

  // Results of the last solve, valid until the next one:
  // q_ij as n×(m+1) row-major, column 0 = q_i0 (each row sums to 1) ...
  Eigen::Map<const RowMatrix> target_marginals() const {
    return Eigen::Map<const RowMatrix>(q_.data(), targets_, measurements_ + 1);
  }
  // ... and q_0j, size m.
  Eigen::Map<const Vector> clutter_marginals() const { return Eigen::Map<const Vector>(q_clutter_.data(), measurements_); }

 private:
  void build(WeightMatrix w, WeightVector miss_weight, WeightVector clutter_weight);
  void column_step(const FractionalBpOptions& options);  // x = r(y), eqs (160)-(162)
  double row_step(const FractionalBpOptions& options);   // y = s(x), eqs (163)-(165); returns d (or +inf, surely > tolerance)
  void write_outputs();
  double objective(const FractionalBpOptions& options) const;

  int targets_ = 0;
  int measurements_ = 0;
  int edges_ = 0;
  double e_kappa_ = 1.0;  // e^κ
  // The buffers below only grow; the counts above say how much of each is in use.
  // Pairs with w_ij > 0, target by target in increasing measurement order.
  std::vector<int> row_begin_;        // size n+1
  std::vector<int> edge_column_;
  std::vector<double> edge_weight_;   // w_ij
  std::vector<double> x_;             // x_ij
  std::vector<double> y_;             // y_ij
  std::vector<double> miss_;          // w_i0
  std::vector<double> x_miss_;        // x_i0
  std::vector<double> y_miss_;        // y_i0
  std::vector<double> row_sum_;       // R_i of the last row step
  std::vector<double> clutter_;       // w_0j
  std::vector<double> x_clutter_;     // x_0j
  std::vector<double> y_clutter_;     // y_0j
  std::vector<double> column_sum_;    // C_j
  std::vector<double> column_factor_; // e^κ C_j^{−(1−γ)}
  std::vector<int> column_top_;       // the pair with the largest term w_ij y_ij of C_j (−1: none)
  std::vector<double> column_top_value_;  // that term
  std::vector<double> column_rest_;   // C_j minus that term, summed without subtraction
  std::vector<double> q_;             // n×(m+1) output
  std::vector<double> q_clutter_;     // m output
};

// The registered single-scan solver: marginals p(a_i = j) = q_ij of (138) with ψ as w_ij and the
// problem's w_i0, w_0j; SolveReport::free_energy = (138) at the solution.
class FractionalBp final : public SingleScanSolver {
 public:
  using Options = FractionalBpOptions;
  static constexpr std::string_view kName = "fbp";
  static constexpr std::string_view kSummary =
      "fractional BP, Algorithm 1 / eqs (160)-(165) of multiscan-convex-variational (gamma=1: bp)";

  explicit FractionalBp(const Options& options);
  void solve(const SingleScanProblem& problem, MarginalTable& marginals, SolveReport& report) override;

 private:
  Options options_;
  FractionalBpKernel kernel_;
};

}  // namespace dabench
