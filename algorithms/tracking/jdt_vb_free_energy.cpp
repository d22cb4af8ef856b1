// JDT-VB: the free energy B (algorithms/tracking/jdt_vb.hpp) from its terms per scan and per
// track (algorithms/tracking/jdt_vb_free_energy_terms.hpp) on the run's state.
#include "algorithms/tracking/jdt_vb_run.hpp"

#include "algorithms/tracking/jdt_vb_free_energy_terms.hpp"

namespace dabench::jdt_vb_detail {

double Run::bethe_entropy(const ScanAssociation& scan) const {
  std::vector<std::vector<int>> gated_columns(scan.pseudo_targets());
  for (int p = 0; p < scan.pseudo_targets(); ++p)
    for (int j : scan.gate[p]) gated_columns[p].push_back(scan.column_of(j));
  return dabench::bethe_entropy(scan.result, gated_columns);
}

// Σ_j E[a^{0,j}] log λ of one scan (measurements outside every gate are clutter).
double Run::association_energy(const ScanAssociation& scan, int k) const {
  const int outside = static_cast<int>(problem_.scans[k].cols()) - static_cast<int>(scan.columns.size());
  return clutter_energy(scan.result.clutter, outside, log_clutter_density_);
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
      const LinearisedLogLikelihood expected_log_likelihood(noise_[tau], sensor_.measure(tau, x.mean),
                                                            sensor_.jacobian(tau, x.mean), x.covariance);
      for (int j : scan.gate[p])
        b += scan.result.detection(p, scan.column_of(j)) * expected_log_likelihood(problem_.scans[k].col(j));
    }
  }
  return add_gauss_markov_energy(b, {marginal, coupling}, {t.head, transition_, process_});
}

// E log p(s_i) + Σ_k E ξ_k(s_k) + H(q(s_i)) from the chain's single and pairwise marginals.
double Run::track_meta_terms(int track) const {
  const TrackRecord& t = tracks_[track];
  std::vector<std::array<double, 2>> evidence;
  for (int k = t.first; k <= t.last; ++k) evidence.push_back(meta_evidence(scans_[k], first_pseudo_of(track, k)));
  return meta_state_energy(t.meta, evidence, t.initial_active, o_.stay);
}

double Run::free_energy() const {
  double b = 0.0;
  for (int k = 0; k < problem_.scan_count(); ++k) b += association_energy(scans_[k], k) + bethe_entropy(scans_[k]);
  for (int i : batch_) b += track_kinematic_terms(i, tracks_[i].marginal, tracks_[i].coupling) + track_meta_terms(i);
  return b;
}

}  // namespace dabench::jdt_vb_detail
