#pragma once
// Internals of the JDT-VB tracker (algorithms/tracking/jdt_vb.hpp), shared by its source files:
//  - jdt_vb.cpp: options, the sequential pass (track management), the VB loop, the output;
//  - jdt_vb_evidence.cpp: gates (eqs 33–35), the evidence χ of eq (43), ξ of eq (39);
//  - jdt_vb_smoothing.cpp: Module 1 (synthetic measurements eq 36, smoothers, eq 32);
//  - jdt_vb_free_energy.cpp: the free energy B from its terms (jdt_vb_free_energy_terms.hpp).
// Not part of the public interface.
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/Cholesky>

#include "algorithms/tracking/chi_square.hpp"
#include "algorithms/tracking/jdt_vb.hpp"
#include "algorithms/tracking/meta_state_chain.hpp"
#include "algorithms/tracking/multipath_association.hpp"
#include "algorithms/tracking/track_heads.hpp"
#include "algorithms/tracking/ukf.hpp"
#include "harness/core/special_values.hpp"

namespace dabench::jdt_vb_detail {

constexpr double kNoMass = 1e-12;  // a path with less gated mass at a scan gives no synthetic measurement
// Expected clutter per scan assumed when the problem has none: log λ of eq (43) must be finite.
constexpr double kClutterFloor = 1e-6;
// Largest p_d used: a miss of an active target must keep a finite χ^{i,0,τ} = log(1 − p_d).
constexpr double kMaxPd = 1.0 - 1e-9;

// c_n of eq (34): the volume of the unit n-ball (4π/3 for n = 3).
double unit_ball_volume(int n);

inline double log_det(const Eigen::LLT<Eigen::MatrixXd>& llt) {
  return 2.0 * llt.matrixLLT().diagonal().array().log().sum();
}

// A target hypothesis: the sequential pass's live track, then a batch track over its span.
struct TrackRecord {
  int id = 0;
  int first = 0, last = 0;  // span, 0-based scans, inclusive
  Gaussian head;            // p(x_first)
  double initial_active = 0.0;
  std::vector<Gaussian> marginal;  // q(x_k), k = first..last (index k − first)
  std::vector<Eigen::MatrixXd> coupling;  // batch: Cov_q(x_k, x_{k+1}), k = first..last − 1
  std::vector<double> active;      // q(s_k = 1)
  MetaStateChain meta;             // batch: q(s) with pairwise marginals
  bool confirmed_once = false;
  bool alive = true;

  int length() const { return last - first + 1; }
  const Gaussian& at(int k) const { return marginal[k - first]; }
};

// Eq (33) quantities of one (track, path) at one scan.
struct PathPrediction {
  Vector predicted;                  // h^τ(x̂)
  Eigen::MatrixXd jacobian;          // H
  Eigen::LLT<Eigen::MatrixXd> innovation;  // S = H P Hᵀ + R
  double first_variance = 0.0;       // S₀₀: the gate's half-width along the first component is √(γ S₀₀)
  double gate_volume = 0.0;          // eq (34)
};

// Module 3's problem and answer for one scan. Pseudo-target p = (track, path).
struct ScanAssociation {
  std::vector<int> track;                 // per pseudo-target: index into the track list
  std::vector<int> path;                  // per pseudo-target
  std::vector<std::vector<int>> gate;     // per pseudo-target: gated measurements, sorted (grows in the batch)
  std::vector<int> columns;               // the measurements gated by some pseudo-target, sorted
  MultipathEvidence evidence;
  MultipathAssociation result;

  int pseudo_targets() const { return static_cast<int>(track.size()); }
  int column_of(int measurement) const {  // measurement must be gated by some pseudo-target
    return static_cast<int>(std::lower_bound(columns.begin(), columns.end(), measurement) - columns.begin());
  }
};

class Run {
 public:
  Run(const JdtVbOptions& options, const TrackingProblem& problem)
      : o_(options), problem_(problem), sensor_(*problem.sensor), paths_(sensor_.paths()),
        gate_(chi_square_quantile(options.gate_probability, sensor_.measurement_dim())),
        log_clutter_density_(std::log(std::max(problem.clutter_mean, kClutterFloor) / problem.region_volume())) {
    order_.resize(problem.scan_count());
    for (int k = 0; k < problem.scan_count(); ++k) {
      auto& order = order_[k];
      order.resize(problem.scans[k].cols());
      for (int j = 0; j < static_cast<int>(order.size()); ++j) order[j] = j;
      const auto& scan = problem.scans[k];
      std::sort(order.begin(), order.end(), [&](int a, int b) { return scan(0, a) < scan(0, b) || (scan(0, a) == scan(0, b) && a < b); });
    }
    head_options_ = ground_head_options(sensor_.state_dim(), sensor_.measurement_dim(),
                                       {o_.head_range, o_.head_range_rate, o_.head_azimuth}, o_.head_bearing_rate_sd,
                                       gate_, o_.alternative_heads);
    for (int tau = 0; tau < paths_; ++tau) noise_.emplace_back(sensor_.noise_covariance(tau));
    transition_ = problem.transition;
    process_ = Eigen::LLT<Eigen::MatrixXd>(problem.process_covariance);
  }

