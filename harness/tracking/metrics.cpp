#include "harness/core/special_values.hpp"
#include "harness/tracking/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "harness/core/errors.hpp"

namespace dabench {

namespace {

constexpr int kMaxOspaSmallerSet = 16;  // exact subset DP below is O(n · 2^m · m)

int last_scan(const Track& track) { return track.first_scan + track.length() - 1; }

// How one eligible track relates to one target, per scan of the track.
struct FollowRecord {
  std::vector<char> follows;  // per scan of the track: within the gate of the target
  int count = 0;
  double distance_sum = 0.0;
};

int truth_scan_count(const TrackingTruth& truth, const TrackSet& tracks) {
  int scans = -1;
  for (const auto& target : truth.targets) {
    const int k = static_cast<int>(target.alive.size());
    if (scans >= 0 && k != scans) throw InputError("tracking metrics: truth targets differ in scan count");
    if (target.states.cols() != k) throw InputError("tracking metrics: truth states and alive flags differ in length");
    if (target.states.rows() < 4) throw InputError("tracking metrics: truth state dimension below 4 ([g, ġ, ϑ, ϑ̇])");
    scans = k;
  }
  if (scans < 0)
    for (const auto& track : tracks.tracks) scans = std::max(scans, last_scan(track) + 1);
  if (scans <= 0) throw InputError("tracking metrics: no scans (no truth targets and no tracks)");
  return scans;
}

void check_track(const Track& track, int scans) {
  const std::string name = "tracking metrics: track " + std::to_string(track.id);
  if (track.states.rows() < 4) throw InputError(name + " has state dimension below 4");
  if (track.first_scan < 0 || last_scan(track) >= scans)
    throw InputError(name + " lies outside scans 0.." + std::to_string(scans - 1));
}

}  // namespace

void TrackingMetricsOptions::bind(ParamList& p) {
  p.add("min_track_length", min_track_length, "scans a confirmed track needs to be scored (Sec. IV-B: 5), >= 1");
  p.add("gate_km", gate_km,
        "follow gate, km of ground-plane distance: a track farther from a target does not follow it (not in the paper)");
  p.add("min_follow_fraction", min_follow_fraction, "share of a track's scans it must follow its target, else false, in (0, 1]");
  p.add("ospa_cutoff_km", ospa_cutoff_km, "OSPA cut-off c, km (not in the paper)");
  p.add("ospa_order", ospa_order, "OSPA order p (not in the paper), >= 1");
  p.add("aee_assigned", aee_assigned,
        "AEE pairs: 0 = scans a labelled track follows its target (within the gate); 1 = every scan it shares with it");
}

std::string TrackingMetricsOptions::validate() const {
  if (min_track_length < 1) return "min_track_length = " + std::to_string(min_track_length) + " must be >= 1";
  if (!(gate_km > 0.0 && std::isfinite(gate_km))) return "gate_km must be finite and > 0";
  if (!(min_follow_fraction > 0.0 && min_follow_fraction <= 1.0)) return "min_follow_fraction must be in (0, 1]";
  if (!(ospa_cutoff_km > 0.0 && std::isfinite(ospa_cutoff_km))) return "ospa_cutoff_km must be finite and > 0";
  if (!(ospa_order >= 1.0 && std::isfinite(ospa_order))) return "ospa_order must be finite and >= 1";
  return {};
}

Eigen::Vector2d ground_point(const Eigen::VectorXd& state) {
  return {state(0) * std::cos(state(2)), state(0) * std::sin(state(2))};
}

double ospa_distance(const std::vector<Eigen::Vector2d>& x, const std::vector<Eigen::Vector2d>& y,
                     double cutoff, double order) {
  const auto& small = x.size() <= y.size() ? x : y;
  const auto& large = x.size() <= y.size() ? y : x;
  const int m = static_cast<int>(small.size());
  const int n = static_cast<int>(large.size());
  if (n == 0) return 0.0;
  if (m > kMaxOspaSmallerSet)
    throw InputError("ospa: both sets exceed " + std::to_string(kMaxOspaSmallerSet) + " points");
  // min over injections π: small → large of Σ min(c, ‖s − l_π(s)‖)^p, by DP over the subset of
  // small points already matched while the large points are taken in turn.
  const std::size_t full = (std::size_t{1} << m) - 1;
  std::vector<double> best(full + 1, std::numeric_limits<double>::infinity());
  best[0] = 0.0;
  for (int j = 0; j < n; ++j) {
    for (std::size_t mask = full + 1; mask-- > 0;) {  // descending: each large point used once
      if (!std::isfinite(best[mask])) continue;
      for (int s = 0; s < m; ++s) {
        if (mask & (std::size_t{1} << s)) continue;
        const double d = std::min(cutoff, (small[s] - large[j]).norm());
        double& target = best[mask | (std::size_t{1} << s)];
        target = std::min(target, best[mask] + std::pow(d, order));
      }
    }
  }
  const double total = best[full] + std::pow(cutoff, order) * (n - m);
  return std::pow(total / n, 1.0 / order);
}

TrackingMetrics compute_tracking_metrics(const TrackingTruth& truth, const TrackSet& tracks,
                                         const TrackingMetricsOptions& options) {
  if (const std::string why = options.validate(); !why.empty()) throw InputError("tracking metrics: " + why);
  const int scans = truth_scan_count(truth, tracks);
  std::vector<const Track*> eligible;
  for (const auto& track : tracks.tracks) {
    check_track(track, scans);
    if (track.confirmed && track.length() >= options.min_track_length) eligible.push_back(&track);
  }
  const int targets = static_cast<int>(truth.targets.size());
  const int count = static_cast<int>(eligible.size());

  auto target_point = [&](int i, int k) { return ground_point(truth.targets[i].states.col(k)); };
  auto track_point = [&](int t, int k) {
    return ground_point(eligible[t]->states.col(k - eligible[t]->first_scan));
  };

  // follow[t][i]: per scan of track t, whether it follows target i (distance ≤ gate).
  std::vector<std::vector<FollowRecord>> follow(count, std::vector<FollowRecord>(targets));
  for (int t = 0; t < count; ++t) {
    const Track& track = *eligible[t];
    for (int i = 0; i < targets; ++i) {
      FollowRecord& record = follow[t][i];
      record.follows.assign(track.length(), 0);
      for (int k = track.first_scan; k <= last_scan(track); ++k) {
        if (!truth.targets[i].alive[k]) continue;
        const double d = (track_point(t, k) - target_point(i, k)).norm();
        if (d > options.gate_km) continue;
        record.follows[k - track.first_scan] = 1;
        ++record.count;
        record.distance_sum += d;
      }
    }
  }

  // Label each track with the target it follows most, or none (false track).
  TrackingMetrics metrics;
  std::vector<std::vector<int>> labelled(targets);
  for (int t = 0; t < count; ++t) {
    int label = -1;
    for (int i = 0; i < targets; ++i) {
      const FollowRecord& r = follow[t][i];
      if (r.count == 0) continue;
      if (label < 0 || r.count > follow[t][label].count ||
          (r.count == follow[t][label].count && r.distance_sum < follow[t][label].distance_sum))
        label = i;
    }
    if (label >= 0 && follow[t][label].count >= options.min_follow_fraction * eligible[t]->length())
      labelled[label].push_back(t);
    else
      metrics.false_tracks += 1.0;
  }

  // Per target: accepted tracks (non-overlapping spans, best followers first) and ghosts.
  for (int i = 0; i < targets; ++i) {
    auto order = labelled[i];
    std::sort(order.begin(), order.end(), [&](int a, int b) {
      if (follow[a][i].count != follow[b][i].count) return follow[a][i].count > follow[b][i].count;
      if (eligible[a]->first_scan != eligible[b]->first_scan)
        return eligible[a]->first_scan < eligible[b]->first_scan;
      return eligible[a]->id < eligible[b]->id;
    });
    std::vector<int> accepted;
    for (int t : order) {
      const bool overlaps = std::any_of(accepted.begin(), accepted.end(), [&](int a) {
        return eligible[t]->first_scan <= last_scan(*eligible[a]) &&
               eligible[a]->first_scan <= last_scan(*eligible[t]);
      });
      if (overlaps)
        metrics.ghost_tracks += 1.0;
      else
        accepted.push_back(t);
    }
    if (accepted.size() == 1) metrics.nvt += 1.0;
    if (accepted.size() > 1) metrics.broken_targets += 1.0;
  }
  metrics.nft = metrics.false_tracks + metrics.ghost_tracks;

  // TPD, TTL, AEE from the scans at which a labelled track follows its target.
  double tpd_sum = 0.0, ttl_sum = 0.0, range_error_sum = 0.0, bearing_error_sum = 0.0;
  int tpd_targets = 0, ttl_targets = 0, error_pairs = 0;
  for (int i = 0; i < targets; ++i) {
    const auto& target = truth.targets[i];
    int alive_scans = 0, covered_scans = 0, first_alive = -1, first_covered = -1;
    for (int k = 0; k < scans; ++k) {
      if (!target.alive[k]) continue;
      ++alive_scans;
      if (first_alive < 0) first_alive = k;
      // The nearest labelled track that follows the target at k (TPD, TTL, AEE), and the
      // nearest that merely exists at k (AEE with aee_assigned).
      int nearest = -1, nearest_assigned = -1;
      double nearest_distance = 0.0, nearest_assigned_distance = 0.0;
      for (int t : labelled[i]) {
        const Track& track = *eligible[t];
        if (k < track.first_scan || k > last_scan(track)) continue;
        const double d = (track_point(t, k) - target_point(i, k)).norm();
        if (nearest_assigned < 0 || d < nearest_assigned_distance) nearest_assigned = t, nearest_assigned_distance = d;
        if (!follow[t][i].follows[k - track.first_scan]) continue;
        if (nearest < 0 || d < nearest_distance) nearest = t, nearest_distance = d;
      }
      if (nearest >= 0) {
        ++covered_scans;
        if (first_covered < 0) first_covered = k;
      }
      const int scored = options.aee_assigned ? nearest_assigned : nearest;
      if (scored < 0) continue;
      const auto estimate = eligible[scored]->states.col(k - eligible[scored]->first_scan);
      range_error_sum += std::abs(estimate(0) - target.states(0, k));
      bearing_error_sum += std::abs(estimate(2) - target.states(2, k));
      ++error_pairs;
    }
    if (alive_scans == 0) continue;
    tpd_sum += static_cast<double>(covered_scans) / alive_scans;
    ++tpd_targets;
    if (first_covered >= 0) ttl_sum += first_covered - first_alive, ++ttl_targets;
  }
  metrics.tpd = tpd_targets > 0 ? tpd_sum / tpd_targets : kNaN;
  metrics.ttl_scans = ttl_targets > 0 ? ttl_sum / ttl_targets : kNaN;
  metrics.aee_range_km = error_pairs > 0 ? range_error_sum / error_pairs : kNaN;
  metrics.aee_bearing_rad = error_pairs > 0 ? bearing_error_sum / error_pairs : kNaN;

  // MOSPA: OSPA per scan between alive targets and eligible tracks, averaged over the K scans.
  double ospa_sum = 0.0;
  for (int k = 0; k < scans; ++k) {
    std::vector<Eigen::Vector2d> truth_points, track_points;
    for (int i = 0; i < targets; ++i)
      if (truth.targets[i].alive[k]) truth_points.push_back(target_point(i, k));
    for (int t = 0; t < count; ++t)
      if (k >= eligible[t]->first_scan && k <= last_scan(*eligible[t])) track_points.push_back(track_point(t, k));
    ospa_sum += ospa_distance(truth_points, track_points, options.ospa_cutoff_km, options.ospa_order);
  }
  metrics.mospa_km = ospa_sum / scans;
  return metrics;
}

TrackingMetrics mean_over_runs(const std::vector<TrackingMetrics>& runs) {
  if (runs.empty()) throw InputError("tracking metrics: no runs to average");
  static constexpr double TrackingMetrics::*kFields[] = {
      &TrackingMetrics::nvt,          &TrackingMetrics::tpd,          &TrackingMetrics::nft,
      &TrackingMetrics::false_tracks, &TrackingMetrics::ghost_tracks, &TrackingMetrics::broken_targets,
      &TrackingMetrics::ttl_scans,    &TrackingMetrics::aee_range_km, &TrackingMetrics::aee_bearing_rad,
      &TrackingMetrics::mospa_km};
  TrackingMetrics mean;
  for (auto field : kFields) {
    double sum = 0.0;
    int defined = 0;
    for (const auto& run : runs)
      if (!std::isnan(run.*field)) sum += run.*field, ++defined;
    mean.*field = defined > 0 ? sum / defined : kNaN;
  }
  return mean;
}

}  // namespace dabench
