#include "algorithms/tracking/mptf.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <fmt/format.h>

#include "algorithms/tracking/chi_square.hpp"
#include "harness/tracking/registry.hpp"

namespace dabench {

std::string MptfOptions::validate() const {
  if (!(pg > 0.0 && pg < 1.0)) return fmt::format("pg = {} must be in (0, 1)", pg);
  if (confirm_scans < 1 || confirm_scans > 50) return fmt::format("confirm_scans = {} must be in 1..50", confirm_scans);
  if (confirm_hits < 1 || confirm_hits > confirm_scans) {
    return fmt::format("confirm_hits = {} must be in 1..confirm_scans ({})", confirm_hits, confirm_scans);
  }
  if (deletion_misses < 0 || deletion_misses > 100) return fmt::format("deletion_misses = {} must be in 0..100", deletion_misses);
  if (!(max_azimuth_rate > 0.0 && std::isfinite(max_azimuth_rate))) {
    return fmt::format("max_azimuth_rate = {} must be finite and > 0", max_azimuth_rate);
  }
  if (!(slant_psd_scale > 0.0 && std::isfinite(slant_psd_scale))) {
    return fmt::format("slant_psd_scale = {} must be finite and > 0", slant_psd_scale);
  }
  if (!(fusion_pg > 0.0 && fusion_pg < 1.0)) return fmt::format("fusion_pg = {} must be in (0, 1)", fusion_pg);
  if (!(duplicate_distance >= 0.0 && std::isfinite(duplicate_distance))) {
    return fmt::format("duplicate_distance = {} must be finite and >= 0", duplicate_distance);
  }
  if (ground_iterations < 1 || ground_iterations > 200) return fmt::format("ground_iterations = {} must be in 1..200", ground_iterations);
  if (confirm_members < 1 || confirm_members > 8) return fmt::format("confirm_members = {} must be in 1..8", confirm_members);
  return {};
}

namespace mptf {

namespace {

Matrix4 symmetrised(const Matrix4& m) { return 0.5 * (m + m.transpose()); }

}  // namespace

int pda_update(Estimate& track, const Eigen::MatrixXd& scan, const ScanIndex& index, const PdaModel& model,
               PdaScratch& scratch, std::vector<char>& gated) {
  const Eigen::Vector3d predicted = track.mean.head<3>();
  const Eigen::Matrix3d S = track.covariance.topLeftCorner<3, 3>() + model.noise;
  const Eigen::Matrix3d S_inv = S.llt().solve(Eigen::Matrix3d::Identity());
  const double half_width = std::sqrt(model.gate * S(0, 0));  // range extent of the gate ellipsoid
  scratch.columns.clear();
  scratch.innovations.clear();
  scratch.weights.clear();
  const auto begin = std::lower_bound(index.range.begin(), index.range.end(), predicted[0] - half_width);
  for (auto it = begin; it != index.range.end() && *it <= predicted[0] + half_width; ++it) {
    const int j = index.order[it - index.range.begin()];
    const Eigen::Vector3d nu = scan.col(j).head<3>() - predicted;
    const double d2 = nu.dot(S_inv * nu);
    if (d2 > model.gate) continue;
    gated[j] = 1;
    scratch.columns.push_back(j);
    scratch.innovations.push_back(nu);
    scratch.weights.push_back(std::exp(-0.5 * d2));
  }
  const int count = static_cast<int>(scratch.columns.size());
  if (count == 0) return 0;
  // b = λ |2πS|^{1/2} (1 − P_D P_G)/P_D; β_j = e_j/(b + Σe), β_0 = b/(b + Σe).
  const double b = model.clutter_density * std::pow(2.0 * std::numbers::pi, 1.5) * std::sqrt(S.determinant()) *
                   (1.0 - model.pd * model.pg) / model.pd;
  const double total = b + std::accumulate(scratch.weights.begin(), scratch.weights.end(), 0.0);
  const double beta_miss = b / total;
  Eigen::Vector3d nu = Eigen::Vector3d::Zero();
  Eigen::Matrix3d spread = Eigen::Matrix3d::Zero();
  for (int i = 0; i < count; ++i) {
    const double beta = scratch.weights[i] / total;
    nu += beta * scratch.innovations[i];
    spread += beta * scratch.innovations[i] * scratch.innovations[i].transpose();
  }
  const Eigen::Matrix<double, 4, 3> gain = track.covariance.leftCols<3>() * S_inv;  // P⁻Hᵀ S⁻¹
  track.mean += gain * nu;
  track.covariance = symmetrised(track.covariance - (1.0 - beta_miss) * gain * S * gain.transpose() +
                                 gain * (spread - nu * nu.transpose()) * gain.transpose());
  return count;
}

void TrackLogic::record(bool hit) {
  if (deleted_) return;
  if (!confirmed_) {
    hits_ += hit ? 1 : 0;
    --window_;
    if (hits_ >= needed_) confirmed_ = true;
    else if (window_ == 0) deleted_ = true;
    return;
  }
  misses_ = hit ? 0 : misses_ + 1;
  if (misses_ >= miss_limit_) deleted_ = true;
}

Vector4 slant_state(const MultipathMeasurementModel& sensor, int path, const Vector4& ground) {
  const Vector y = sensor.measure(path, ground);
  const Eigen::MatrixXd J = sensor.jacobian(path, ground);
  return {y[0], y[1], y[2], J(2, 0) * ground[1] + J(2, 2) * ground[3]};  // ζ̇ = ∇h_ζ·[ġ, 0, ϑ̇, 0]
}

Matrix4 slant_state_jacobian(const MultipathMeasurementModel& sensor, int path, const Vector4& ground) {
  Matrix4 J = Matrix4::Zero();
  const Eigen::MatrixXd H = sensor.jacobian(path, ground);
  J.topRows<3>() = H;
  J(3, 1) = H(2, 0);
  J(3, 3) = H(2, 2);
  // ∂ζ̇/∂g and ∂ζ̇/∂ϑ: central differences of ∇h_ζ·[ġ, 0, ϑ̇, 0].
  const double steps[2] = {1e-4 * std::max(1.0, std::abs(ground[0])), 1e-6};
  for (int c = 0; c < 2; ++c) {
    Vector4 plus = ground, minus = ground;
    plus[2 * c] += steps[c];
    minus[2 * c] -= steps[c];
    const Eigen::MatrixXd Hp = sensor.jacobian(path, plus), Hm = sensor.jacobian(path, minus);
    const double rate_plus = Hp(2, 0) * ground[1] + Hp(2, 2) * ground[3];
    const double rate_minus = Hm(2, 0) * ground[1] + Hm(2, 2) * ground[3];
    J(3, 2 * c) = (rate_plus - rate_minus) / (2.0 * steps[c]);
  }
  return J;
}

bool ground_from_slant(const MultipathMeasurementModel& sensor, int path, const Estimate& slant, int iterations,
                       Estimate& ground) {
  Vector4 x = slant.mean;  // OTHR slant and ground coordinates differ by tens of km
  for (int it = 0; it < iterations; ++it) {
    const Matrix4 J = slant_state_jacobian(sensor, path, x);
    const Vector4 step = J.partialPivLu().solve(slant.mean - slant_state(sensor, path, x));
    if (!step.allFinite()) return false;
    x += step;
    if (!(x[0] > 0.0)) return false;
    if ((step.array().abs() <= 1e-10 * (1.0 + x.array().abs())).all()) {
      const Matrix4 J_inv = slant_state_jacobian(sensor, path, x).inverse();
      ground.mean = x;
      ground.covariance = symmetrised(J_inv * slant.covariance * J_inv.transpose());
      return ground.covariance.allFinite();
    }
  }
  return false;
}

double fuse(const Estimate* const* members, int count, Estimate& fused) {
  Matrix4 information = Matrix4::Zero();
  Vector4 information_mean = Vector4::Zero();
  for (int i = 0; i < count; ++i) {
    const Matrix4 P_inv = members[i]->covariance.llt().solve(Matrix4::Identity());
    information += P_inv;
    information_mean += P_inv * members[i]->mean;
  }
  fused.covariance = symmetrised(information.llt().solve(Matrix4::Identity()));
  fused.mean = fused.covariance * information_mean;
  double chi2 = 0.0;
  for (int i = 0; i < count; ++i) {
    const Vector4 d = members[i]->mean - fused.mean;
    chi2 += d.dot(members[i]->covariance.llt().solve(d));
  }
  return chi2;
}

}  // namespace mptf

namespace {

using mptf::Estimate;
using mptf::Matrix4;
using mptf::Vector4;

constexpr int kMaxPaths = 8;  // labelling enumeration bound (N_P ≤ 8)

// A slant track's ground conversion under one path, in information form for fast fusion.
struct GroundHypothesis {
  bool valid = false;
  Estimate estimate;
  Matrix4 information;  // P⁻¹
};

struct SlantTrack {
  SlantTrack(int id_, int first_scan_, mptf::TrackLogic logic_) : id(id_), first_scan(first_scan_), logic(logic_) {}

