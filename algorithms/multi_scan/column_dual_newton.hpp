#pragma once
// The reduced column-dual solver for the multiple-scan convex free energy (63) of Williams & Lau,
// "Multiple scan data association by convex variational inference" (multiscan-convex-variational):
// the same minimiser as Algorithm 2 (convex_variational.hpp), reached by damped Newton on a
// concave dual with one variable per measurement instead of primal–dual coordinate ascent over
// the particle tables. Derivation (from ../shared/multiscan-fast-solver.md §2–3, rechecked here):
//  1. Each track is a star tree (A, one a_t per scan), so for fixed association marginals μ^i its
//     Bethe entropy −H(A) − Σ_t H(a_t | A) is its exact entropy, and minimising (63) over the
//     pair beliefs leaves A_i*(μ^i), the conjugate of the track's log partition function
//     log Z_i(θ) = log Σ_A ψ^i(A) Π_t Σ_a ψ^i_t(A, a) e^{θ_t(a)} (Wainwright & Jordan, Thm 3.4).
//     (63) becomes: minimise Σ_i F_i(μ^i) + Σ_t β_t Σ_j q⁰_tj log q⁰_tj subject to the column
//     constraints (61) Σ_i μ^i_t(j) + q⁰_tj = 1, with
//       F_i = A_i* − Σ_t γ_t Σ_j (1 − μ^i_t(j)) log(1 − μ^i_t(j));
//     the row constraints (62) hold by construction.
//  2. F_i is strictly convex if Σ_t γ_t < 1: −H(q) = −(1 − Σγ) H(q) − Σ_t γ_t H(rest | a_t)
//     − Σ_t γ_t H(a_t), and each γ_t [−H(a_t) − Σ_j (1 − μ_j) log(1 − μ_j)] is convex on the
//     simplex (Vontobel, Thm 20, as in the paper's proof of Lemma 3). This re-derives (64).
//  3. Dualising only (61), with multipliers σ_t(j) (the σ of (132)–(133)): the dual
//       D(σ) = Σ_i min_μ [F_i(μ) + ⟨σ, μ⟩] − Σ_tj [β_t q⁰_tj + σ_tj],  q⁰_tj = e^{−σ_tj/β_t − 1} (133),
//     is concave and C¹ with gradient r_tj = Σ_i μ^i_t(j) + q⁰_tj − 1, and strong duality holds
//     with an attained maximum when every track can miss in every scan (the Slater point "every
//     track misses": not in general, as the notes have it — a track that must take measurement j
//     pushes σ_tj to +∞; applicable() sends such problems to Algorithm 2). The inner minimum of track i is the
//     tilted posterior of tilted_track.hpp (θ = −σ on scans with γ = 0; on the others θ solves
//     θ = −σ − γ[1 + log(1 − μ(θ))], the analogue of (132), by the track's inner Newton).
//  4. −∇²D = K = Σ_i K_i + diag(q⁰/β), with K_i ⪰ 0 the derivative of track i's marginals
//     through its inner solve (tilted_track.hpp), so K ≻ 0: damped Newton with Armijo
//     backtracking on D converges from any start and quadratically near the maximiser (Boyd &
//     Vandenberghe §9.5). At the maximiser every condition of (56)–(62) and (132)–(133) holds,
//     so its beliefs are the minimiser of (63) that Algorithm 2 approaches.
// The step is not the plain Δσ = K⁻¹ r: D's clutter part C(σ) = −Σ_tj [β_t q⁰_tj + σ_tj] has
// curvature q⁰/β, and on the past scans of cvs (β ≈ 0.01) a plain step of a few units in σ
// multiplies q⁰ by e^{hundreds} (most of the damped phase the notes report). The step maximises
// a model that keeps C exact and quadratises only the tracks' part (newton_direction()), and is
// cut to a trust radius of 10 in every σ_tj, which the model needs where every track's
// indicator of an association is all but certain (its curvature there is ~1e-30).
// Theorem 3 (eq 91) changes no table: reweight() adds Δγ[1 + log(1 − μ^i_t(j))] − Δβ[1 + log q⁰_tj]
// to the track's offsets δ^i_t(j) and moves σ_tj by −Δβ[1 + log q⁰_tj] (eq 137), after which the
// previous solution is exactly optimal (the next solve takes no Newton step).
//
// Hessian-free variant (method kLbfgs): L-BFGS on the same dual (Liu & Nocedal 1989), with the
// diagonal of K as initial inverse-Hessian scaling and the same line search. It needs only the
// gradient, so its cost does not grow with D²; kAuto uses it when the number of column duals
// D = Σ_t m_t exceeds `newton_limit` (1500). Newton's matrix costs about (mass-carrying
// hypotheses) × (associations per hypothesis)² per track plus a few D³/3 Cholesky factors per
// step, so the switch is set where the factors (≈ 10⁹ flops at D = 1500) start to cost more
// than the passes L-BFGS repeats (an estimate, not a measurement). Newton against L-BFGS on the
// same trials: bearings_trial/cvs_newton, cvs_lbfgs, cv_newton, cv_lbfgs in
// bench/multi_scan/bench_multi_scan.cpp.
//
// Engineering (none of it changes the maximiser): a line-search trial first evaluates D only (the
// scans outside the tracks' inner sets are read once); the marginals of those scans — a second
// read — are computed only for the point kept. The inner unknowns of a trial start from their
// first-order prediction (∂v/∂σ from the Newton matrix). With one γ-scan (cvs) the inner solves
// read no table (tilted_track.hpp); with several (cv) they are inexact while ‖r‖ is large (an
// inexact Newton method: inner tolerance 1e-2 ‖r‖∞, down to `inner.tolerance` at the end). When
// one scan was appended since the last solve (the sequential methods), its duals are first solved
// alone with the other scans fixed (`presolve`: block Newton, which reads no table either), which
// removes most of the damped phase of the full iteration. Costs: benchmark bearings_trial in
// bench/multi_scan/bench_multi_scan.cpp.
//
// Stopping: the largest column residual |r_tj| below `tolerance` and every inner residual
// |v − log(1 − μ)| below `inner.tolerance`. Near the maximiser D changes by less than its
// floating-point resolution; a step is then accepted when it lowers ‖r‖ instead.
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
