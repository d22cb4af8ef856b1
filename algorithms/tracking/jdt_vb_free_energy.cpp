// JDT-VB: the free energy B (algorithms/tracking/jdt_vb.hpp) and its terms per scan and per track.
#include "algorithms/tracking/jdt_vb_run.hpp"

#include <algorithm>

namespace dabench::jdt_vb_detail {

// H_Bethe(q(A_k)) = Σ_rows H(row) + Σ_columns H(column) − Σ_pairs H_binary(E[a]).
double Run::bethe_entropy(const ScanAssociation& scan) const {
  const auto& r = scan.result;
  double h = 0.0;
  for (int p = 0; p < scan.pseudo_targets(); ++p) h -= xlogx(r.miss[p]);
  for (int c = 0; c < static_cast<int>(scan.columns.size()); ++c) h -= xlogx(r.clutter[c]);
  for (int p = 0; p < scan.pseudo_targets(); ++p)
    for (int j : scan.gate[p]) {
      const int c = scan.column_of(j);
      const double b = r.detection(p, c);
      h -= 2.0 * xlogx(b);                  // in its row and in its column
      h += xlogx(b) + xlogx(1.0 - b);       // minus its binary entropy
    }
  return h;
}

// Σ_j E[a^{0,j}] log λ of one scan (measurements outside every gate are clutter).
double Run::association_energy(const ScanAssociation& scan, int k) const {
  const int outside = static_cast<int>(problem_.scans[k].cols()) - static_cast<int>(scan.columns.size());
  return (scan.result.clutter.sum() + outside) * log_clutter_density_;
}

// The terms of B that depend on q(x_i): Σ_{k,τ,j} E[a] E log N(y_j | h^τ(x_k), R) (linearised as
// in eq 43), E log p(x_i) and H(q(x_i)) of the Gauss–Markov chain with these marginals.
double Run::track_kinematic_terms(int track, const std::vector<Gaussian>& marginal,
                                  const std::vector<Eigen::MatrixXd>& coupling) const {
  const TrackRecord& t = tracks_[track];
  double b = 0.0;
  for (int k = t.first; k <= t.last; ++k) {
    const ScanAssociation& scan = scans_[k];
    const int first_pseudo = first_pseudo_of(track, k);
    const Gaussian& x = marginal[k - t.first];
    for (int tau = 0; tau < paths_; ++tau) {
      const int p = first_pseudo + tau;
      if (scan.gate[p].empty()) continue;
      const Eigen::LLT<Eigen::MatrixXd>& r = noise_[tau];
      const Vector predicted = sensor_.measure(tau, x.mean);
      const Eigen::MatrixXd h = sensor_.jacobian(tau, x.mean);
      const double constant = -0.5 * (static_cast<double>(predicted.size()) * kLog2Pi + log_det(r) +
                                      r.solve(h * x.covariance * h.transpose()).trace());
      for (int j : scan.gate[p]) {
        const int c = scan.column_of(j);
        const Vector d = problem_.scans[k].col(j) - predicted;
        b += scan.result.detection(p, c) * (constant - 0.5 * d.dot(r.solve(d)));
      }
    }
  }
  // E log N(x_first | head) and the transitions; entropy of the chain.
  const int n = sensor_.state_dim();
  const Eigen::LLT<Eigen::MatrixXd> head(t.head.covariance);
  const Vector d0 = marginal[0].mean - t.head.mean;
  b -= 0.5 * (head.solve(marginal[0].covariance).trace() + d0.dot(head.solve(d0)) + n * kLog2Pi + log_det(head));
  const double entropy_constant = 0.5 * n * (1.0 + kLog2Pi);
  for (int k = 0; k + 1 < t.length(); ++k) {
    const Gaussian& now = marginal[k];
    const Gaussian& next = marginal[k + 1];
    const Eigen::MatrixXd& c = coupling[k];
    Eigen::LLT<Eigen::MatrixXd> conditional(now.covariance - c * next.covariance.llt().solve(c.transpose()));
    if (conditional.info() != Eigen::Success) return -HUGE_VAL;  // not a valid joint Gaussian
    const Vector d = next.mean - transition_ * now.mean;
    const Eigen::MatrixXd fc = transition_ * c;
    const Eigen::MatrixXd second = next.covariance - fc.transpose() - fc + transition_ * now.covariance * transition_.transpose() + d * d.transpose();
    b -= 0.5 * (process_.solve(second).trace() + n * kLog2Pi + log_det(process_));
    b += entropy_constant + 0.5 * log_det(conditional);
  }
  b += entropy_constant + 0.5 * log_det(Eigen::LLT<Eigen::MatrixXd>(marginal.back().covariance));
  return b;
}

// E log p(s_i) + Σ_k E ξ_k(s_k) + H(q(s_i)) from the chain's single and pairwise marginals.
double Run::track_meta_terms(int track) const {
  const TrackRecord& t = tracks_[track];
  const auto& q = t.meta;
  const double stay = std::log(o_.stay), move = std::log1p(-o_.stay);
  double b = 0.0;
  const double a0 = q.active[0];
  if (a0 > 0.0) b += a0 * std::log(t.initial_active);
  if (a0 < 1.0) b += (1.0 - a0) * std::log1p(-t.initial_active);
  for (int k = t.first; k <= t.last; ++k) {
    const ScanAssociation& scan = scans_[k];
    const int first_pseudo = first_pseudo_of(track, k);
    const auto xi = meta_evidence(scan, first_pseudo);
    const double a = q.active[k - t.first];
    b += a * xi[1] + (1.0 - a) * xi[0];
  }
  for (int k = 0; k + 1 < t.length(); ++k) {
    const auto& pair = q.pairwise[k];
    b += (pair[0] + pair[3]) * stay + (pair[1] + pair[2]) * move;
    for (double v : pair) b -= xlogx(v);
    if (k > 0) b += xlogx(q.active[k]) + xlogx(1.0 - q.active[k]);
  }
  if (t.length() == 1) b -= xlogx(a0) + xlogx(1.0 - a0);
  return b;
}

double Run::free_energy() const {
  double b = 0.0;
  for (int k = 0; k < problem_.scan_count(); ++k) b += association_energy(scans_[k], k) + bethe_entropy(scans_[k]);
  for (int i : batch_) b += track_kinematic_terms(i, tracks_[i].marginal, tracks_[i].coupling) + track_meta_terms(i);
  return b;
}

}  // namespace dabench::jdt_vb_detail