  int id = 0;
  int first_scan = 0;
  Estimate current;
  std::vector<Estimate> history;  // filtered estimates, scans first_scan ..
  mptf::TrackLogic logic;
  bool grouped = false;
  bool convertible = false;  // some path's conversion succeeded this scan (confirmed tracks)
  std::array<GroundHypothesis, kMaxPaths> ground;  // this scan's conversions (confirmed tracks)
};

// A fused (ground) track: slant tracks with distinct paths.
struct Group {
  int output = -1;  // index of its fused track in the output, −1 until created
  std::vector<int> members;  // slant track ids
  std::vector<int> labels;   // path per member, −1 = none yet
  double chi2 = 0.0;
  Estimate fused{Vector4::Zero(), Matrix4::Identity()};
};

struct FusedOutput {
  bool confirmed = false;
  int first_scan = 0;
  std::vector<Vector4> means, diagonals;
};

// The best injective path labelling of a set of slant tracks (item 4 of the header).
struct Labeller {
  int paths = 0;
  int count = 0;
  const SlantTrack* const* tracks = nullptr;
  std::array<int, kMaxPaths> trial{}, best{};
  double best_chi2 = std::numeric_limits<double>::infinity();
  Estimate best_fused, scratch;

  double score(const std::array<int, kMaxPaths>& labels, Estimate& fused) const {
    Matrix4 information = Matrix4::Zero();
    Vector4 information_mean = Vector4::Zero();
    for (int i = 0; i < count; ++i) {
      const GroundHypothesis& h = tracks[i]->ground[labels[i]];
      if (!h.valid) return std::numeric_limits<double>::infinity();
      information += h.information;
      information_mean += h.information * h.estimate.mean;
    }
    fused.covariance = 0.5 * (information.inverse() + information.inverse().transpose());
    fused.mean = fused.covariance * information_mean;
    double chi2 = 0.0;
    for (int i = 0; i < count; ++i) {
      const GroundHypothesis& h = tracks[i]->ground[labels[i]];
      const Vector4 d = h.estimate.mean - fused.mean;
      chi2 += d.dot(h.information * d);
    }
    return chi2;
  }