  void sequential_pass();
  // `iterations`, when set, receives the output before the first iteration and after each.
  // `rejected` counts the rejected Module-1 updates, `largest_rejected_decrease` the most any of
  // them would have lowered B (left as it is when none is rejected).
  void batch(std::vector<double>& history, int& rejected, double& largest_rejected_decrease, SolveReport& report,
             std::vector<TrackSet>* iterations);
  void output(TrackSet& tracks) const;

 private:
  double expected_log_pd(double active, int path, bool detected) const {
    const double pd = gated_pd(path);
    return detected ? active * std::log(pd) + (1.0 - active) * std::log(o_.dormant_pd)
                    : active * std::log1p(-pd) + (1.0 - active) * std::log1p(-o_.dormant_pd);
  }
  // p^τ_d p_g: a detection of an active target falls in its gate with probability p_g (eq 15
  // has no p_g; without it one detection outside its gate at p_d ≈ 1 makes the target dormant).
  double gated_pd(int path) const {
    return std::min(problem_.detection_probability[path] * o_.gate_probability, kMaxPd);
  }
  PathPrediction predict_path(const Gaussian& x, int path) const;
  void gate_measurements(int k, const PathPrediction& p, std::vector<int>& gated) const;
  void build_evidence(int k, ScanAssociation& scan, const std::vector<PathPrediction>& predictions,
                      const std::vector<double>& active, bool predictive);
  std::array<double, 2> meta_evidence(const ScanAssociation& scan, int first_pseudo) const;
  void ukf_update(Gaussian& x, const ScanAssociation& scan, int first_pseudo, int k) const;
  struct KinematicChain {
    std::vector<Gaussian> marginal;
    std::vector<Eigen::MatrixXd> coupling;
  };
  // Cov(x_k, x_{k+1}) of the chain with these marginals (scans first, first + 1, ...).
  std::vector<Eigen::MatrixXd> markov_couplings(const std::vector<Gaussian>& marginal, int first) const;
  KinematicChain smooth_and_fuse(int track) const;
  KinematicChain joint_smoother(int track) const;
  int first_pseudo_of(int track, int k) const {
    const auto& t = scans_[k].track;
    return static_cast<int>(std::find(t.begin(), t.end(), track) - t.begin());
  }
  double bethe_entropy(const ScanAssociation& scan) const;
  double association_energy(const ScanAssociation& scan, int k) const;
  double track_kinematic_terms(int track, const std::vector<Gaussian>& marginal,
                               const std::vector<Eigen::MatrixXd>& coupling) const;
  double track_meta_terms(int track) const;
  double free_energy() const;

  const JdtVbOptions& o_;
  const TrackingProblem& problem_;
  const MultipathMeasurementModel& sensor_;
  const int paths_;
  const double gate_;
  const double log_clutter_density_;
  std::vector<std::vector<int>> order_;  // per scan: measurements by increasing first component
  TrackHeadOptions head_options_;
  std::vector<Eigen::LLT<Eigen::MatrixXd>> noise_;  // per path: Cholesky factor of R^τ
  Eigen::MatrixXd transition_;
  Eigen::LLT<Eigen::MatrixXd> process_;
  std::vector<TrackRecord> tracks_;       // every track of the sequential pass
  std::vector<int> batch_;                // indices of the tracks in the batch VB
  std::vector<ScanAssociation> scans_;    // batch: per scan
  MultipathAssociationBp lbp_;
  int next_id_ = 1;
};

// Synthetic measurement of eq (36) for one pseudo-target: false when its gated mass is ~0.
[[nodiscard]] bool synthetic_measurement(const ScanAssociation& scan, const Eigen::MatrixXd& measurements, int p,
                           const Eigen::MatrixXd& noise, ScanMeasurement& out);

}  // namespace dabench::jdt_vb_detail
