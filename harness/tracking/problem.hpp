#pragma once
// Multi-target tracking over a whole scenario run (jdt-vb-multipath-othr, Sec. II): K scans of
// measurements y_{j,k}, each from one target through one of N_P propagation paths (eq 2) or
// from clutter, and the tracks a tracker returns. Scans are 0-based here: scan k holds the
// paper's time k + 1.
//
//  - TrackingProblem: what a tracker may read — the scans and the known model: linear
//    near-constant-velocity motion x_{k+1} = F x_k + v_k, v_k ~ N(0, Q) (eq 1), per path a
//    measurement function h^τ with noise N(0, R^τ) and detection probability p^τ_d (eq 2),
//    and Poisson clutter uniform over a box in measurement space.
//  - TrackingTruth: what only metrics, tests and plots may read.
//  - TrackSet: a tracker's output.
#include <limits>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "harness/core/matrix_types.hpp"

namespace dabench {

// h^τ and R^τ of eq (2), τ = 0..paths()−1. Implementations are immutable and shared by the
// problems of concurrent trials.
class MultipathMeasurementModel {
 public:
  virtual ~MultipathMeasurementModel() = default;
  virtual int state_dim() const = 0;        // n_x
  virtual int measurement_dim() const = 0;  // n_y
  virtual int paths() const = 0;            // N_P
  virtual Vector measure(int path, const Vector& state) const = 0;           // h^τ(x)
  virtual Eigen::MatrixXd jacobian(int path, const Vector& state) const = 0; // ∂h^τ/∂x, n_y × n_x
  virtual const Eigen::MatrixXd& noise_covariance(int path) const = 0;       // R^τ
  // A state x with h^τ(x) = y, components h^τ does not depend on set to 0; false if none
  // exists. Trackers use it to start tracks from single measurements.
  [[nodiscard]] virtual bool invert(int path, const Vector& measurement, Vector& state) const = 0;
};

struct TrackingProblem {
  std::vector<Eigen::MatrixXd> scans;  // per scan k: n_y × M_k, one column per measurement y_{j,k}
  double scan_interval = 0.0;          // T_s, seconds between scans
  Eigen::MatrixXd transition;          // F, n_x × n_x
  Eigen::MatrixXd process_covariance;  // Q, n_x × n_x
  std::shared_ptr<const MultipathMeasurementModel> sensor;
  std::vector<double> detection_probability;  // p^τ_d, per path
  double clutter_mean = 0.0;           // N_c: expected clutter measurements per scan
  Vector region_lower, region_upper;   // surveillance box in measurement space (n_y each)

  int scan_count() const { return static_cast<int>(scans.size()); }
  double region_volume() const { return (region_upper - region_lower).prod(); }
  double clutter_density() const { return clutter_mean / region_volume(); }  // per unit volume
};

// Where measurement j of a scan came from: (target, path), or clutter (target = −1, path = −1).
struct MeasurementOrigin {
  int target = -1;
  int path = -1;
  bool is_clutter() const { return target < 0; }
};

struct TrackingTruth {
  struct Target {
    Eigen::MatrixXd states;   // n_x × K; columns of scans where the target is not alive are NaN
    std::vector<bool> alive;  // per scan
  };
  std::vector<Target> targets;
  std::vector<std::vector<MeasurementOrigin>> origin;  // per scan, per measurement (column)
  // Counts over the run, for statistics tests.
  int detections = 0;          // detections drawn (each alive target, path and scan w.p. p^τ_d)
  int dropped_detections = 0;  // of those, outside the surveillance region (not in the scans)
  int clutter = 0;             // clutter measurements (all inside the region)
};

struct TrackingScenarioSample {
  TrackingProblem problem;
  TrackingTruth truth;
};

// One track: estimates for the consecutive scans first_scan .. first_scan + length() − 1.
struct Track {
  int id = 0;
  int first_scan = 0;
  Eigen::MatrixXd states;                // n_x × length: posterior means
  Eigen::MatrixXd covariance_diagonals;  // n_x × length: diagonals of the posterior covariances
  bool confirmed = false;                // false: tentative (metrics count confirmed tracks only)

  int length() const { return static_cast<int>(states.cols()); }
};

struct TrackSet {
  std::vector<Track> tracks;
  // The tracker's objective for these tracks where it has one (JDT-VB: the free energy B of
  // the iteration that produced them); NaN otherwise.
  double objective = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace dabench