  void search(int i, unsigned used) {
    if (i == count) {
      const double chi2 = score(trial, scratch);
      const bool better = std::isinf(best_chi2) ? chi2 < best_chi2 : chi2 < best_chi2 - 1e-9 * (1.0 + best_chi2);
      if (better) {
        best_chi2 = chi2;
        best = trial;
        best_fused = scratch;
      }
      return;
    }
    for (int tau = 0; tau < paths; ++tau) {
      if (used & (1u << tau)) continue;
      trial[i] = tau;
      search(i + 1, used | (1u << tau));
    }
  }

  // Least-χ² labelling; `current` (if complete and valid) wins ties.
  double run(const SlantTrack* const* members, int n, const int* current) {
    tracks = members;
    count = n;
    best_chi2 = std::numeric_limits<double>::infinity();
    bool complete = true;
    for (int i = 0; i < n; ++i) complete = complete && current[i] >= 0;
    if (complete) {
      std::copy(current, current + n, trial.begin());
      best_chi2 = score(trial, best_fused);
      best = trial;
    }
    search(0, 0u);
    return best_chi2;
  }
};

// One run of the tracker over a problem.
class MptfRun {
 public:
  MptfRun(const MptfOptions& options, const TrackingProblem& problem) : o_(options), problem_(problem) {
    const MultipathMeasurementModel& sensor = *problem.sensor;
    paths_ = sensor.paths();
    labeller_.paths = paths_;
    T_ = problem.scan_interval;
    miss_limit_ = o_.deletion_misses > 0 ? o_.deletion_misses : (problem.clutter_mean <= 200.0 ? 3 : 5);
    pda_.noise = sensor.noise_covariance(0).topLeftCorner<3, 3>();
    pda_.pd = std::accumulate(problem.detection_probability.begin(), problem.detection_probability.end(), 0.0) /
              static_cast<double>(problem.detection_probability.size());
    pda_.pg = o_.pg;
    pda_.gate = chi_square_quantile(o_.pg, 3);
    pda_.clutter_density = problem.clutter_mean > 0.0 ? problem.clutter_density() : 0.0;
    pair_gate_ = chi_square_quantile(o_.pg, 2);
    azimuth_gate_ = std::sqrt(chi_square_quantile(o_.pg, 1));
    merge_gate_ = chi_square_quantile(o_.fusion_pg, 4);
    set_slant_model();
  }

