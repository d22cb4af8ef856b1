#pragma once
// One track of the reduced column-dual problem of the multiple-scan convex free energy (63) of
// Williams & Lau, "Multiple scan data association by convex variational inference"
// (multiscan-convex-variational); the solver around it is column_dual_newton.hpp. A track is a
// star tree (hypothesis A, one association a_t per scan), so for fixed association marginals its
// part of (63) is minimised by the tilted posterior
//   q(A, a_1..a_S) ∝ ψ(A) Π_t ψ_t(A, a_t) e^{τ_t(a_t)},   τ_t(0) = 0,
//   τ_t(j) = −σ_t(j) + δ_t(j) − γ_t (1 + v_t(j)),          j ≥ 1,
// with σ the column duals of (61), δ the accumulated Theorem-3 offsets of eq (91) (kept as numbers;
// the tables are never rewritten) and, on the scans with γ_t > 0, the inner unknowns
// v_t(j) = log(1 − μ_t(j)), the track's form of the stationarity condition (132), solved by damped
// Newton on v − log(1 − μ(v)) = 0 (the inner solve).
// Marginals: μ_t(a) = Σ_A q(A) ψ_t(A, a) e^{τ_t(a)} / s_t(A), s_t(A) = Σ_a ψ_t(A, a) e^{τ_t(a)},
// q(A) ∝ ψ(A) Π_t s_t(A).
//
// Passes. Factor tables are column-major (one contiguous column per association). An evaluation
// reads the scans outside the inner set once (their evidence s_t and its product, `rest`), then
// solves the inner equations on the inner set (the γ-scans, plus an `extra_inner_scan` during the
// solver's new-scan presolve). With one inner scan g (as in cvs) that solve reads no table:
//   μ_g(a) = e^{τ_g(a)} U(a) / Σ_b e^{τ_g(b)} U(b),   U(a) = Σ_A rest(A) ψ_g(A, a),
// with U fixed by the other scans. finish() reads the other scans again for their marginals, only
// for points the solver keeps. Newton matrix and the inner Jacobian across scans:
// track_newton_matrix.hpp.
//
// Numerical invariants:
//  - linear domain over the hypotheses, scaled: per scan the tilts are e^{τ − c_t},
//    c_t = max(0, max_j τ_t(j)), and the running product over scans is rescaled by an exact power
//    of two after every scan (no overflow, no underflow of the heaviest hypothesis);
//  - marginals are kept as logarithms (log μ = τ − c_t + log U − log Z), and complements
//    1 − μ_t(j) are log-sums of the other entries, never 1 − x (at γ = 0.95 they reach e^{−100});
//  - hypotheses with ψ(A) = 0 or an all-zero factor row in some scan are dropped from the tables;
//    an association impossible for this track (zero column) takes no part in the inner solve.
// Background: docs/models/column-dual-newton.md
#include <Eigen/Core>
#include <Eigen/LU>
#include <cstdint>
#include <vector>

#include "algorithms/multi_scan/track_newton_matrix.hpp"
#include "harness/core/matrix_types.hpp"

namespace dabench {

using ColumnMatrix = Eigen::MatrixXd;  // column-major

struct InnerSolveSettings {
  double tolerance = 1e-13;  // stop when every |v_t(j) − log(1 − μ_t(j))| is below this
  int max_iterations = 100;  // damped Newton steps per evaluation
};

// What one evaluation of a track did.
struct TrackEvaluation {
  bool finite = true;           // false: the tilts put every hypothesis at probability 0 (or NaN)
  int inner_iterations = 0;     // inner Newton steps taken
  double inner_residual = 0.0;  // max |v − log(1 − μ)| over the inner unknowns at the end
};

class TiltedTrack {
 public:
  // Starts the track with prior ψ(A) over `prior.size()` hypotheses and no scans.
  void start(const Vector& prior);
  // Appends the factors ψ_t(A, a) of a new scan (one row per original hypothesis, column 0 =
  // missed detection), with γ = 0, δ = 0, v = 0. `factor` must outlive the track's use (the
  // tables are re-packed from it when a later scan removes hypotheses).
  void append_scan(const RowMatrix& factor);
  // False if no hypothesis is left (no feasible event for this track).
  bool feasible() const { return !kept_.empty(); }
  int scans() const { return scan_count_; }

