#include "algorithms/tracking/md_hmht_tracks.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "algorithms/tracking/chi_square.hpp"
#include "harness/core/special_values.hpp"

namespace dabench::md_hmht {

namespace {

// Expected clutter per scan assumed when the problem has none, so that ln λ is finite (as jdt-vb).
constexpr double kClutterFloor = 1e-6;

}  // namespace

TrackFilter::TrackFilter(const TrackingProblem& problem, double gate_probability)
    : problem_(problem), sensor_(*problem.sensor), paths_(sensor_.paths()),
      gate_(chi_square_quantile(gate_probability, sensor_.measurement_dim())),
      log_clutter_(std::log(std::max(problem.clutter_mean, kClutterFloor) / problem.region_volume())) {
  for (int tau = 0; tau < paths_; ++tau) {
    const double pd = problem.detection_probability[tau];
    log_pd_.push_back(std::log(pd));
    log_miss_.push_back(std::log1p(-pd * gate_probability));
  }
}

void TrackFilter::predict(const TrackNode& node, const Eigen::MatrixXd& scan, const ScanIndex& index,
                          TrackPrediction& out) const {
  const Eigen::MatrixXd& F = problem_.transition;
  out.predicted.mean = F * node.estimate.mean;
  out.predicted.covariance = symmetrised(F * node.estimate.covariance * F.transpose() + problem_.process_covariance);
  out.stacked = unscented_transform(out.predicted, [&](const Vector& x) {
    Vector h(kDim * paths_);
    for (int tau = 0; tau < paths_; ++tau) h.segment(kDim * tau, kDim) = sensor_.measure(tau, x);
    return h;
  });
  out.arcs.resize(paths_);
  out.miss_log_sum = 0.0;
  out.gate_hit = false;
  for (int tau = 0; tau < paths_; ++tau) {
    out.miss_log_sum += log_miss_[tau];
    std::vector<Arc>& arcs = out.arcs[tau];
    arcs.clear();
    const Eigen::Vector3d predicted = out.stacked.mean.segment<3>(3 * tau);
    const Eigen::Matrix3d S =
        symmetrised(out.stacked.covariance.block<3, 3>(3 * tau, 3 * tau) + sensor_.noise_covariance(tau));
    const Eigen::LLT<Eigen::Matrix3d> llt(S);
    if (llt.info() != Eigen::Success) throw UnscentedFailure("innovation", node.scan + 1);
    const Eigen::Matrix3d S_inverse = llt.solve(Eigen::Matrix3d::Identity());
    const double log_det = 2.0 * llt.matrixLLT().diagonal().array().log().sum();
    // ln ψ_pj + ½ d² (header): ln p_d − ½ ln|2πS| − ln(1 − p_d p_g) − ln λ.
    const double base = log_pd_[tau] - 0.5 * (3 * kLog2Pi + log_det) - log_miss_[tau] - log_clutter_;
    // The gate ellipsoid's extent along each component is ±√(γ S_ii): range by binary search,
    // range rate and azimuth by comparison before the quadratic form.
    const Eigen::Vector3d reach = (gate_ * S.diagonal()).cwiseSqrt();
    const auto begin = std::lower_bound(index.range.begin(), index.range.end(), predicted[0] - reach[0]);
    for (auto it = begin; it != index.range.end() && *it <= predicted[0] + reach[0]; ++it) {
      const int j = index.order[it - index.range.begin()];
      const Eigen::Vector3d d = scan.col(j).head<3>() - predicted;
      if (std::abs(d[1]) > reach[1] || std::abs(d[2]) > reach[2]) continue;
      const double d2 = d.dot(S_inverse * d);
      if (d2 > gate_) continue;
      arcs.push_back({j, -(base - 0.5 * d2)});
    }
    out.gate_hit = out.gate_hit || !arcs.empty();
  }
}

TrackNode TrackFilter::update(const NodePtr& node, const TrackPrediction& prediction, const int* measurement_of_path,
                              const Eigen::MatrixXd& scan, int k, long serial) const {
  TrackNode next;
  next.serial = serial;
  next.track = node->track;
  next.family = node->family;
  next.first_scan = node->first_scan;
  next.scan = k;
  next.last_hit_scan = node->last_hit_scan;
  next.estimate = prediction.predicted;
  next.llr = node->llr + prediction.miss_log_sum;
  next.empty_gates = prediction.gate_hit ? 0 : node->empty_gates + 1;
  next.confirmed_scan = node->confirmed_scan;
  next.assigned.assign(measurement_of_path, measurement_of_path + paths_);
  next.previous = node;

  // Rows of the stacked transform that the assigned paths select.
  std::vector<int> rows;
  Vector y;
  for (int tau = 0; tau < paths_; ++tau) {
    const int j = measurement_of_path[tau];
    if (j < 0) continue;
    const auto& arcs = prediction.arcs[tau];
    const auto arc = std::find_if(arcs.begin(), arcs.end(), [j](const Arc& a) { return a.measurement == j; });
    next.llr -= arc->cost;  // the assignment only uses gated pairs
    for (int r = 0; r < kDim; ++r) rows.push_back(kDim * tau + r);
    y.conservativeResize(y.size() + kDim);
    y.tail(kDim) = scan.col(j);
  }
  if (rows.empty()) return next;
  next.last_hit_scan = k;
  const int m = static_cast<int>(rows.size());
  Vector predicted(m);
  Eigen::MatrixXd S(m, m), cross(prediction.predicted.mean.size(), m);
  for (int a = 0; a < m; ++a) {
    predicted[a] = prediction.stacked.mean[rows[a]];
    cross.col(a) = prediction.stacked.cross.col(rows[a]);
    for (int b = 0; b < m; ++b) S(a, b) = prediction.stacked.covariance(rows[a], rows[b]);
  }
  for (int a = 0; a < m; a += kDim) {
    const int tau = rows[a] / kDim;
    S.block(a, a, kDim, kDim) += sensor_.noise_covariance(tau);
  }
  const Eigen::LLT<Eigen::MatrixXd> llt(symmetrised(S));
  if (llt.info() != Eigen::Success) throw UnscentedFailure("innovation", k);
  const Eigen::MatrixXd gain = llt.solve(cross.transpose()).transpose();  // C S⁻¹
  next.estimate.mean += gain * (y - predicted);
  next.estimate.covariance = symmetrised(next.estimate.covariance - gain * S * gain.transpose());
  return next;
}

}  // namespace dabench::md_hmht