  void run(TrackSet& tracks) {
    std::vector<int> candidates;  // previous scan's measurements in no gate
    for (int k = 0; k < problem_.scan_count(); ++k) {
      const Eigen::MatrixXd& scan = problem_.scans[k];
      index_.build(scan);
      gated_.assign(scan.cols(), 0);
      update_slant_tracks(scan);
      std::vector<char> paired(scan.cols(), 0);
      if (k > 0) initiate(k, problem_.scans[k - 1], candidates, scan, paired);
      candidates.clear();
      for (int j = 0; j < scan.cols(); ++j) {
        if (!gated_[j] && !paired[j]) candidates.push_back(j);
      }
      remove_deleted_and_duplicates();
      fuse_scan(k);
    }
    write_output(tracks);
  }

 private:
  void set_slant_model() {
    const Eigen::MatrixXd& Q = problem_.process_covariance;
    const double q_r = o_.slant_psd_scale * Q(1, 1) / T_, q_z = o_.slant_psd_scale * Q(3, 3) / T_;
    Eigen::Matrix2d F1, Q1;
    F1 << 1.0, T_, 0.0, 1.0;
    Q1 << T_ * T_ * T_ / 3.0, T_ * T_ / 2.0, T_ * T_ / 2.0, T_;
    F_ = Matrix4::Zero();
    F_.block<2, 2>(0, 0) = F1;
    F_.block<2, 2>(2, 2) = F1;
    Q_ = Matrix4::Zero();
    Q_.block<2, 2>(0, 0) = q_r * Q1;
    Q_.block<2, 2>(2, 2) = q_z * Q1;
  }

  void update_slant_tracks(const Eigen::MatrixXd& scan) {
    for (SlantTrack& t : slant_) {
      t.current.mean = F_ * t.current.mean;
      t.current.covariance = F_ * t.current.covariance * F_.transpose() + Q_;
      const bool hit = mptf::pda_update(t.current, scan, index_, pda_, scratch_, gated_) > 0;
      t.logic.record(hit);
      t.history.push_back(t.current);
    }
  }

  // First M/N stage: pairs (y₁ at k − 1, y₂ at k) through the gate of header item 2.
  void initiate(int k, const Eigen::MatrixXd& previous, const std::vector<int>& candidates,
                const Eigen::MatrixXd& scan, std::vector<char>& paired) {
    const double var_r = pda_.noise(0, 0), var_rr = pda_.noise(1, 1), var_z = pda_.noise(2, 2);
    const double var_u = 2.0 * var_r + T_ * T_ * var_rr / 2.0, var_v = 2.0 * var_rr;
    const double window = std::sqrt(pair_gate_ * var_u) + 0.5 * T_ * std::sqrt(pair_gate_ * var_v);
    const double azimuth_window = T_ * o_.max_azimuth_rate + azimuth_gate_ * std::sqrt(2.0 * var_z);
    for (int j1 : candidates) {
      const Eigen::Vector3d y1 = previous.col(j1).head<3>();
      const double centre = y1[0] + T_ * y1[1];
      const auto begin = std::lower_bound(index_.range.begin(), index_.range.end(), centre - window);
      for (auto it = begin; it != index_.range.end() && *it <= centre + window; ++it) {
        const int j2 = index_.order[it - index_.range.begin()];
        if (gated_[j2]) continue;
        const Eigen::Vector3d y2 = scan.col(j2).head<3>();
        const double u = y2[0] - y1[0] - 0.5 * T_ * (y1[1] + y2[1]), v = y2[1] - y1[1];
        if (u * u / var_u + v * v / var_v > pair_gate_ || std::abs(y2[2] - y1[2]) > azimuth_window) continue;
        paired[j2] = 1;
        start_track(k, y1, y2);
      }
    }
  }

