#pragma once
// The Newton-matrix part of a TiltedTrack (tilted_track.hpp): the track's block of the column-dual
// solver's Newton matrix, −∂μ/∂σ with the inner solve eliminated,
//   K_i = Σ + Σ_{:,Γ} (I − G S_ΓΓᵀ)⁻¹ G S_{:,Γ}ᵀ,   S = Σ_{:,Γ} diag(1/(1 − μ_Γ)),  G = diag(γ),
// where Σ is the covariance of the association indicators 1[a_t = j] under the tilted posterior
// q: closed form within a scan, summed over the hypotheses across scans. The matrix only steers
// the steps (the gradient is exact), so the sums run over the hypotheses with q(A) ≥ 1e-8 and,
// per hypothesis, over the associations of its candidate list with √q(A) p_t(j | A) ≥ 1e-8, and
// span the track's active associations (μ_t(j) ≥ 1e-12; the others would add O(μ)). The same
// cross-scan Σ gives the track's inner Newton solve its Jacobian when several scans are inner.
// Also keeps the first-order model of the inner unknowns around the last matrix point
// (∂v_Γ/∂σ), which guess_inner() uses to warm-start the next evaluation.
#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "harness/core/matrix_types.hpp"

namespace dabench {

class TiltedTrack;

class TrackNewtonMatrix {
 public:
  // Below this 1 − μ_t(j), the γ-column j carries no cross-scan terms (see add()).
  static constexpr double kSmallComplement = 1e-6;
  // Associations less likely than this for a track (μ_t(j) < 1e-12) change its Newton matrix and
  // inner Jacobian by O(μ) only: they take no part in their dense solves.
  static inline const double kLogActiveFloor = std::log(1e-12);

  // The track's scans or hypotheses changed: the candidate lists and the inner model are stale.
  void invalidate() {
    candidates_valid_ = false;
    sensitivity_valid_ = false;
  }

  // Adds the track's K_i to `matrix` (D × D over every scan's measurements, scan t from
  // `offsets[t]`) at its last evaluation (after finish()); records ∂v/∂σ for guess_inner().
  void add(const TiltedTrack& track, const std::vector<int>& offsets, Eigen::MatrixXd& matrix);
  // Adds −∂μ_t/∂σ_t for scan t alone (the others fixed; t the only scan of the inner set), closed form.
  static void add_block(const TiltedTrack& track, int t, int offset, Eigen::MatrixXd& matrix);
  // Sets the track's inner unknowns to their first-order prediction at σ = σ_matrix + `step`
  // (stacked like the matrix), σ_matrix being the point of the last add().
  void guess_inner(TiltedTrack& track, const Vector& step);

  // Σ over the active associations (μ ≥ 1e-12) of `track`'s last evaluation, stacked with scan t
  // from offsets[t] (`size` entries in all): into covariance(), with the active associations'
  // stacked indices in active_index() and each stacked index's position among them (−1: not
  // active) in active_position().
  void covariance(const TiltedTrack& track, const std::vector<int>& offsets, int size);
  [[nodiscard]] const Eigen::MatrixXd& covariance() const { return active_covariance_; }
  [[nodiscard]] const std::vector<int>& active_position() const { return active_position_; }

 private:
  // Per kept hypothesis, over all scans in order, the associations j ≥ 1 whose factor is within
  // the track's candidate floor of its row's largest (the scans' candidate lists, merged): the
  // only ones that can reach the matrix's entry floor at moderate tilts. Rebuilt after a scan is
  // appended.
  struct Candidate {
    int scan;
    int column;
    double factor;
  };
  void build_candidates(const TiltedTrack& track);

  std::vector<int> candidate_start_;  // kept + 1 offsets into candidates_
  std::vector<Candidate> candidates_;
  bool candidates_valid_ = false;
  // Σ over the active associations and what it was summed from.
  std::vector<int> active_index_;     // stacked index of each active association
  std::vector<int> active_position_;  // stacked index → position among the active, or −1
  std::vector<int> active_scan_;      // scan of each active association
  Vector active_mu_;                  // μ of each active association
  Eigen::MatrixXd active_covariance_;
  std::vector<int> entry_position_;   // one hypothesis's entries so far: active position, p_t(j | A)
  std::vector<double> entry_probability_;
  std::vector<double> inverse_evidence_;     // row-major kept × scans: 1 / s̃_t(A)
  std::vector<const double*> tilt_of_scan_;  // e^{τ_t − c_t} per scan
  std::vector<double> cross_scan_moments_;   // row-major active²: Σ_A q p_k p_l, k in a later scan than l
  std::vector<int> gamma_column_;     // the γ-columns: active inner unknowns of the γ-scans
  // First-order model of the inner unknowns around the last Newton-matrix point.
  Eigen::MatrixXd inner_sensitivity_;     // ∂v_Γ/∂σ: active γ-unknowns × active associations
  std::vector<int> sensitivity_rows_;     // the rows' positions among the stacked inner unknowns
  std::vector<int> sensitivity_columns_;  // the columns' stacked σ indices
  Vector inner_base_;                     // v at that point
  Vector guess_;                          // the predicted inner unknowns
  bool sensitivity_valid_ = false;
};

}  // namespace dabench