  void set_gamma(int t, double gamma) { scans_[t].gamma = gamma; }
  // Adds `shift` to δ_t (Theorem 3: Δγ [1 + log(1 − μ_t(j))] − Δβ [1 + log q⁰_t(j)], eq (91)).
  void add_offset(int t, const Vector& shift) { scans_[t].offset += shift; }

  // Evaluates at column duals σ (`sigma[t]` has m_t entries): every scan's evidence, then the
  // inner solve on the inner set (the scans with γ > 0, and `extra_inner_scan` if ≥ 0), warm-started from
  // the last v. Gives log Z and the inner set's marginals; finish() gives the others'.
  TrackEvaluation evaluate(const std::vector<Vector>& sigma, const InnerSolveSettings& settings,
                           int extra_inner_scan = -1);
  // Re-evaluates after σ changed on the inner set only: the other scans' evidence is reused.
  TrackEvaluation evaluate_inner(const std::vector<Vector>& sigma, const InnerSolveSettings& settings);
  // Marginals of the scans outside the inner set, at the last evaluation (same σ).
  void finish(const std::vector<Vector>& sigma);

  double log_partition() const { return log_partition_; }  // log Z(τ)
  // The track's term of the dual: −log Z − Σ_{γ-scans} γ Σ_j [(1 + v_j) μ_j + (1 − μ_j) log(1 − μ_j)].
  double dual_value() const;
  const Vector& log_marginal(int t) const { return scans_[t].log_marginal; }      // log μ_t(a), a = 0..m_t
  const Vector& log_complement(int t) const { return scans_[t].log_complement; }  // log(1 − μ_t(j)), j = 1..m_t

  // Adds this track's block of the Newton matrix, −∂μ/∂σ with the inner solve eliminated
  // (TrackNewtonMatrix::add), to `matrix` (D × D over every scan's measurements, scan t from
  // `offsets[t]`). Call after finish(). Also records ∂v/∂σ for guess_inner().
  void add_newton_matrix(const std::vector<int>& offsets, Eigen::MatrixXd& matrix);
  // Adds −∂μ_t/∂σ_t for scan t alone (the others fixed; t the only scan of the inner set), closed form.
  void add_block_matrix(int t, int offset, Eigen::MatrixXd& matrix) const;
  // Sets the inner unknowns to their first-order prediction at σ = σ_matrix + `step` (stacked
  // like the matrix), σ_matrix being the point of the last add_newton_matrix().
  void guess_inner(const Vector& step);

  // q(A) for every original hypothesis (0 for dropped ones) and μ_t(a) of scan t.
  void write_belief(Vector& belief) const;
  void write_marginals(int t, double* row) const;
  // The pair beliefs q_t(A, a) of scan t, one row per original hypothesis (for optimality checks).
  RowMatrix pair_belief(int t) const;

 private:
  friend class TrackNewtonMatrix;  // reads the evaluation, sets the inner unknowns

  struct Scan {
    int measurements = 0;
    double gamma = 0.0;
    const RowMatrix* original = nullptr;  // the appended factor (all hypotheses), to re-pack
    std::vector<double> factor;           // ψ_t(A, a), kept hypotheses × (m + 1), column-major
    // Its candidate associations per kept hypothesis (compressed rows; the Newton matrix's
    // cross-scan sums read only these, see TrackNewtonMatrix).
    std::vector<int> candidate_start;
    std::vector<int> candidate_column;
    std::vector<double> candidate_factor;
    Vector offset;                        // δ_t(j), j = 1..m
    Vector inner_log_complement;          // v_t(j), j = 1..m: inner unknowns where γ > 0, log(1 − μ_t(j)) once solved
    std::vector<char> possible;           // column j ≥ 1 is nonzero for some kept hypothesis
    // Last evaluation.
    double shift = 0.0;                   // c_t
    Vector log_tilt;                      // τ_t(a) − c_t, a = 0..m
    Vector tilt;                          // e^{τ_t(a) − c_t}
    Vector log_marginal;                  // log μ_t(a)
    Vector log_complement;                // log(1 − μ_t(j)), j = 1..m
    bool inner = false;                   // in the inner set
  };