  // Two-point differencing (header item 2).
  void start_track(int k, const Eigen::Vector3d& y1, const Eigen::Vector3d& y2) {
    SlantTrack t(next_slant_id_++, k - 1, mptf::TrackLogic(o_.confirm_hits, o_.confirm_scans, miss_limit_));
    const double var_z = pda_.noise(2, 2);
    const double rate = (y2[2] - y1[2]) / T_;
    for (int s = 0; s < 2; ++s) {
      const Eigen::Vector3d& y = s == 0 ? y1 : y2;
      Estimate e;
      e.mean = Vector4(y[0], y[1], y[2], rate);
      e.covariance = Matrix4::Zero();
      e.covariance(0, 0) = pda_.noise(0, 0);
      e.covariance(1, 1) = pda_.noise(1, 1);
      e.covariance(2, 2) = var_z;
      e.covariance(2, 3) = e.covariance(3, 2) = (s == 0 ? -1.0 : 1.0) * var_z / T_;
      e.covariance(3, 3) = 2.0 * var_z / (T_ * T_);
      t.history.push_back(e);
    }
    t.current = t.history.back();
    slant_.push_back(std::move(t));
  }

  // Deletes tracks whose logic says so, then younger duplicates of older tracks.
  void remove_deleted_and_duplicates() {
    std::vector<char> drop(slant_.size(), 0);
    for (std::size_t a = 0; a < slant_.size(); ++a) {
      drop[a] = slant_[a].logic.deleted();
    }
    for (std::size_t a = 0; a < slant_.size(); ++a) {
      if (drop[a]) continue;
      for (std::size_t b = a + 1; b < slant_.size(); ++b) {  // b is younger (ids increase)
        if (drop[b]) continue;
        const Eigen::Vector3d d = slant_[a].current.mean.head<3>() - slant_[b].current.mean.head<3>();
        const Eigen::Matrix3d S =
            slant_[a].current.covariance.topLeftCorner<3, 3>() + slant_[b].current.covariance.topLeftCorner<3, 3>();
        if (d[0] * d[0] > 25.0 * S(0, 0)) continue;  // far apart in range: not a duplicate
        if (d.dot(S.llt().solve(d)) < o_.duplicate_distance) drop[b] = 1;
      }
    }
    std::size_t kept = 0;
    for (std::size_t a = 0; a < slant_.size(); ++a) {
      if (drop[a]) continue;
      if (kept != a) slant_[kept] = std::move(slant_[a]);  // (self-move would empty the history)
      ++kept;
    }
    slant_.erase(slant_.begin() + static_cast<std::ptrdiff_t>(kept), slant_.end());
    position_.assign(next_slant_id_, -1);
    for (std::size_t a = 0; a < slant_.size(); ++a) position_[slant_[a].id] = static_cast<int>(a);
  }

  GroundHypothesis convert(const Estimate& slant, int path) const {
    GroundHypothesis h;
    h.valid = mptf::ground_from_slant(*problem_.sensor, path, slant, o_.ground_iterations, h.estimate);
    if (h.valid) {
      const Eigen::LLT<Matrix4> llt(h.estimate.covariance);
      h.valid = llt.info() == Eigen::Success;
      h.information = llt.solve(Matrix4::Identity());
    }
    return h;
  }

  double label_group(Group& g) {
    const SlantTrack* members[kMaxPaths];
    for (std::size_t i = 0; i < g.members.size(); ++i) members[i] = &slant_[position_[g.members[i]]];
    g.chi2 = labeller_.run(members, static_cast<int>(g.members.size()), g.labels.data());
    std::copy(labeller_.best.begin(), labeller_.best.begin() + g.members.size(), g.labels.begin());
    g.fused = labeller_.best_fused;
    return g.chi2;
  }

