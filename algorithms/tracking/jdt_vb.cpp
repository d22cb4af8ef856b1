#include "algorithms/tracking/jdt_vb.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Cholesky>
#include <fmt/format.h>

#include "algorithms/tracking/jdt_vb_run.hpp"
#include "harness/core/errors.hpp"
#include "harness/tracking/registry.hpp"

namespace dabench {

void JdtVbOptions::bind(ParamList& p) {
  p.add("convergence", convergence, "delta_T: stop when the free energy B changes by less, > 0");
  p.add("max_iterations", max_iterations, "r_max: VB iteration cap, >= 1");
  p.add("confirm", confirm, "delta_s: confirmation and deletion threshold on q(s=1), in (0, 1)");
  p.add("stay", stay, "p(s_k = s_k-1) of the meta-state chain, in (0, 1)");
  p.add("dormant_pd", dormant_pd, "detection probability of a dormant target (s = 0), in (0, 1)");
  p.add("delete_on_mean", delete_on_mean,
        "deletion reading of Sec. III-E: 1 = the mean q(s=1) of three scans < delta_s; 0 = q(s=1) < delta_s at each of three scans");
  p.add("gate_probability", gate_probability, "p_g of the gates (eq 33), in (0, 1)");
  p.add("head_range", head_range, "track-head threshold on slant range, km, > 0");
  p.add("head_range_rate", head_range_rate, "track-head threshold on slant range rate, km/s, > 0");
  p.add("head_azimuth", head_azimuth, "track-head threshold on azimuth, rad, > 0");
  p.add("head_bearing_rate_sd", head_bearing_rate_sd, "s.d. of the bearing rate of a new track, rad/s, > 0");
  p.add("joint_fusion", joint_fusion, "Module 1: 0 = per-path smoothers fused by eq (32), 1 = one smoother on all paths");
  p.add("alternative_heads", alternative_heads,
        "1: a head for every equally good path reading of a new return group (not in the paper); 0: only the best");
  p.add_choice("report_from", report_from, {"confirmation", "head"},
               "a confirmed track is output from its first scan with q(s=1) >= delta_s, or from its head scan");
  p.add("literal", literal, "1: the paper-literal set, overriding joint_fusion = 0 (eq 32) and alternative_heads = 0");
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
  if (report_from != kFromConfirmation && report_from != kFromHead)
    return fmt::format("report_from = {} must be 0 (confirmation) or 1 (head)", report_from);
  return association.validate();
}

JdtVbOptions JdtVbOptions::resolved() const {
  JdtVbOptions o = *this;
  if (literal) {
    o.joint_fusion = false;
    o.alternative_heads = false;
  }
  return o;
}

namespace jdt_vb_detail {

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
    tracks_[i].coupling = markov_couplings(tracks_[i].marginal, tracks_[i].first);
  }
}

void Run::batch(std::vector<double>& history, int& rejected, double& largest_rejected_decrease, SolveReport& report,
                std::vector<TrackSet>* iterations) {
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
      const double proposed = track_kinematic_terms(i, candidate.marginal, candidate.coupling);
      const double kept = track_kinematic_terms(i, t.marginal, t.coupling);
      if (proposed >= kept) {
        t.marginal = std::move(candidate.marginal);
        t.coupling = std::move(candidate.coupling);
      } else {
        ++rejected;
        if (!(kept - proposed <= largest_rejected_decrease)) largest_rejected_decrease = kept - proposed;  // NaN sticks
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
    if (!confirmed || o_.report_from == JdtVbOptions::kFromHead) from = 0;
    if (!confirmed) to = t.length() - 1;
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

}  // namespace jdt_vb_detail

JdtVbTracker::JdtVbTracker(const Options& options) : options_(options.resolved()) {
  if (const std::string why = options_.validate(); !why.empty()) throw InputError("jdt-vb: " + why);
}

void JdtVbTracker::run(const TrackingProblem& problem, TrackSet& tracks, SolveReport& report) {
  report.reset();
  free_energy_history_.clear();
  rejected_updates_ = 0;
  largest_rejected_decrease_ = 0.0;
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
  try {
    jdt_vb_detail::Run run(options_, problem);
    run.sequential_pass();
    run.batch(free_energy_history_, rejected_updates_, largest_rejected_decrease_, report, iteration_history());
    run.output(tracks);
  } catch (const UnscentedFailure& failure) {  // a covariance lost positive definiteness: no tracks
    tracks.tracks.clear();
    report.skipped = std::string("failed:") + failure.what();
    return;
  }
  tracks.objective = report.free_energy;
}

DABENCH_REGISTER_TRACKING_TRACKER(JdtVbTracker);

}  // namespace dabench
