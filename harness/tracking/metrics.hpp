#pragma once
// Multi-target tracking metrics of jdt-vb-multipath-othr Sec. IV-B (Table IV): NVT, TPD, NFT,
// TTL, AEE in ground range and bearing, MOSPA. TET is wall-clock time and is measured by the
// caller. Sec. IV-B defers the definitions to Gorji, Tharmarasa & Kirubarajan, "Performance
// measures for multiple target tracking problems", Fusion 2011 ([47]); it states only that
// values are averaged over Monte Carlo runs, that tracks shorter than five scans are excluded,
// that NFT = false tracks + ghost tracks, and that AEE-R is in km and AEE-B in mrad.
//
// Positions: the state is [g, ġ, ϑ, ϑ̇] (ground range km, bearing rad). Distances between a
// track and a target use the ground-plane point (g cos ϑ, g sin ϑ) in km, so range and bearing
// errors weigh alike; AEE reports the range and bearing errors separately.
//
// Which tracks count: confirmed tracks with at least min_track_length scans ("eligible").
// Association (Gorji's truth-to-track assignment, with our concrete rules):
//  - a track follows target i at scan k when both exist at k and their distance ≤ gate;
//  - a track is labelled with the target it follows on the most scans (ties: smaller summed
//    distance over those scans, then lower index) if it follows it on at least
//    min_follow_fraction of its own scans, otherwise it is a false track;
//  - per target, its tracks are taken in decreasing number of followed scans (ties: earlier
//    first scan, then lower id); a track whose scan span overlaps an already accepted track of
//    the same target is a ghost (redundant) track, otherwise it is accepted.
// Metrics of one run:
//  - NVT: targets with exactly one accepted track (Gorji: a valid track is assigned to one
//    target that is assigned to no other track; a broken track — several accepted tracks in
//    sequence — is therefore not valid).
//  - TPD: mean over targets alive in the run of (scans at which a track labelled with the
//    target follows it) / (scans the target is alive); NaN when no target is alive.
//  - NFT: false tracks + ghost tracks.
//  - TTL: mean over targets followed at least once of (first followed scan − first alive
//    scan), in scans; NaN when no target is followed.
//  - AEE-R, AEE-B: mean |ĝ − g| (km) and |ϑ̂ − ϑ| (rad) over the (target, scan) pairs at which
//    a labelled track follows the target (within the gate), using the nearest such track; NaN
//    when none. With `aee_assigned`, over every (target, scan) pair at which a track labelled
//    with the target exists, followed or not (the nearest such track): the errors of a track's
//    excursions beyond the gate count too (Gorji's AEE averages over assigned pairs; the
//    paper does not say which).
//  - MOSPA: mean over all K scans of OSPA (Schuhmacher, Vo & Vo 2008, eq 3) between the alive
//    targets' and the eligible tracks' ground-plane points (false and ghost tracks included),
//    order p, cut-off c (km).
#include <string>
#include <vector>

#include <Eigen/Core>

#include "harness/core/params.hpp"
#include "harness/tracking/problem.hpp"

namespace dabench {

// Settable in a tracking experiment's [metrics] section (recorded in meta.json).
struct TrackingMetricsOptions {
  int min_track_length = 5;           // Sec. IV-B: "tracks with minimum length five"
  double gate_km = 20.0;              // follow gate on ground-plane distance (not in the paper)
  double min_follow_fraction = 0.5;   // share of a track's scans on its target (not in the paper)
  double ospa_cutoff_km = 50.0;       // OSPA c (the paper gives none)
  double ospa_order = 2.0;            // OSPA p (the paper gives none)
  bool aee_assigned = false;          // AEE over every scan a labelled track shares with its target, not only followed ones

  void bind(ParamList& p);
  std::string validate() const;  // "" if valid; else why (a non-positive length, gate or cut-off, ...)
};

struct TrackingMetrics {
  double nvt = 0.0;             // number of valid tracks
  double tpd = 0.0;             // track probability of detection
  double nft = 0.0;             // false + ghost tracks
  double false_tracks = 0.0;    // of NFT: tracks following no target
  double ghost_tracks = 0.0;    // of NFT: redundant tracks on a target already tracked
  double broken_targets = 0.0;  // targets with more than one accepted track
  double ttl_scans = 0.0;       // tentative track latency, scans
  double aee_range_km = 0.0;    // AEE in ground range
  double aee_bearing_rad = 0.0; // AEE in bearing (Table IV prints mrad)
  double mospa_km = 0.0;        // mean OSPA over scans
};

// OSPA distance d_p^(c)(X, Y) between finite sets of points (Schuhmacher, Vo & Vo 2008, eq 3):
// 0 when both are empty, c when exactly one is.
double ospa_distance(const std::vector<Eigen::Vector2d>& x, const std::vector<Eigen::Vector2d>& y,
                     double cutoff, double order);

// Ground-plane point (g cos ϑ, g sin ϑ) of a state [g, ġ, ϑ, ϑ̇].
Eigen::Vector2d ground_point(const Eigen::VectorXd& state);

// Metrics of one run. InputError when the options are invalid or the tracks do not fit the
// truth (state dimension below 4, tracks outside the K scans, column counts that differ).
TrackingMetrics compute_tracking_metrics(const TrackingTruth& truth, const TrackSet& tracks,
                                         const TrackingMetricsOptions& options);

// Mean over runs, field by field, skipping runs where the field is NaN (TTL, AEE); NaN when
// every run is NaN. InputError on an empty list.
TrackingMetrics mean_over_runs(const std::vector<TrackingMetrics>& runs);

}  // namespace dabench