  // Header item 4 (a)–(e) for scan k.
  void fuse_scan(int k) {
    for (SlantTrack& t : slant_) {
      if (!t.logic.confirmed()) continue;
      t.convertible = false;
      for (int tau = 0; tau < paths_; ++tau) {
        t.ground[tau] = convert(t.current, tau);
        t.convertible = t.convertible || t.ground[tau].valid;
      }
    }
    drop_lost_members();
    for (SlantTrack& t : slant_) {
      if (!t.logic.confirmed() || t.grouped || !t.convertible) continue;
      t.grouped = true;
      Group& g = groups_.emplace_back();
      g.members.push_back(t.id);
      g.labels.push_back(-1);
    }
    for (Group& g : groups_) label_feasibly(g);
    merge_groups();
    for (Group& g : groups_) {
      if (g.output < 0) {
        g.output = static_cast<int>(outputs_.size());
        outputs_.emplace_back();
        write_history(g, k);
      }
      FusedOutput& out = outputs_[g.output];
      if (!out.confirmed && static_cast<int>(g.members.size()) >= o_.confirm_members) {
        out.confirmed = true;
        write_history(g, k);  // the labels are now backed by confirm_members paths
      }
      out.means.push_back(g.fused.mean);
      out.diagonals.push_back(g.fused.covariance.diagonal());
    }
  }

  // A group with no feasible labelling (conversions failed) releases members from the last;
  // a lone member is always feasible (it is convertible).
  void label_feasibly(Group& g) {
    while (!std::isfinite(label_group(g)) && g.members.size() > 1) {
      slant_[position_[g.members.back()]].grouped = false;
      g.members.pop_back();
      g.labels.pop_back();
      std::fill(g.labels.begin(), g.labels.end(), -1);
    }
  }

  // Removes deleted and unconvertible members (the latter may start a group again later).
  void drop_lost_members() {
    for (Group& g : groups_) {
      std::size_t kept = 0;
      for (std::size_t i = 0; i < g.members.size(); ++i) {
        const int at = position_[g.members[i]];
        if (at < 0) continue;
        if (!slant_[at].convertible) {
          slant_[at].grouped = false;
          continue;
        }
        g.members[kept] = g.members[i];
        g.labels[kept++] = g.labels[i];
      }
      g.members.resize(kept);
      g.labels.resize(kept);
    }
    std::erase_if(groups_, [](const Group& g) { return g.members.empty(); });
  }

  // Greedy merging by least Δχ² (header item 4(d)).
  void merge_groups() {
    for (;;) {
      double best = merge_gate_;
      int best_a = -1, best_b = -1;
      for (std::size_t a = 0; a < groups_.size(); ++a) {
        for (std::size_t b = a + 1; b < groups_.size(); ++b) {
          const double increase = merge_increase(groups_[a], groups_[b]);
          if (increase <= best) {
            best = increase;
            best_a = static_cast<int>(a);
            best_b = static_cast<int>(b);
          }
        }
      }
      if (best_a < 0) return;
      merge(best_a, best_b);
    }
  }

  double merge_increase(const Group& a, const Group& b) {
    constexpr double kNever = std::numeric_limits<double>::infinity();
    const std::size_t n = a.members.size() + b.members.size();
    if (n > static_cast<std::size_t>(paths_)) return kNever;
    if (std::abs(a.fused.mean[0] - b.fused.mean[0]) > MultipathTrackFusion::kMergeWindowRange ||
        std::abs(a.fused.mean[2] - b.fused.mean[2]) > MultipathTrackFusion::kMergeWindowBearing) {
      return kNever;
    }
    const SlantTrack* members[kMaxPaths];
    int current[kMaxPaths];
    std::size_t i = 0;
    for (const Group* g : {&a, &b}) {
      for (std::size_t m = 0; m < g->members.size(); ++m, ++i) {
        members[i] = &slant_[position_[g->members[m]]];
        current[i] = -1;
      }
    }
    return labeller_.run(members, static_cast<int>(n), current) - a.chi2 - b.chi2;
  }

  // Merges groups a < b; the older fused track survives (a group without output is newest).
  void merge(int a, int b) {
    Group& ga = groups_[a];
    Group& gb = groups_[b];
    const bool a_older = ga.output >= 0 && (gb.output < 0 || ga.output < gb.output);
    Group& keep = a_older || gb.output < 0 ? ga : gb;
    Group& gone = &keep == &ga ? gb : ga;
    keep.members.insert(keep.members.end(), gone.members.begin(), gone.members.end());
    keep.labels.assign(keep.members.size(), -1);
    label_group(keep);
    groups_.erase(groups_.begin() + (&gone == &ga ? a : b));
  }

