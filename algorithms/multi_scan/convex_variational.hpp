#pragma once
// Primal–dual coordinate ascent (PDCA) for the multiple-scan convex free energy: Algorithm 2 of
// Williams & Lau, "Multiple scan data association by convex variational inference"
// (multiscan-convex-variational), Sec. III and Appendices B–C. msbp and cvsh1 run it; cv, cvs,
// cvh and cvsh run it under `solver=pdca`, as the validator of their default column-dual solver
// (column_dual_newton.hpp: the same minimiser of (63)). See convex_variational_variants.hpp.
//
// Objective (63), with per-scan coefficients γ_t' (concave terms) and β_t' (false alarms):
//   F = −Σ_i {H(A^i) + E log ψ^i} − Σ_t' Σ_i {H(a_t'|A^i) + E log ψ^i_t'}
//       + Σ_t' β_t' Σ_j q^{0,j} log q^{0,j} − Σ_t' γ_t' Σ_{i,j} (1 − q^{i,j}) log(1 − q^{i,j}),
// split as f + Σ_t' (h_{t',1} + h_{t',2}) (65)–(68) with the κ weights of Lemma 4, eqs (69)–(73)
// (convergent when η = 1 − Σγ_t' > 0, Theorem 2), or the heuristic weights of eqs (93)–(95).
//
// One sweep visits the scans newest → oldest → newest; at each scan block (t',1), then (t',2):
//   (t',1), Lemma 5: μ(A) = Σ_{τ≠t'} λ_{τ,1,A} + Σ_τ λ_{τ,2,A}, μ_t' = λ_{t',2,t'};
//     φ = log ψ − μ (76), φ_t' = log ψ_t' − μ_t' (77), K1 = κ_{f,t'} + κ_{t',1,t'},
//     φ̃(a) = log Σ_A exp{(φ(A) + φ_t'(A,a))/K1} (78); the single-scan problem (79) with
//     w^{i,j} = exp φ̃(j), α = 1, β̃ = β/K1, γ̃ = γ/K1 is solved by Algorithm 1
//     (FractionalBpKernel); q_t'(A,a) = q(a) exp{(φ + φ_t')/K1 − φ̃(a)} (75),
//     q(A) = Σ_a q_t'(A,a) (82), λ by (80)–(81).
//   (t',2), Lemma 6: μ(A) = Σ_τ λ_{τ,1,A} + Σ_{τ≠t'} λ_{τ,2,A}, μ_t' = λ_{t',1,t'};
//     K2 = κ_{f,t'} + κ_{t',2,t'}, φ̃(A) = K2 log Σ_a exp{φ_t'(A,a)/K2} (88),
//     q(A) ∝ exp{(φ + φ̃)/(κ_{f,A} + κ_{f,t'} + κ_{t',2,A} + κ_{t',2,t'})} (84),
//     q_t'(A,a) = q(A) exp{(φ_t' − φ̃(A))/K2} (85), λ by (89)–(90).
// Dual updates, (54): λ_A = φ − κ_{f,A} log q(A), λ_t' = φ_t' − κ_{f,t'} log q_t'(A,a) (the
// additive constants of (80)–(81) change no belief and are dropped).
// Stopping: the largest λ change of a sweep below `tolerance`, or the beliefs' estimated
// distance to their limit below `belief_tolerance`, or `max_sweeps` sweeps (converged = false).
//
// Invariants: every quantity is a logarithm and sums are log-sum-exp (the 1/K scalings put
// exponents outside double range). Exact zeros of ψ stay −∞, with λ = 0 there; a hypothesis
// with ψ^i(A) = 0 or an all-zero factor row in some scan is removed (log ψ^i(A) = −∞).
// Algorithm 1's weights are floored at e^{−600}·min(row maximum, 1), its outputs at DBL_MIN.
//
// Sequential use (Sec. III-D): scans are appended one at a time; reweight() changes every
// scan's (γ_t', β_t') and, for scans solved before, modifies the factors by Theorem 3, eq (91):
//   log ψ̄_t'(A, j) = log ψ_t'(A, j) + Δγ [1 + log(1 − q^{i,j})] − Δβ [1 + log q^{0,j}], j > 0,
// so that the previous solution is the solution of the reweighted problem.
// Background (κ values, warm starts, stopping rules, why the ascent is slow, floors):
// docs/algorithms/multi-scan.md#algorithm-2-and-the-convex-family
#include <vector>

#include "algorithms/single_scan/fractional_bp.hpp"
#include "harness/core/solve_report.hpp"
#include "harness/multi_scan/problem.hpp"

namespace dabench {

enum class KappaWeights {
  kLemma4,     // eqs (69)–(73): convergent for Σγ < 1 (Theorem 2)
  kHeuristic,  // eqs (93)–(95)
};

struct PdcaSettings {
  KappaWeights weights = KappaWeights::kLemma4;
  double tolerance = 1e-9;          // stop when no λ entry moved more than this in a sweep
  double belief_tolerance = 0.0;    // or when the beliefs' estimated distance to their limit is below this
  int max_sweeps = 2000;            // sweep cap (converged = false when it stops the ascent)
  double kernel_tolerance = 1e-11;  // Algorithm 1's final stopping tolerance on max |log Δy|
                                    // (looser in early sweeps: 1e-3 × the last sweep's λ change)
  int kernel_max_iterations = 10000;
};

class ConvexVariationalPdca {
 public:
  // Starts a problem with the tracks and priors of `problem` and no scans.
  void start(const MultiScanProblem& problem);
  // Appends scan `scan` of the problem given to start(), with γ = 0, β = 1 until reweight().
  void append_scan(const ScanFactors& scan);
  int scans() const { return static_cast<int>(scans_.size()); }
  // False if some track has no hypothesis left with nonzero weight (no feasible event).
  bool feasible() const;

