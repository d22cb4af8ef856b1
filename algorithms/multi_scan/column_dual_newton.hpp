#pragma once
// The reduced column-dual solver for the multiple-scan convex free energy (63) of Williams & Lau,
// "Multiple scan data association by convex variational inference" (multiscan-convex-variational):
// the minimiser of (63) that Algorithm 2 (convex_variational.hpp) approaches, reached by damped
// Newton on a concave dual with one variable per measurement: σ_t(j), the multiplier of the
// column constraint (61) (the σ of (132)–(133)).
//  - Each track is a star tree (A, one a_t per scan), so its part of (63) is minimised exactly for
//    given association marginals by the tilted posterior of tilted_track.hpp; (57)–(59) and (62)
//    hold by construction, and only (61) is dualised.
//  - Dual: D(σ) = Σ_i TiltedTrack::dual_value() − Σ_tj [β_t q⁰_tj + σ_tj], q⁰_tj = e^{−σ_tj/β_t − 1}
//    (133); gradient r_tj = Σ_i μ^i_t(j) + q⁰_tj − 1 (the column residual);
//    −∇²D = K = Σ_i K_i + diag(q⁰/β), K_i ⪰ 0 (track_newton_matrix.hpp), so K ≻ 0.
//  - Invariants the callers keep: Σ_t γ_t < 1 (each track's part strictly convex, cf. (64)), and
//    applicable() — every track can miss in every scan — without which the dual maximum is not
//    attained (such problems go to Algorithm 2).
//  - At the maximiser every condition of (56)–(62) and (132)–(133) holds, and D equals (63) at the
//    beliefs (with the modified factors ψ̄ of (91)).
//  - Step (newton_direction()): the maximiser of a model that keeps D's clutter term exact and
//    quadratises the tracks' part, cut to a trust radius of 10 in every σ_tj; Armijo backtracking
//    on D (line_search()). kLbfgs: L-BFGS on the same dual, diag(K)⁻¹ scaling, same line search;
//    kAuto uses it when D = Σ_t m_t exceeds `newton_limit`.
//  - Stopping: every |r_tj| ≤ `tolerance` and every inner residual |v − log(1 − μ)| ≤
//    `inner.tolerance`. Where D's change is below its floating-point resolution, a step is
//    accepted when it lowers ‖r‖. With several γ-scans (cv) the inner solves are inexact while ‖r‖
//    is large (inner tolerance 1e-2 ‖r‖∞, down to `inner.tolerance`).
//  - Theorem 3 (eq 91) changes no table: reweight() adds Δγ[1 + log(1 − μ^i_t(j))] − Δβ[1 + log q⁰_tj]
//    to each track's offsets δ^i_t(j) and moves σ_tj by −Δβ[1 + log q⁰_tj] (eq 137); the previous
//    solution then stays exactly optimal (the next solve takes no step).
//  - A newly appended scan (sequential methods) is first solved alone with the other scans fixed
//    (`presolve`: block Newton, which reads no table).
// Background: docs/models/column-dual-newton.md
#include <deque>
#include <span>
#include <vector>

#include "algorithms/multi_scan/tilted_track.hpp"
#include "harness/core/solve_report.hpp"
#include "harness/multi_scan/problem.hpp"

namespace dabench {

enum class DualMethod {
  kAuto,    // Newton if D ≤ newton_limit, else L-BFGS
  kNewton,  // damped Newton with the exact matrix K
  kLbfgs,   // L-BFGS (Hessian-free)
};

struct ColumnDualSettings {
  DualMethod method = DualMethod::kAuto;
  double tolerance = 1e-12;      // largest column residual |Σ_i μ + q⁰ − 1| at which a solve stops
  int max_iterations = 500;      // Newton (or L-BFGS) iterations per solve; converged = false at the cap
  InnerSolveSettings inner;      // the tracks' inner solves on scans with γ > 0
  int newton_limit = 1500;       // kAuto: Newton while D = Σ_t m_t ≤ this
  int lbfgs_memory = 12;         // (s, y) pairs kept by L-BFGS
  bool presolve = true;          // solve a newly appended scan's duals alone first
  double presolve_tolerance = 1e-6;  // ... until its largest column residual is below this
};

class ColumnDualSolver {
 public:
  // Strong duality with an attained dual maximum needs a strictly feasible point; "every track
  // misses every scan" is one when every track can miss in every scan (a hypothesis that
  // survives all scans with ψ_t(A, 0) > 0). Without it (say a track that must take measurement
  // j) the maximising σ_t(j) is at infinity; such problems go to Algorithm 2.
  static bool applicable(const MultiScanProblem& problem);