  // (Re)writes a fused track's states before scan k from its members' slant histories under
  // the current labels (header item 4).
  void write_history(const Group& g, int k) {
    FusedOutput& out = outputs_[g.output];
    int first = k;
    for (int id : g.members) first = std::min(first, slant_[position_[id]].first_scan);
    std::vector<Estimate> back;  // scans k − 1 down to the first that converts
    for (int s = k - 1; s >= first; --s) {
      std::vector<GroundHypothesis> hypotheses;
      for (std::size_t i = 0; i < g.members.size(); ++i) {
        const SlantTrack& t = slant_[position_[g.members[i]]];
        if (s < t.first_scan) continue;
        const GroundHypothesis h = convert(t.history[s - t.first_scan], g.labels[i]);
        if (h.valid) hypotheses.push_back(h);
      }
      if (hypotheses.empty()) break;
      std::vector<const Estimate*> estimates;
      for (const GroundHypothesis& h : hypotheses) estimates.push_back(&h.estimate);
      Estimate fused;
      mptf::fuse(estimates.data(), static_cast<int>(estimates.size()), fused);
      back.push_back(fused);
    }
    out.first_scan = k - static_cast<int>(back.size());
    out.means.clear();
    out.diagonals.clear();
    for (auto it = back.rbegin(); it != back.rend(); ++it) {
      out.means.push_back(it->mean);
      out.diagonals.push_back(it->covariance.diagonal());
    }
  }

  void write_output(TrackSet& tracks) const {
    tracks.tracks.clear();
    for (std::size_t i = 0; i < outputs_.size(); ++i) {
      const FusedOutput& out = outputs_[i];
      Track track;
      track.id = static_cast<int>(i);
      track.first_scan = out.first_scan;
      track.confirmed = out.confirmed;
      const int n = static_cast<int>(out.means.size());
      track.states.resize(4, n);
      track.covariance_diagonals.resize(4, n);
      for (int c = 0; c < n; ++c) {
        track.states.col(c) = out.means[c];
        track.covariance_diagonals.col(c) = out.diagonals[c];
      }
      tracks.tracks.push_back(std::move(track));
    }
  }

  const MptfOptions& o_;
  const TrackingProblem& problem_;
  int paths_ = 0;
  double T_ = 0.0;
  int miss_limit_ = 3;
  mptf::PdaModel pda_;
  double pair_gate_ = 0.0, azimuth_gate_ = 0.0, merge_gate_ = 0.0;
  Matrix4 F_, Q_;
  ScanIndex index_;
  mptf::PdaScratch scratch_;
  std::vector<char> gated_;
  std::vector<SlantTrack> slant_;
  std::vector<int> position_;  // slant id → index in slant_, −1 once deleted
  int next_slant_id_ = 0;
  std::vector<Group> groups_;
  std::vector<FusedOutput> outputs_;
  Labeller labeller_;
};

void check_mptf_problem(const TrackingProblem& problem) {
  if (!problem.sensor) throw InputError("mptf: the problem has no sensor model");
  const MultipathMeasurementModel& sensor = *problem.sensor;
  if (sensor.state_dim() != 4 || sensor.measurement_dim() != 3) {
    throw InputError("mptf: needs ground states [g, g', theta, theta'] and slant measurements [r, r', zeta]");
  }
  if (sensor.paths() < 1 || sensor.paths() > kMaxPaths) {
    throw InputError(fmt::format("mptf: {} paths; 1..{} supported", sensor.paths(), kMaxPaths));
  }
  if (static_cast<int>(problem.detection_probability.size()) != sensor.paths()) {
    throw InputError("mptf: one detection probability per path is needed");
  }
  for (double pd : problem.detection_probability) {
    if (!(pd > 0.0 && pd <= 1.0)) throw InputError(fmt::format("mptf: detection probability {} not in (0, 1]", pd));
  }
  if (!(problem.scan_interval > 0.0)) throw InputError("mptf: scan_interval must be > 0");
  if (problem.process_covariance.rows() != 4 || problem.process_covariance.cols() != 4) {
    throw InputError("mptf: process covariance must be 4 x 4");
  }
  for (const Eigen::MatrixXd& scan : problem.scans) {
    if (scan.cols() > 0 && scan.rows() != 3) throw InputError("mptf: scans must have 3 rows [r, r', zeta]");
  }
}

}  // namespace

void MultipathTrackFusion::run(const TrackingProblem& problem, TrackSet& tracks, SolveReport& report) {
  report.reset();
  check_mptf_problem(problem);
  MptfRun(options_, problem).run(tracks);
}

DABENCH_REGISTER_TRACKING_TRACKER(MultipathTrackFusion);

}  // namespace dabench
