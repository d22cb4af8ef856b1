#pragma once
// The track side of MD-HMHT (algorithms/tracking/md_hmht.hpp): immutable track nodes shared by
// the hypotheses, and the UKF that predicts a node to the next scan, gates each path's
// pseudo-target with its costs c_pj = −ln ψ_pj, and updates it with the measurements one child
// assigns it. Not part of the public interface.
//
// One unscented transform per track and scan serves every path and every child: the sigma points
// of the predicted state go through the stacked h = [h^0; ...; h^{P−1}], whose mean, covariance
// and cross-covariance give each path's gate (its blocks) and the update with any subset A of
// paths (the A rows and columns) — exactly the UKF update on the stacked measurement of A.
#include <memory>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "algorithms/tracking/scan_index.hpp"
#include "algorithms/tracking/ukf.hpp"
#include "harness/tracking/problem.hpp"

namespace dabench::md_hmht {

// One track's filtered estimate at one scan; `previous` links its history. Immutable once made,
// so hypotheses share it.
struct TrackNode {
  long serial = 0;       // creation order in the run, unique: keys the per-scan caches
  long track = 0;        // the track's id (its head's serial)
  long family = 0;       // heads of one return group (alternative path readings) share it
  int first_scan = 0;    // the head's scan
  int scan = 0;          // the scan of `estimate`
  int last_hit_scan = 0; // last scan with an assigned measurement
  Gaussian estimate;
  double llr = 0.0;      // Σ over scans since the head of Σ_τ ln(1 − p_d p_g) + Σ_assigned ln ψ
  int empty_gates = 0;   // successive scans with no measurement in any path's gate
  int confirmed_scan = -1;  // the scan at which llr first reached the confirmation threshold, −1 none
  std::vector<int> assigned;  // per path, the measurement it took at `scan` (−1 none); empty for a head
  std::shared_ptr<const TrackNode> previous;

  bool confirmed() const { return confirmed_scan >= 0; }
};
using NodePtr = std::shared_ptr<const TrackNode>;

struct Arc {
  int measurement;  // column of the scan
  double cost;      // c_pj = −ln ψ_pj
};

// A node predicted to the next scan, with its gates.
struct TrackPrediction {
  Gaussian predicted;              // x⁻, P⁻
  UnscentedTransform stacked;      // of [h^0; ...; h^{P−1}] at x⁻
  std::vector<std::vector<Arc>> arcs;  // per path: gated measurements, by increasing slant range
  double miss_log_sum = 0.0;       // Σ_τ ln(1 − p^τ_d p_g): the track's score if it takes nothing
  bool gate_hit = false;           // some path gates some measurement
};

class TrackFilter {
 public:
  static constexpr int kDim = 3;  // measurements [r, ṙ, ζ]

  TrackFilter(const TrackingProblem& problem, double gate_probability);

  int paths() const { return paths_; }
  double log_miss(int path) const { return log_miss_[path]; }

  // Predicts `node` to the scan `scan` (sorted by `index`) and gates every path.
  void predict(const TrackNode& node, const Eigen::MatrixXd& scan, const ScanIndex& index,
               TrackPrediction& out) const;

  // The node at scan k after the child's assignment: measurement_of_path[τ] is a column gated by
  // path τ or −1. `serial` is the new node's; confirmed_scan is the node's (the caller confirms).
  TrackNode update(const NodePtr& node, const TrackPrediction& prediction, const int* measurement_of_path,
                   const Eigen::MatrixXd& scan, int k, long serial) const;

 private:
  const TrackingProblem& problem_;
  const MultipathMeasurementModel& sensor_;
  int paths_ = 0;
  double gate_ = 0.0;         // γ
  double log_clutter_ = 0.0;  // ln λ
  std::vector<double> log_pd_, log_miss_;  // per path: ln p^τ_d, ln(1 − p^τ_d p_g)
};

}  // namespace dabench::md_hmht