  // Starts a problem with the tracks and priors of `problem` and no scans.
  void start(const MultiScanProblem& problem);
  // Appends a scan with γ = 0, β = 1 (until reweight()) and σ = 0. Its factors are read from
  // `scan`, which must outlive the solver's use of the problem.
  void append_scan(const ScanFactors& scan);
  int scans() const { return static_cast<int>(scans_.size()); }
  // False if some track has no hypothesis left with nonzero weight (no feasible event).
  bool feasible() const;

  // Sets (γ_t, β_t) for every scan; scans solved before get the Theorem-3 modification (91).
  void reweight(const std::vector<double>& gamma, const std::vector<double>& beta);

  // Maximises the dual from the current σ. Adds the iterations on the full dual to
  // report.iterations (the presolve's block steps are not counted) and the backtracking steps
  // to report.line_search_steps; sets report.residual and report.inner_residual (the largest
  // over the solves so far); clears report.converged at the iteration cap; sets
  // report.skipped = "numerical" if the dual cannot be evaluated (at the start or at any later
  // point, or its residual is not finite at the end).
  void solve(const ColumnDualSettings& settings, SolveReport& report);

  // q^i(A) and q^{i,j}_t at the last evaluation; only after a solve that was not skipped (a
  // failed evaluation leaves the tracks without beliefs).
  void write_beliefs(MultiScanBeliefs& beliefs) const;

  // For optimality checks: the pair beliefs q^i_t(A, a) (rows: the problem's hypotheses),
  // q⁰_t(j) = e^{−σ_tj/β_t − 1}, and the dual value D at the last evaluation (equal to the
  // minimum of (63), with the modified factors ψ̄ of (91), at the solution).
  RowMatrix pair_belief(int track, int scan) const { return tracks_[track].pair_belief(scan); }
  Vector clutter(int scan) const;
  double dual_value() const { return value_; }

 private:
  struct Scan {
    int measurements = 0;
    int offset = 0;          // first index of this scan's duals in the stacked vector
    double gamma = 0.0;
    double beta = 1.0;
    bool solved = false;     // has a solution that reweight() must preserve
  };

  // D at σ (value_) with the tracks' inner solves; `extra_inner_scan` joins every track's inner
  // set. False if not finite.
  [[nodiscard]] bool evaluate_value(const Vector& sigma, int extra_inner_scan = -1);
  [[nodiscard]] bool evaluate_inner_value(const Vector& sigma);  // the same after σ changed on the inner sets only
  void finish_gradient();                         // gradient_ at the last evaluation
  [[nodiscard]] bool evaluate(const Vector& sigma) { return evaluate_value(sigma) && (finish_gradient(), gradient_.allFinite()); }
  double clutter_value(const Vector& sigma) const;  // −Σ_tj (β_t q⁰_tj + σ_tj)
  void split(const Vector& sigma);                  // stacked σ → per-scan vectors for the tracks
  double largest_inner_residual() const;
  void newton_direction(Vector& direction);
  void lbfgs_direction(Vector& direction);
  // Adds the last step's pair (s = trial_ − σ, y = −(r change)) to the L-BFGS memory when its
  // curvature is positive, keeping the `memory` newest.
  void remember_step(int memory);
  // Backtracking line search along direction_ (ascent slope `slope` = r · direction_): true with
  // the accepted point in trial_ and the tracks, value_ and gradient_ evaluated there.
  [[nodiscard]] bool line_search(double slope, SolveReport& report);
  void diagonal_scaling(Vector& scaling) const;     // 1 / diag(K)
  // The solve's first evaluation at σ, after the presolve of a lone new scan where it applies;
  // false if not finite.
  [[nodiscard]] bool evaluate_start(SolveReport& report);
  // Block Newton on the duals of `scan` alone; true if the tracks hold σ's evaluation after it.
  [[nodiscard]] bool presolve(int scan, SolveReport& report);
  bool only_gamma_scan(int t) const;  // no scan but t has γ > 0

  std::vector<TiltedTrack> track_pool_;  // kept between problems (with their buffers)
  std::span<TiltedTrack> tracks_;         // the current problem's tracks
  std::vector<Scan> scans_;
  std::vector<int> offsets_;
  Vector sigma_;                      // σ, stacked over scans
  std::vector<Vector> sigma_by_scan_;
  Vector gradient_;                   // r at the last evaluation
  double value_ = 0.0;                // D at the last evaluation
  std::vector<TrackEvaluation> evaluations_;
  ColumnDualSettings settings_;
  Eigen::MatrixXd matrix_;            // K
  Vector matrix_sigma_;               // σ at which the tracks' inner sensitivities were taken
  // The outer iteration's direction and trial point, and the L-BFGS memory: (s, y) pairs of −D.
  Vector direction_, trial_, previous_gradient_, scaling_, step_;
  std::deque<std::pair<Vector, Vector>> lbfgs_history_;
  std::vector<double> lbfgs_alpha_;
};

}  // namespace dabench
