// JDT-VB: gates (eqs 33-35), the evidence χ of eq (43) for Module 3 and ξ of eq (39) for Module 2.
#include "algorithms/tracking/jdt_vb_run.hpp"

#include <algorithm>

namespace dabench::jdt_vb_detail {

double unit_ball_volume(int n) { return std::pow(std::numbers::pi, 0.5 * n) / std::tgamma(0.5 * n + 1.0); }

PathPrediction Run::predict_path(const Gaussian& x, int path) const {
  PathPrediction p;
  p.predicted = sensor_.measure(path, x.mean);
  p.jacobian = sensor_.jacobian(path, x.mean);
  const Eigen::MatrixXd s = p.jacobian * x.covariance * p.jacobian.transpose() + sensor_.noise_covariance(path);
  p.innovation.compute(0.5 * (s + s.transpose()));
  p.first_variance = p.innovation.reconstructedMatrix()(0, 0);
  const int n = static_cast<int>(p.predicted.size());
  p.gate_volume = unit_ball_volume(n) * std::pow(gate_, 0.5 * n) * std::exp(0.5 * log_det(p.innovation));
  return p;
}

// Eq (33): measurements with Mahalanobis distance ≤ γ under S, found through the sorted first
// component (the ellipsoid's extent along it is ±√(γ S₀₀)).
void Run::gate_measurements(int k, const PathPrediction& p, std::vector<int>& gated) const {
  const auto& scan = problem_.scans[k];
  const auto& order = order_[k];
  const double reach = std::sqrt(gate_ * p.first_variance);
  auto lower = std::lower_bound(order.begin(), order.end(), p.predicted[0] - reach,
                                [&](int j, double v) { return scan(0, j) < v; });
  for (auto it = lower; it != order.end() && scan(0, *it) <= p.predicted[0] + reach; ++it) {
    const Vector d = scan.col(*it) - p.predicted;
    if (d.dot(p.innovation.solve(d)) <= gate_) gated.push_back(*it);
  }
  std::sort(gated.begin(), gated.end());
  gated.erase(std::unique(gated.begin(), gated.end()), gated.end());
}

// The χ of eq (43) over the gated pairs of one scan. `predictive`: the sequential pass's
// N(y | h(x̂⁻), S) in place of the linearised E_q log N(y | h(x), R).
void Run::build_evidence(int k, ScanAssociation& scan, const std::vector<PathPrediction>& predictions,
                         const std::vector<double>& active, bool predictive) {
  const auto& measurements = problem_.scans[k];
  scan.columns.clear();
  for (const auto& g : scan.gate) scan.columns.insert(scan.columns.end(), g.begin(), g.end());
  std::sort(scan.columns.begin(), scan.columns.end());
  scan.columns.erase(std::unique(scan.columns.begin(), scan.columns.end()), scan.columns.end());
  const int pseudo = scan.pseudo_targets(), columns = static_cast<int>(scan.columns.size());

  // V_k of eq (35): per track the largest of its paths' gate volumes, summed over tracks.
  double volume = 0.0;
  for (int p = 0; p < pseudo; p += paths_) {
    double largest = 0.0;
    for (int t = 0; t < paths_; ++t) largest = std::max(largest, predictions[p + t].gate_volume);
    volume += largest;
  }
  const double log_volume = std::log(std::max(volume, 1e-300));

  auto& e = scan.evidence;
  e.targets = pseudo / paths_;
  e.paths = paths_;
  e.detection.setConstant(pseudo, columns, -HUGE_VAL);
  e.miss.resize(pseudo);
  e.clutter.setConstant(columns, -log_volume);
  for (int p = 0; p < pseudo; ++p) {
    const PathPrediction& pr = predictions[p];
    const int path = scan.path[p];
    const double a = active[p / paths_];
    e.miss[p] = expected_log_pd(a, path, false);
    const Eigen::LLT<Eigen::MatrixXd>& r_llt = noise_[path];
    const auto& cov_llt = predictive ? pr.innovation : r_llt;
    double constant = expected_log_pd(a, path, true) - log_clutter_density_ - log_volume -
                      0.5 * (static_cast<double>(pr.predicted.size()) * kLog2Pi + log_det(cov_llt));
    if (!predictive) {
      const Gaussian& x = tracks_[scan.track[p]].at(k);
      constant -= 0.5 * (r_llt.solve(pr.jacobian * x.covariance * pr.jacobian.transpose())).trace();
    }
    for (int j : scan.gate[p]) {
      const int c = scan.column_of(j);
      const Vector d = measurements.col(j) - pr.predicted;
      e.detection(p, c) = constant - 0.5 * d.dot(cov_llt.solve(d));
    }
  }
}

// ξ_k(s) of eq (39) for one track, from its pseudo-targets first_pseudo .. + N_P.
std::array<double, 2> Run::meta_evidence(const ScanAssociation& scan, int first_pseudo) const {
  std::array<double, 2> xi{0.0, 0.0};
  for (int t = 0; t < paths_; ++t) {
    const double detected = 1.0 - scan.result.miss[first_pseudo + t];  // eq (40): Σ_j E[a] = 1 − E[a^{i,0,τ}]
    const double pd = gated_pd(t);
    xi[1] += detected * std::log(pd) + (1.0 - detected) * std::log1p(-pd);
    xi[0] += detected * std::log(o_.dormant_pd) + (1.0 - detected) * std::log1p(-o_.dormant_pd);
  }
  return xi;
}

}  // namespace dabench::jdt_vb_detail