  void repack();
  void pack(Scan& scan) const;                      // factor table, its candidates, `possible`
  bool is_inner(const Scan& scan, int j) const { return scan.gamma > 0.0 && scan.possible[j]; }
  void set_tilts(int t, const Vector& sigma);
  [[nodiscard]] bool multiply_evidence(int t, Vector& product, double& log_scale, double& pending);  // evidence of t into the product
  [[nodiscard]] bool inner_pass(const std::vector<Vector>& sigma);  // inner set at the current v: log Z, its marginals
  void form_product(const std::vector<Vector>& sigma);  // product_ = rest_ × the inner scans' evidence
  void scan_marginals(int t);
  TrackEvaluation inner_solve(const std::vector<Vector>& sigma, const InnerSolveSettings& settings);
  double inner_residual(Vector& residual) const;
  void inner_step(const Vector& residual, bool refresh, Vector& step);
  void inner_unknowns(Vector& v) const;  // the inner scans' v, stacked in inner_scans_ order
  void set_inner_unknowns(const Vector& v);

  // Storage is kept between problems (scans_ beyond scan_count_, and every buffer's capacity),
  // so that a run's solver allocates nothing after its first trials.
  std::vector<Scan> scans_;
  int scan_count_ = 0;
  Vector prior_;                 // ψ(A), all original hypotheses
  std::vector<int> kept_;        // original index of each kept hypothesis
  Vector weight_;                // ψ(A) / max ψ over the kept hypotheses
  double log_weight_scale_ = 0.0;
  std::vector<int> inner_scans_;
  std::vector<int> other_scans_;
  std::vector<double> evidence_;  // s̃_t(A) = Σ_a ψ_t(A, a) e^{τ_t(a) − c_t}, column-major kept × scans
  Eigen::Index kept_rows() const { return static_cast<Eigen::Index>(kept_.size()); }
  double* evidence(int t) { return evidence_.data() + static_cast<std::size_t>(t) * kept_.size(); }
  const double* evidence(int t) const { return evidence_.data() + static_cast<std::size_t>(t) * kept_.size(); }
  Vector rest_;                  // ψ(A) Π_{t ∉ inner} s̃_t(A), scaled
  double rest_log_scale_ = 0.0;  // log of the factor the scaled rest_ omits
  Vector rest_sums_;             // U(a) = Σ_A rest(A) ψ_g(A, a) when the inner set is one scan g
  Vector log_rest_sums_;
  Vector product_;               // ψ(A) Π_t s̃_t(A), scaled
  bool product_valid_ = false;   // product_ matches the last evaluation
  double product_log_scale_ = 0.0;
  double log_total_ = 0.0;       // log Σ_A product_(A)
  double log_partition_ = 0.0;
  // Workspace of the passes over the tables.
  struct PassWorkspace {
    Vector column_partial_sums;  // 8 partial sums per column (marginal_pass, column_sums)
    Vector column_sums;          // Σ_A ψ_t(A, a) q(A) / s̃_t(A) per association a (scan_marginals)
    Vector suffix_log_sums;      // log Σ_{b ≥ a} e^{x(b)} (log_sums_without)
  } pass_work_;
  // Workspace of the inner Newton solve, over the stacked inner unknowns.
  struct InnerSolveWorkspace {
    std::vector<int> scan_of, measurement_of;  // per stacked unknown: its scan and measurement
    std::vector<int> active;                   // the unknowns in the dense solve (μ ≥ 1e-12)
    std::vector<int> scan_offsets;             // first stacked index of each scan (all scans)
    Eigen::MatrixXd jacobian;                  // J over the active unknowns
    Eigen::PartialPivLU<Eigen::MatrixXd> jacobian_factor;
    Vector active_residual, active_step;       // −F and the Newton step on the active unknowns
    Vector residual, step, unknowns;           // F(v), the step and v at the current point
    Vector trial_unknowns, trial_residual;     // the line search's point and its F
  } inner_work_;
  TrackNewtonMatrix newton_;
};

}  // namespace dabench