  // K1 = κ_{f,t'} + κ_{t',1,t'} of scan t' for coefficients γ (one per scan): β = β̃·K1
  // gives block (t',1) the false-alarm coefficient β̃ of (79).
  static double block_scale(KappaWeights weights, const std::vector<double>& gamma, int scan);

  // Sets (γ_t', β_t') for every scan. Scans solved before and whose coefficients change get the
  // factor modification (91) computed from their current beliefs (Theorem 3).
  void reweight(const std::vector<double>& gamma, const std::vector<double>& beta);

  // Runs Algorithm 2 from λ = 0. Adds the sweeps to report.iterations; clears
  // report.converged if the sweep cap stopped it or the single-scan kernel hit its cap in the
  // last sweep; sets report.skipped = "numerical" if the kernel returned non-finite marginals.
  void solve(const PdcaSettings& settings, SolveReport& report);

  // q^i(A^i) from the latest block (t',2); q^{i,j}_t' from each scan's latest block (t',1).
  void write_beliefs(MultiScanBeliefs& beliefs) const;

  // The primal point the duals of the last solve define, eq (48): ∇f(q) = −Σ λ, i.e.
  //   q^i(A) ∝ exp{(log ψ^i(A) − Σ_τ (λ_{τ,1,A} + λ_{τ,2,A}))/κ_{f,A}},
  //   q^i_t'(A, a) ∝ exp{(log ψ̄^i_t'(A, a) − λ_{t',1,t'} − λ_{t',2,t'})/κ_{f,t'}},
  // each normalised (57). At convergence every block returns this point; it is the full
  // primal solution of (63) (tests check its optimality directly).
  struct Primal {
    std::vector<Vector> track;             // q^i(A)
    std::vector<std::vector<RowMatrix>> pair;  // [scan][track]: q^i_t'(A, a)
  };
  void recover_primal(Primal& primal) const;

 private:
  struct Kappas {
    double f_a, f_t, one_a, one_t, two_a, two_t;  // κ_{f,A}, κ_{f,t'}, κ_{t',1,A}, κ_{t',1,t'}, κ_{t',2,A}, κ_{t',2,t'}
  };
  struct Scan {
    int measurements = 0;
    double gamma = 0.0;
    double beta = 1.0;
    bool solved = false;                 // has beliefs from a solve
    std::vector<RowMatrix> log_factor;   // per track: log ψ̄_t'(A, a), −∞ where ψ = 0
    std::vector<Vector> lambda1_a, lambda2_a;      // λ_{t',1,A}, λ_{t',2,A}
    std::vector<RowMatrix> lambda1_t, lambda2_t;   // λ_{t',1,t'}, λ_{t',2,t'}
    RowMatrix association;               // q^{i,j}_t', n × (m+1)
    Vector clutter;                      // q^{0,j}_t', m
    Vector row_shift, column_shift;      // log scalings of (79) from the previous kernel duals
  };

  static Kappas kappas(KappaWeights weights, const std::vector<double>& gamma, int scan);
  double block_one(int scan, const Kappas& k, const PdcaSettings& settings, double kernel_tolerance);
  double block_two(int scan, const Kappas& k);
  void snapshot_beliefs();                     // copies q^i(A), q^{i,j}_t' for the belief rule
  double belief_change_since_snapshot() const;  // largest change of any of them since

  KappaWeights weights_ = KappaWeights::kLemma4;  // of the last solve
  std::vector<Vector> log_prior_;   // log ψ^i(A), −∞ for removed hypotheses
  std::vector<Vector> lambda_sum_;  // Σ_τ (λ_{τ,1,A} + λ_{τ,2,A}) per track
  std::vector<Vector> log_belief_;  // log q^i(A) from the latest block (t',2)
  std::vector<Scan> scans_;
  std::vector<Vector> last_belief_;          // q^i(A) at the start of the sweep
  std::vector<RowMatrix> last_association_;  // q^{i,j}_t' at the start of the sweep
  FractionalBpKernel kernel_;
  RowMatrix kernel_weight_;         // w^{i,j}, j > 0, of (79)
  Vector kernel_miss_;              // w^{i,0}
  Vector kernel_clutter_;           // w^{0,j}
  bool kernel_failed_ = false;      // Algorithm 1 hit its cap during the current sweep
  bool numerical_failure_ = false;  // Algorithm 1 returned non-finite marginals
  RowMatrix log_column_;            // φ̃_t'^i(a) of (78), n × (m+1)
  std::vector<RowMatrix> scaled_;   // per track: (φ + φ_t')/K1, then log q_t'(A, a)
  // Scratch of the blocks (sized once, reused: no allocation in the sweeps).
  RowMatrix exp_work_;              // exponentials of a log-sum-exp
  RowMatrix phi_t_;                 // φ_t'(A, a) of block (t',2)
  RowMatrix log_q_;                 // log q_t'(A, a) of block (t',2)
  Vector phi_a_, log_q_a_, phi_tilde_, row_shift_;
  Eigen::RowVectorXd column_shift_;
};

}  // namespace dabench
