// JDT-VB Module 1: synthetic measurements (eq 36), the stacked UKF update, per-path smoothers fused
// by eq (32), the joint smoother, and the Gauss–Markov couplings of q(x) where the marginals come
// from no smoother of the model (eq 32, the sequential pass).
#include "algorithms/tracking/jdt_vb_run.hpp"

#include <algorithm>
#include <optional>

#include "algorithms/tracking/gauss_markov_coupling.hpp"

namespace dabench::jdt_vb_detail {

bool synthetic_measurement(const ScanAssociation& scan, const Eigen::MatrixXd& measurements, int p,
                           const Eigen::MatrixXd& noise, ScanMeasurement& out) {
  double mass = 0.0;
  Vector weighted = Vector::Zero(measurements.rows());
  for (int j : scan.gate[p]) {
    const int c = scan.column_of(j);
    const double w = scan.result.detection(p, c);
    mass += w;
    weighted += w * measurements.col(j);
  }
  if (!(mass > kNoMass)) return false;
  out.value = weighted / mass;
  out.covariance = noise / mass;
  return true;
}

// One UKF update with the synthetic measurements (eq 36) of all of a track's paths at scan k,
// stacked (the sequential pass, and each step of joint_smoother).
void Run::ukf_update(Gaussian& x, const ScanAssociation& scan, int first_pseudo, int k) const {
  std::vector<int> used;
  std::vector<ScanMeasurement> synthetic;
  for (int t = 0; t < paths_; ++t) {
    ScanMeasurement m;
    if (synthetic_measurement(scan, problem_.scans[k], first_pseudo + t, sensor_.noise_covariance(t), m)) {
      used.push_back(t);
      synthetic.push_back(std::move(m));
    }
  }
  if (used.empty()) return;
  const int ny = sensor_.measurement_dim(), rows = ny * static_cast<int>(used.size());
  ScanMeasurement y;
  y.value.resize(rows);
  y.covariance = Eigen::MatrixXd::Zero(rows, rows);
  for (std::size_t u = 0; u < used.size(); ++u) {
    y.value.segment(ny * u, ny) = synthetic[u].value;
    y.covariance.block(ny * u, ny * u, ny, ny) = synthetic[u].covariance;
  }
  const auto stacked = [&](const Vector& state) {
    Vector h(rows);
    for (std::size_t u = 0; u < used.size(); ++u) h.segment(ny * u, ny) = sensor_.measure(used[u], state);
    return h;
  };
  unscented_update(x, y, stacked, {}, k);
}

// Module 1 for one track: per path URTS on the synthetic measurements of eq (36), fused by eq (32).
Run::KinematicChain Run::smooth_and_fuse(int track) const {
  const TrackRecord& t = tracks_[track];
  const int n = sensor_.state_dim();
  std::vector<Eigen::MatrixXd> information(t.length(), Eigen::MatrixXd::Zero(n, n));
  std::vector<Vector> weighted(t.length(), Vector::Zero(n));
  UnscentedModel model;
  model.transition = [this](const Vector& x) -> Vector { return transition_ * x; };
  model.process_covariance = problem_.process_covariance;
  for (int tau = 0; tau < paths_; ++tau) {
    std::vector<std::optional<ScanMeasurement>> synthetic(t.length());
    for (int k = t.first; k <= t.last; ++k) {
      const ScanAssociation& scan = scans_[k];
      const int p = first_pseudo_of(track, k) + tau;
      ScanMeasurement m;
      if (synthetic_measurement(scan, problem_.scans[k], p, sensor_.noise_covariance(tau), m)) synthetic[k - t.first] = m;
    }
    model.measure = [this, tau](const Vector& x) -> Vector { return sensor_.measure(tau, x); };
    const auto smoothed = unscented_smoother(unscented_filter(t.head, synthetic, model, {}, t.first), model, {}, t.first);
    for (int k = 0; k < t.length(); ++k) {
      const Eigen::LLT<Eigen::MatrixXd> llt(smoothed[k].covariance);
      const Eigen::MatrixXd inverse = llt.solve(Eigen::MatrixXd::Identity(n, n));
      information[k] += inverse;
      weighted[k] += inverse * smoothed[k].mean;
    }
  }
  KinematicChain fused;
  fused.marginal.resize(t.length());
  for (int k = 0; k < t.length(); ++k) {
    const Eigen::LLT<Eigen::MatrixXd> llt(information[k]);
    fused.marginal[k].mean = llt.solve(weighted[k]);
    const Eigen::MatrixXd p = llt.solve(Eigen::MatrixXd::Identity(n, n));
    fused.marginal[k].covariance = 0.5 * (p + p.transpose());
  }
  fused.coupling = markov_couplings(fused.marginal, t.first);
  return fused;
}

// The couplings of a Gauss–Markov chain with these marginals that maximise B's chain terms
// (gauss_markov_coupling.hpp); a marginal that is not positive definite is a failed run.
std::vector<Eigen::MatrixXd> Run::markov_couplings(const std::vector<Gaussian>& marginal, int first) const {
  std::vector<Eigen::MatrixXd> coupling;
  for (std::size_t k = 0; k + 1 < marginal.size(); ++k) {
    auto c = gauss_markov_coupling(marginal[k].covariance, marginal[k + 1].covariance, transition_, process_);
    if (!c) throw UnscentedFailure("marginal", first + static_cast<int>(k));
    coupling.push_back(std::move(*c));
  }
  return coupling;
}

// Module 1, `fusion = joint`: one unscented filter with all paths' synthetic measurements of
// each scan stacked (the maximiser of eq (31) up to the unscented approximation), then the RTS
// backward pass (the motion model is linear), which also gives Cov(x_k, x_{k+1}) = G_k P_{k+1|K}.
Run::KinematicChain Run::joint_smoother(int track) const {
  const TrackRecord& t = tracks_[track];
  std::vector<Gaussian> filtered(t.length()), predicted(t.length());
  for (int k = t.first; k <= t.last; ++k) {
    const int i = k - t.first;
    if (i == 0) {
      predicted[0] = t.head;
    } else {
      predicted[i].mean = transition_ * filtered[i - 1].mean;
      predicted[i].covariance = transition_ * filtered[i - 1].covariance * transition_.transpose() + problem_.process_covariance;
    }
    filtered[i] = predicted[i];
    ukf_update(filtered[i], scans_[k], first_pseudo_of(track, k), k);
  }
  KinematicChain chain;
  chain.marginal = filtered;
  chain.coupling.resize(std::max(0, t.length() - 1));
  for (int i = t.length() - 2; i >= 0; --i) {
    const Eigen::MatrixXd gain =
        Eigen::LLT<Eigen::MatrixXd>(predicted[i + 1].covariance).solve(transition_ * filtered[i].covariance).transpose();
    const Gaussian& later = chain.marginal[i + 1];
    chain.marginal[i].mean = filtered[i].mean + gain * (later.mean - predicted[i + 1].mean);
    const Eigen::MatrixXd p = filtered[i].covariance + gain * (later.covariance - predicted[i + 1].covariance) * gain.transpose();
    chain.marginal[i].covariance = 0.5 * (p + p.transpose());
    chain.coupling[i] = gain * later.covariance;
  }
  return chain;
}

}  // namespace dabench::jdt_vb_detail
