#include "algorithms/jdt_vb.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include <Eigen/Cholesky>
#include <fmt/format.h>

#include "algorithms/jdt_vb_heads.hpp"
#include "algorithms/meta_state_chain.hpp"
#include "algorithms/ukf.hpp"
#include "harness/errors.hpp"
#include "harness/registry.hpp"

namespace dabench {

void JdtVbOptions::bind(ParamList& p) {
  p.add("convergence", convergence, "delta_T: stop when the free energy B changes by less, > 0");
  p.add("max_iterations", max_iterations, "r_max: VB iteration cap, >= 1");
  p.add("confirm", confirm, "delta_s: confirmation and deletion threshold on q(s=1), in (0, 1)");
  p.add("stay", stay, "p(s_k = s_k-1) of the meta-state chain, in (0, 1)");
  p.add("dormant_pd", dormant_pd, "detection probability of a dormant target (s = 0), in (0, 1)");
  p.add("delete_on_mean", delete_on_mean, "1: delete on the mean q(s=1) of three scans < delta_s (the text); 0: on all three < delta_s");
  p.add("gate_probability", gate_probability, "p_g of the gates (eq 33), in (0, 1)");
  p.add("head_range", head_range, "track-head threshold on slant range, km, > 0");
  p.add("head_range_rate", head_range_rate, "track-head threshold on slant range rate, km/s, > 0");
  p.add("head_azimuth", head_azimuth, "track-head threshold on azimuth, rad, > 0");
  p.add("head_bearing_rate_sd", head_bearing_rate_sd, "s.d. of the bearing rate of a new track, rad/s, > 0");
  p.add("joint_fusion", joint_fusion, "Module 1: 0 = per-path smoothers fused by eq (32), 1 = one smoother on all paths");
  p.add("lbp_tolerance", association.tolerance, "Module 3: stop LBP when no message changes more (log units)");
  p.add("lbp_iterations", association.max_iterations, "Module 3: LBP iteration cap");
}

std::string JdtVbOptions::validate() const {
  auto open_unit = [](double v) { return v > 0.0 && v < 1.0; };
  if (!(convergence > 0.0)) return fmt::format("convergence = {} must be > 0", convergence);
  if (max_iterations < 1) return fmt::format("max_iterations = {} must be >= 1", max_iterations);
  if (!open_unit(confirm)) return fmt::format("confirm = {} must be in (0, 1)", confirm);
  if (!open_unit(stay)) return fmt::format("stay = {} must be in (0, 1)", stay);
  if (!open_unit(dormant_pd)) return fmt::format("dormant_pd = {} must be in (0, 1)", dormant_pd);
  if (!open_unit(gate_probability)) return fmt::format("gate_probability = {} must be in (0, 1)", gate_probability);
  for (auto [name, v] : {std::pair{"head_range", head_range}, {"head_range_rate", head_range_rate},
                         {"head_azimuth", head_azimuth}, {"head_bearing_rate_sd", head_bearing_rate_sd}})
    if (!(v > 0.0 && std::isfinite(v))) return fmt::format("{} = {} must be finite and > 0", name, v);
  return association.validate();
}

namespace {

constexpr double kNoMass = 1e-12;  // a path with less gated mass at a scan gives no synthetic measurement
const double kLog2Pi = std::log(2.0 * std::numbers::pi);
// Expected clutter per scan assumed when the problem has none: log λ of eq (43) must be finite.
constexpr double kClutterFloor = 1e-6;
// Largest p_d used: a miss of an active target must keep a finite χ^{i,0,τ} = log(1 − p_d).
constexpr double kMaxPd = 1.0 - 1e-9;

// Regularised lower incomplete gamma P(a, x) by its power series (x small to moderate).
double lower_gamma_regularised(double a, double x) {
  double term = 1.0 / a, sum = term;
  for (int n = 1; n < 1000 && term > 1e-17 * sum; ++n) {
    term *= x / (a + n);
    sum += term;
  }
  return std::exp(a * std::log(x) - x - std::lgamma(a)) * sum;
}

// γ with P(χ²_n ≤ γ) = p, the gate threshold of eq (33), by bisection.
double chi_square_quantile(double p, int n) {
  double lo = 0.0, hi = 10.0 * n + 100.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (lower_gamma_regularised(0.5 * n, 0.5 * mid) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// c_n of eq (34): the volume of the unit n-ball (4π/3 for n = 3).
double unit_ball_volume(int n) { return std::pow(std::numbers::pi, 0.5 * n) / std::tgamma(0.5 * n + 1.0); }

double log_det(const Eigen::LLT<Eigen::MatrixXd>& llt) {
  return 2.0 * llt.matrixLLT().diagonal().array().log().sum();
}

double xlogx(double p) { return p > 0.0 ? p * std::log(p) : 0.0; }

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
    const int n = sensor_.state_dim();
    head_options_.threshold = Vector::Zero(sensor_.measurement_dim());
    head_options_.threshold.head(3) << o_.head_range, o_.head_range_rate, o_.head_azimuth;
    // Λ₀: weak on the observed components (1000 km, 1 km/s, 1 rad), the bearing-rate prior on ϑ̇.
    head_options_.gate = gate_;
    head_options_.prior_precision = Vector::Constant(n, 1e-6);
    if (n == 4) head_options_.prior_precision << 1e-6, 1.0, 1.0, 1.0 / (o_.head_bearing_rate_sd * o_.head_bearing_rate_sd);
    transition_ = problem.transition;
    process_ = Eigen::LLT<Eigen::MatrixXd>(problem.process_covariance);
  }

  void sequential_pass();
  // `iterations`, when set, receives the output before the first iteration and after each.
  void batch(std::vector<double>& history, int& rejected, SolveReport& report, std::vector<TrackSet>* iterations);
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
  std::vector<Eigen::MatrixXd> markov_couplings(const std::vector<Gaussian>& marginal) const;
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
  Eigen::MatrixXd transition_;
  Eigen::LLT<Eigen::MatrixXd> process_;
  std::vector<TrackRecord> tracks_;       // every track of the sequential pass
  std::vector<int> batch_;                // indices of the tracks in the batch VB
  std::vector<ScanAssociation> scans_;    // batch: per scan
  MultipathAssociationBp lbp_;
  int next_id_ = 1;
};

PathPrediction Run::predict_path(const Gaussian& x, int path) const {
  PathPrediction p;
  p.predicted = sensor_.measure(path, x.mean);
  p.jacobian = sensor_.jacobian(path, x.mean);
  const Eigen::MatrixXd s = p.jacobian * x.covariance * p.jacobian.transpose() + sensor_.noise_covariance(path);
  p.innovation.compute(0.5 * (s + s.transpose()));
  const int n = static_cast<int>(p.predicted.size());
  p.gate_volume = unit_ball_volume(n) * std::pow(gate_, 0.5 * n) * std::exp(0.5 * log_det(p.innovation));
  return p;
}

// Eq (33): measurements with Mahalanobis distance ≤ γ under S, found through the sorted first
// component (the ellipsoid's extent along it is ±√(γ S₀₀)).
void Run::gate_measurements(int k, const PathPrediction& p, std::vector<int>& gated) const {
  const auto& scan = problem_.scans[k];
  const auto& order = order_[k];
  const Eigen::MatrixXd s = p.innovation.reconstructedMatrix();
  const double reach = std::sqrt(gate_ * s(0, 0));
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
    const Eigen::MatrixXd& r = sensor_.noise_covariance(path);
    const Eigen::LLT<Eigen::MatrixXd> r_llt(r);
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

// Synthetic measurement of eq (36) for one pseudo-target: false when its gated mass is ~0.
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
  Vector value(rows);
  Eigen::MatrixXd noise = Eigen::MatrixXd::Zero(rows, rows);
  for (std::size_t u = 0; u < used.size(); ++u) {
    value.segment(ny * u, ny) = synthetic[u].value;
    noise.block(ny * u, ny * u, ny, ny) = synthetic[u].covariance;
  }
  const auto stacked = [&](const Vector& state) {
    Vector y(rows);
    for (std::size_t u = 0; u < used.size(); ++u) y.segment(ny * u, ny) = sensor_.measure(used[u], state);
    return y;
  };
  const UnscentedTransform ut = unscented_transform(x, stacked);
  const Eigen::MatrixXd s = ut.covariance + noise;
  const Eigen::MatrixXd gain = s.llt().solve(ut.cross.transpose()).transpose();
  x.mean += gain * (value - ut.mean);
  const Eigen::MatrixXd p = x.covariance - gain * s * gain.transpose();
  x.covariance = 0.5 * (p + p.transpose());
}

void Run::sequential_pass() {
  const int scans = problem_.scan_count();
  std::vector<int> live;
  for (int k = 0; k < scans; ++k) {
    // Predict the live tracks to scan k (linear motion, eq 1).
    for (int i : live) {
      TrackRecord& t = tracks_[i];
      Gaussian x = t.marginal.back();
      x.mean = transition_ * x.mean;
      x.covariance = transition_ * x.covariance * transition_.transpose() + problem_.process_covariance;
      t.marginal.push_back(std::move(x));
      t.last = k;
    }
    ScanAssociation scan;
    std::vector<PathPrediction> predictions;
    std::vector<double> predicted_active;
    for (int i : live) {
      const TrackRecord& t = tracks_[i];
      const double a = t.active.back();
      predicted_active.push_back(o_.stay * a + (1.0 - o_.stay) * (1.0 - a));
      for (int tau = 0; tau < paths_; ++tau) {
        scan.track.push_back(i);
        scan.path.push_back(tau);
        predictions.push_back(predict_path(t.marginal.back(), tau));
        scan.gate.emplace_back();
        gate_measurements(k, predictions.back(), scan.gate.back());
      }
    }
    build_evidence(k, scan, predictions, predicted_active, true);
    std::vector<int> survivors;
    if (!live.empty()) {
      lbp_.solve(scan.evidence, o_.association, scan.result);
      for (std::size_t n = 0; n < live.size(); ++n) {
        TrackRecord& t = tracks_[live[n]];
        const int first_pseudo = static_cast<int>(n) * paths_;
        ukf_update(t.marginal.back(), scan, first_pseudo, k);
        t.active.push_back(meta_state_filter_step(t.active.back(), o_.stay, meta_evidence(scan, first_pseudo)));
        t.confirmed_once = t.confirmed_once || t.active.back() >= o_.confirm;
        // Deletion (Sec. III-E) over the last three scans after the first.
        const int after_first = k - t.first;
        bool weak = false;
        if (after_first >= 3) {
          const double* last3 = &t.active[after_first - 2];
          weak = o_.delete_on_mean ? (last3[0] + last3[1] + last3[2]) / 3.0 < o_.confirm
                                   : std::max({last3[0], last3[1], last3[2]}) < o_.confirm;
        }
        if (weak) t.alive = false;
        else survivors.push_back(live[n]);
      }
    }
    // Heads from the measurements no live track gates.
    std::vector<char> gated(problem_.scans[k].cols(), 0);
    for (const auto& g : scan.gate)
      for (int j : g) gated[j] = 1;
    std::vector<int> candidates;
    for (int j = 0; j < static_cast<int>(gated.size()); ++j)
      if (!gated[j]) candidates.push_back(j);
    for (TrackHead& h : form_track_heads(problem_.scans[k], candidates, sensor_, head_options_)) {
      TrackRecord t;
      t.id = next_id_++;
      t.first = t.last = k;
      t.head = {h.mean, h.covariance};
      t.initial_active = h.initial_active;
      t.marginal.push_back(t.head);
      t.active.push_back(h.initial_active);
      t.confirmed_once = h.initial_active >= o_.confirm;
      survivors.push_back(static_cast<int>(tracks_.size()));
      tracks_.push_back(std::move(t));
    }
    live = std::move(survivors);
  }
  for (int i = 0; i < static_cast<int>(tracks_.size()); ++i) {
    if (!tracks_[i].confirmed_once) continue;
    batch_.push_back(i);
    tracks_[i].coupling = markov_couplings(tracks_[i].marginal);
  }
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
    const auto smoothed = unscented_smoother(unscented_filter(t.head, synthetic, model), model);
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
  fused.coupling = markov_couplings(fused.marginal);
  return fused;
}

// The coupling of a Gauss–Markov chain with given marginals under the motion model:
// Cov(x_k, x_{k+1}) = G_k P_{k+1}, G_k = P_k Fᵀ (F P_k Fᵀ + Q)⁻¹; zero where the resulting
// conditional covariance P_k − G_k P_{k+1} G_kᵀ is not positive definite.
std::vector<Eigen::MatrixXd> Run::markov_couplings(const std::vector<Gaussian>& marginal) const {
  std::vector<Eigen::MatrixXd> coupling;
  for (std::size_t k = 0; k + 1 < marginal.size(); ++k) {
    const Eigen::MatrixXd& now = marginal[k].covariance;
    const Eigen::MatrixXd& next = marginal[k + 1].covariance;
    const Eigen::MatrixXd predicted = transition_ * now * transition_.transpose() + problem_.process_covariance;
    const Eigen::MatrixXd gain = Eigen::LLT<Eigen::MatrixXd>(predicted).solve(transition_ * now).transpose();
    const Eigen::LLT<Eigen::MatrixXd> conditional(now - gain * next * gain.transpose());
    coupling.push_back(conditional.info() == Eigen::Success ? Eigen::MatrixXd(gain * next)
                                                            : Eigen::MatrixXd::Zero(now.rows(), now.cols()));
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
      const Eigen::LLT<Eigen::MatrixXd> r(sensor_.noise_covariance(tau));
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

void Run::batch(std::vector<double>& history, int& rejected, SolveReport& report, std::vector<TrackSet>* iterations) {
  const int scans = problem_.scan_count();
  scans_.assign(scans, {});
  for (int i : batch_) {
    TrackRecord& t = tracks_[i];
    for (int k = t.first; k <= t.last; ++k) {
      for (int tau = 0; tau < paths_; ++tau) {
        scans_[k].track.push_back(i);
        scans_[k].path.push_back(tau);
        scans_[k].gate.emplace_back();
      }
    }
  }
  report.converged = false;
  if (iterations) output(iterations->emplace_back());
  for (int r = 1; r <= o_.max_iterations; ++r) {
    // Module 3: gates about q(x) (grown), eq (43) evidence, LBP.
    for (int k = 0; k < scans; ++k) {
      ScanAssociation& scan = scans_[k];
      std::vector<PathPrediction> predictions;
      std::vector<double> active;
      for (int p = 0; p < scan.pseudo_targets(); ++p) {
        const TrackRecord& t = tracks_[scan.track[p]];
        predictions.push_back(predict_path(t.at(k), scan.path[p]));
        gate_measurements(k, predictions.back(), scan.gate[p]);
        if (scan.path[p] == 0) active.push_back(t.active[k - t.first]);
      }
      build_evidence(k, scan, predictions, active, false);
      if (scan.pseudo_targets() > 0) lbp_.solve(scan.evidence, o_.association, scan.result);
      else scan.result = {};
    }
    // Module 2: forward–backward per track.
    for (int i : batch_) {
      TrackRecord& t = tracks_[i];
      std::vector<std::array<double, 2>> xi;
      for (int k = t.first; k <= t.last; ++k) {
        const ScanAssociation& scan = scans_[k];
        xi.push_back(meta_evidence(scan, first_pseudo_of(i, k)));
      }
      meta_state_forward_backward(xi, t.initial_active, o_.stay, t.meta);
      t.active = t.meta.active;
    }
    // Module 1, kept per track only where it does not lower B.
    for (int i : batch_) {
      TrackRecord& t = tracks_[i];
      KinematicChain candidate = o_.joint_fusion ? joint_smoother(i) : smooth_and_fuse(i);
      if (track_kinematic_terms(i, candidate.marginal, candidate.coupling) >=
          track_kinematic_terms(i, t.marginal, t.coupling)) {
        t.marginal = std::move(candidate.marginal);
        t.coupling = std::move(candidate.coupling);
      } else {
        ++rejected;
      }
    }
    history.push_back(free_energy());
    report.iterations = r;
    if (iterations) {
      output(iterations->emplace_back());
      iterations->back().objective = history.back();
    }
    if (r > 1 && std::abs(history[r - 1] - history[r - 2]) < o_.convergence) {
      report.converged = true;
      break;
    }
  }
  report.free_energy = history.empty() ? std::numeric_limits<double>::quiet_NaN() : history.back();
}

void Run::output(TrackSet& out) const {
  out.tracks.clear();
  out.objective = std::numeric_limits<double>::quiet_NaN();
  for (int i : batch_) {
    const TrackRecord& t = tracks_[i];
    int from = -1, to = -1;
    for (int k = 0; k < t.length(); ++k)
      if (t.active[k] >= o_.confirm) {
        if (from < 0) from = k;
        to = k;
      }
    const bool confirmed = from >= 0;
    if (!confirmed) from = 0, to = t.length() - 1;
    Track track;
    track.id = t.id;
    track.first_scan = t.first + from;
    track.confirmed = confirmed;
    const int n = sensor_.state_dim(), length = to - from + 1;
    track.states.resize(n, length);
    track.covariance_diagonals.resize(n, length);
    for (int k = 0; k < length; ++k) {
      track.states.col(k) = t.marginal[from + k].mean;
      track.covariance_diagonals.col(k) = t.marginal[from + k].covariance.diagonal();
    }
    out.tracks.push_back(std::move(track));
  }
}

}  // namespace

JdtVbTracker::JdtVbTracker(const Options& options) : options_(options) {
  if (const std::string why = options_.validate(); !why.empty()) throw InputError("jdt-vb: " + why);
}

void JdtVbTracker::run(const TrackingProblem& problem, TrackSet& tracks, SolveReport& report) {
  report.reset();
  free_energy_history_.clear();
  rejected_updates_ = 0;
  if (!problem.sensor || problem.sensor->measurement_dim() < 3 ||
      static_cast<int>(problem.detection_probability.size()) != problem.sensor->paths()) {
    report.skipped = "problem_without_multipath_sensor";
    return;
  }
  if (Eigen::LLT<Eigen::MatrixXd>(problem.process_covariance).info() != Eigen::Success) {
    report.skipped = "process_covariance_not_positive_definite";
    return;
  }
  if (!(problem.region_volume() > 0.0)) {
    report.skipped = "empty_surveillance_region";
    return;
  }
  Run run(options_, problem);
  run.sequential_pass();
  run.batch(free_energy_history_, rejected_updates_, report, iteration_history());
  run.output(tracks);
  tracks.objective = report.free_energy;
}

DABENCH_REGISTER_TRACKER(JdtVbTracker);

}  // namespace dabench
