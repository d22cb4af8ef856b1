#include "algorithms/multi_scan/track_newton_matrix.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "algorithms/multi_scan/tilted_track.hpp"

namespace dabench {

namespace {

// Hypotheses with q(A) below this (normalised) are left out of the Newton matrix's cross-scan sums.
constexpr double kMatrixMassFloor = 1e-8;
// Association probabilities p_t(j | A) below this are left out of the cross-scan sums (an
// absolute error below 1e-9 of the entry's own marginal: the matrix only steers the Newton step).
constexpr double kMatrixEntryFloor = 1e-9;
// Hypotheses contribute the entries with √q(A) p_t(j | A) above this to the cross-scan sums.
constexpr double kMatrixWeightFloor = 1e-8;

}  // namespace

void TrackNewtonMatrix::build_candidates(const TiltedTrack& track) {
  const auto kept = static_cast<Eigen::Index>(track.kept_.size());
  candidate_start_.assign(1, 0);
  candidates_.clear();
  for (Eigen::Index a = 0; a < kept; ++a) {
    for (int t = 0; t < track.scans(); ++t) {
      const TiltedTrack::Scan& scan = track.scans_[t];
      for (int c = scan.candidate_start[a]; c < scan.candidate_start[a + 1]; ++c) {
        candidates_.push_back({t, scan.candidate_column[c], scan.candidate_factor[c]});
      }
    }
    candidate_start_.push_back(static_cast<int>(candidates_.size()));
  }
  candidates_valid_ = true;
}

void TrackNewtonMatrix::covariance(const TiltedTrack& track, const std::vector<int>& offsets, int size) {
  // Σ over the active associations (μ ≥ 1e-12; the others' entries are O(μ)): within a
  // scan closed form, across scans E[p_k(A) p_l(A)] − μ_k μ_l with the sums over the hypotheses
  // that carry mass, from each hypothesis's candidate associations,
  // p_t(j | A) = ψ_t(A, j) e^{τ_t(j) − c_t} / s̃_t(A). Entries come in scan order, so the pairs
  // across scans are those with an entry of an earlier scan.
  if (!candidates_valid_) build_candidates(track);
  active_index_.clear();
  active_position_.assign(static_cast<std::size_t>(size), -1);
  for (int t = 0; t < track.scans(); ++t) {
    for (int j = 0; j < track.scans_[t].measurements; ++j) {
      if (track.scans_[t].log_marginal[j + 1] < kLogActiveFloor) continue;
      active_position_[offsets[t] + j] = static_cast<int>(active_index_.size());
      active_index_.push_back(offsets[t] + j);
    }
  }
  const auto active = static_cast<Eigen::Index>(active_index_.size());
  const auto kept = static_cast<Eigen::Index>(track.kept_.size());
  const double inverse_total = std::exp(-track.log_total_);
  entry_position_.resize(static_cast<std::size_t>(active));
  entry_probability_.resize(static_cast<std::size_t>(active));
  cross_scan_moments_.assign(static_cast<std::size_t>(active) * static_cast<std::size_t>(active), 0.0);
  const int scan_count = track.scans();
  tilt_of_scan_.resize(static_cast<std::size_t>(scan_count));
  for (int t = 0; t < scan_count; ++t) tilt_of_scan_[t] = track.scans_[t].tilt.data();
  inverse_evidence_.resize(static_cast<std::size_t>(kept) * static_cast<std::size_t>(scan_count));
  for (int t = 0; t < scan_count; ++t) {
    const double* column = track.evidence(t);
    for (Eigen::Index a = 0; a < kept; ++a) inverse_evidence_[a * scan_count + t] = 1.0 / column[a];
  }
  for (Eigen::Index a = 0; a < kept; ++a) {
    const double q = track.product_[a] * inverse_total;
    if (q < kMatrixMassFloor) continue;
    // An entry enters if √q p ≥ kMatrixWeightFloor: the pairs left out change an entry of the
    // matrix by at most kMatrixWeightFloor Σ_A √q(A) ≤ kMatrixWeightFloor √H.
    const double entry_floor = std::max(kMatrixEntryFloor, kMatrixWeightFloor / std::sqrt(q));
    if (entry_floor > 1.0) continue;
    int count = 0, scan = -1, scan_first = 0;
    double inverse = 0.0;
    for (int c = candidate_start_[a]; c < candidate_start_[a + 1]; ++c) {
      const Candidate& candidate = candidates_[c];
      if (candidate.scan != scan) {
        scan = candidate.scan;
        scan_first = count;
        inverse = inverse_evidence_[a * scan_count + scan];
      }
      const int position = active_position_[offsets[scan] + candidate.column - 1];
      if (position < 0) continue;
      const double p = candidate.factor * tilt_of_scan_[scan][candidate.column] * inverse;
      if (p < entry_floor) continue;
      const double qp = q * p;
      double* row = cross_scan_moments_.data() + static_cast<std::size_t>(position) * static_cast<std::size_t>(active);
      for (int y = 0; y < scan_first; ++y) row[entry_position_[y]] += qp * entry_probability_[y];
      entry_position_[count] = position;
      entry_probability_[count] = p;
      ++count;
    }
  }
  Eigen::MatrixXd& sigma = active_covariance_;
  sigma.resize(active, active);
  Vector& mu = active_mu_;
  mu.resize(active);
  std::vector<int>& scan_of = active_scan_;
  scan_of.resize(static_cast<std::size_t>(active));
  for (Eigen::Index k = 0; k < active; ++k) {
    int t = 0;
    while (t + 1 < scan_count && offsets[t + 1] <= active_index_[k]) ++t;
    scan_of[k] = t;
    mu[k] = std::exp(track.scans_[t].log_marginal[active_index_[k] - offsets[t] + 1]);
  }
  for (Eigen::Index k = 0; k < active; ++k) {
    const TiltedTrack::Scan& scan = track.scans_[scan_of[k]];
    const int j = active_index_[k] - offsets[scan_of[k]];
    for (Eigen::Index l = 0; l < k; ++l) {
      sigma(k, l) = scan_of[l] == scan_of[k] ? -mu[k] * mu[l]
                                             : cross_scan_moments_[static_cast<std::size_t>(k) * static_cast<std::size_t>(active) + l] - mu[k] * mu[l];
      sigma(l, k) = sigma(k, l);
    }
    sigma(k, k) = std::exp(scan.log_marginal[j + 1] + scan.log_complement[j]);  // μ(1 − μ)
  }
}

void TrackNewtonMatrix::add(const TiltedTrack& track, const std::vector<int>& offsets, Eigen::MatrixXd& matrix) {
  covariance(track, offsets, static_cast<int>(matrix.rows()));
  Eigen::MatrixXd& full = active_covariance_;
  const auto active = static_cast<Eigen::Index>(active_index_.size());
  // The γ-columns (active inner unknowns of the γ-scans): S = Σ_{:,Γ} / (1 − μ_Γ).
  gamma_column_.clear();
  for (Eigen::Index k = 0; k < active; ++k) {
    const TiltedTrack::Scan& scan = track.scans_[active_scan_[k]];
    if (track.is_inner(scan, active_index_[k] - offsets[active_scan_[k]])) gamma_column_.push_back(static_cast<int>(k));
  }
  const auto count = static_cast<Eigen::Index>(gamma_column_.size());
  const auto scatter = [&](const Eigen::MatrixXd& block) {
    for (Eigen::Index c = 0; c < active; ++c) {
      for (Eigen::Index r = 0; r < active; ++r) matrix(active_index_[r], active_index_[c]) += block(r, c);
    }
  };
  if (count == 0) {
    scatter(full);
    sensitivity_valid_ = false;
    return;
  }
  Vector complement(count), gamma(count);
  for (Eigen::Index c = 0; c < count; ++c) {
    const int k = gamma_column_[c];
    const TiltedTrack::Scan& scan = track.scans_[active_scan_[k]];
    complement[c] = std::exp(scan.log_complement[active_index_[k] - offsets[active_scan_[k]]]);
    gamma[c] = scan.gamma;
    // Where 1 − μ_t(j) is small, the association is all but certain and Σ_{:,j} lives on that
    // scale: its cross-scan entries are differences of O(1) sums, noise once divided by 1 − μ.
    // They are dropped there; every entry they touch is itself of order 1 − μ_t(j), so the
    // matrix only loses accuracy in directions whose residuals are that small.
    if (complement[c] >= kSmallComplement) continue;
    for (Eigen::Index l = 0; l < active; ++l) {
      if (active_scan_[l] != active_scan_[k]) full(l, k) = full(k, l) = 0.0;
    }
  }
  Eigen::MatrixXd scaled(active, count);  // S_{:,Γ}
  for (Eigen::Index c = 0; c < count; ++c) scaled.col(c) = full.col(gamma_column_[c]) / complement[c];
  Eigen::MatrixXd inner(count, count);  // I − G S_ΓΓᵀ
  Eigen::MatrixXd transposed(count, count);  // I − S_ΓΓᵀ G
  for (Eigen::Index r = 0; r < count; ++r) {
    for (Eigen::Index c = 0; c < count; ++c) {
      const double s = scaled(gamma_column_[c], r);  // S_ΓΓ(c, r)
      inner(r, c) = (r == c ? 1.0 : 0.0) - gamma[r] * s;
      transposed(r, c) = (r == c ? 1.0 : 0.0) - s * gamma[c];
    }
  }
  const Eigen::MatrixXd right = gamma.asDiagonal() * scaled.transpose();  // G S_{:,Γ}ᵀ
  Eigen::MatrixXd columns(active, count);
  for (Eigen::Index c = 0; c < count; ++c) columns.col(c) = full.col(gamma_column_[c]);
  const Eigen::MatrixXd correction = columns * inner.partialPivLu().solve(right);
  scatter(full + 0.5 * (correction + correction.transpose()));
  // ∂v_Γ/∂σ = diag(1/(1 − μ_Γ)) K_i[Γ, :] = (I − S_ΓΓᵀ G)⁻¹ S_{:,Γ}ᵀ for guess_inner(), on the
  // active columns; rows mapped to the inner unknowns (stacked over the inner scans).
  inner_sensitivity_ = transposed.partialPivLu().solve(Eigen::MatrixXd(scaled.transpose()));
  sensitivity_columns_ = active_index_;
  sensitivity_rows_.assign(static_cast<std::size_t>(count), -1);
  int stacked = 0;
  for (int t : track.inner_scans_) {
    for (int j = 0; j < track.scans_[t].measurements; ++j, ++stacked) {
      const int position = active_position_[offsets[t] + j];
      if (position < 0) continue;
      const auto found = std::find(gamma_column_.begin(), gamma_column_.end(), position);
      if (found != gamma_column_.end()) sensitivity_rows_[found - gamma_column_.begin()] = stacked;
    }
  }
  track.inner_unknowns(inner_base_);
  sensitivity_valid_ = true;
}

void TrackNewtonMatrix::add_block(const TiltedTrack& track, int t, int offset, Eigen::MatrixXd& matrix) {
  // Σ_tt = diag(μ) − μμᵀ and, if t is a γ-scan, + Σ_tt (I − γ S_ttᵀ)⁻¹ γ S_ttᵀ, S = Σ diag(1/(1 − μ)).
  const TiltedTrack::Scan& scan = track.scans_[t];
  const int m = scan.measurements;
  Eigen::MatrixXd sigma(m, m);
  for (int j = 0; j < m; ++j) {
    sigma(j, j) = std::exp(scan.log_marginal[j + 1] + scan.log_complement[j]);
    for (int l = 0; l < j; ++l) sigma(j, l) = sigma(l, j) = -std::exp(scan.log_marginal[j + 1] + scan.log_marginal[l + 1]);
  }
  if (!(scan.gamma > 0.0)) {
    matrix.block(offset, offset, m, m) += sigma;
    return;
  }
  Eigen::MatrixXd scaled_transposed(m, m);  // S_ttᵀ(j, l) = Σ(l, j) / (1 − μ_j) on the inner unknowns
  for (int j = 0; j < m; ++j) {
    for (int l = 0; l < m; ++l) {
      const bool inner = track.is_inner(scan, j) && track.is_inner(scan, l);
      scaled_transposed(j, l) = !inner ? 0.0
                                : l == j ? std::exp(scan.log_marginal[j + 1])
                                         : -std::exp(scan.log_marginal[j + 1] + scan.log_marginal[l + 1] - scan.log_complement[j]);
    }
  }
  const Eigen::MatrixXd inner = Eigen::MatrixXd::Identity(m, m) - scan.gamma * scaled_transposed;
  const Eigen::MatrixXd correction = sigma * inner.partialPivLu().solve(scan.gamma * scaled_transposed);
  matrix.block(offset, offset, m, m) += sigma + 0.5 * (correction + correction.transpose());
}

void TrackNewtonMatrix::guess_inner(TiltedTrack& track, const Vector& step) {
  if (!sensitivity_valid_) return;
  guess_ = inner_base_;
  for (Eigen::Index r = 0; r < inner_sensitivity_.rows(); ++r) {
    if (sensitivity_rows_[r] < 0 || sensitivity_rows_[r] >= guess_.size()) continue;
    double change = 0.0;
    for (Eigen::Index c = 0; c < inner_sensitivity_.cols(); ++c) change += inner_sensitivity_(r, c) * step[sensitivity_columns_[c]];
    guess_[sensitivity_rows_[r]] = std::min(inner_base_[sensitivity_rows_[r]] + change, 0.0);  // v = log(1 − μ) ≤ 0
  }
  track.set_inner_unknowns(guess_);
}

}  // namespace dabench
