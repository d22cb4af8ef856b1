// Tests of the tracking metrics (harness/tracking/metrics.hpp) on hand-worked cases: OSPA of
// small point sets (empty sets, cut-off, order, optimal assignment), and the run metrics on a
// two-target truth (target 0 alive scans 0..19, target 1 alive 9..29, K = 30, both standing
// still) with a perfect tracker, a false track, a late track, a broken track, a ghost track,
// short and tentative tracks, and known range and bearing errors.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "harness/core/errors.hpp"
#include "harness/core/special_values.hpp"
#include "harness/tracking/metrics.hpp"

namespace DABENCH_TEST_FILE {

namespace {

using dabench::kNaN;
using dabench::Track;
using dabench::TrackingMetrics;
using dabench::TrackingMetricsOptions;
using dabench::TrackingTruth;
using dabench::TrackSet;
using Eigen::Vector2d;

constexpr int kScans = 30;

// Fixed [g, ġ, ϑ, ϑ̇] of the two targets, and their alive scans.
const double kRange[2] = {1700.0, 1850.0};
const double kBearing[2] = {0.48, 0.54};
const int kFirst[2] = {0, 9};
const int kLast[2] = {19, 29};

TrackingTruth two_targets() {
  TrackingTruth truth;
  for (int i = 0; i < 2; ++i) {
    TrackingTruth::Target target;
    target.states = Eigen::MatrixXd::Constant(4, kScans, kNaN);
    target.alive.assign(kScans, false);
    for (int k = kFirst[i]; k <= kLast[i]; ++k) {
      target.states.col(k) << kRange[i], 0.0, kBearing[i], 0.0;
      target.alive[k] = true;
    }
    truth.targets.push_back(target);
  }
  return truth;
}

Track track_at(int id, int first, int last, double range, double bearing, bool confirmed = true) {
  Track track;
  track.id = id;
  track.first_scan = first;
  track.states.resize(4, last - first + 1);
  track.covariance_diagonals = Eigen::MatrixXd::Ones(4, last - first + 1);
  for (int c = 0; c < track.length(); ++c) track.states.col(c) << range, 0.0, bearing, 0.0;
  track.confirmed = confirmed;
  return track;
}

// A track on target i over scans first..last with errors dg (km) and dθ (rad).
Track on_target(int id, int i, int first, int last, double dg = 0.0, double dtheta = 0.0) {
  return track_at(id, first, last, kRange[i] + dg, kBearing[i] + dtheta);
}

TrackSet perfect() {
  TrackSet set;
  for (int i = 0; i < 2; ++i) set.tracks.push_back(on_target(i + 1, i, kFirst[i], kLast[i]));
  return set;
}

TrackingMetrics metrics_of(const TrackSet& set) {
  return dabench::compute_tracking_metrics(two_targets(), set, TrackingMetricsOptions{});
}

void require_ideal(const TrackingMetrics& m) {
  REQUIRE(m.nvt == 2.0);
  REQUIRE(m.tpd == Approx(1.0));
  REQUIRE(m.nft == 0.0);
  REQUIRE(m.broken_targets == 0.0);
  REQUIRE(m.ttl_scans == 0.0);
  REQUIRE(m.aee_range_km == Approx(0.0).margin(1e-12));
  REQUIRE(m.aee_bearing_rad == Approx(0.0).margin(1e-12));
  REQUIRE(m.mospa_km == Approx(0.0).margin(1e-9));
}

}  // namespace

TEST_CASE("ospa of empty and one-sided sets") {
  const std::vector<Vector2d> none;
  const std::vector<Vector2d> one{Vector2d(3.0, 4.0)};
  REQUIRE(dabench::ospa_distance(none, none, 50.0, 2.0) == 0.0);
  REQUIRE(dabench::ospa_distance(one, none, 50.0, 2.0) == Approx(50.0));
  REQUIRE(dabench::ospa_distance(none, one, 7.0, 1.0) == Approx(7.0));
}

TEST_CASE("ospa of two pairs at known distances and the order p") {
  // Distances 3 and 4 under the optimal pairing: p = 1 → (3 + 4)/2, p = 2 → √((9 + 16)/2).
  const std::vector<Vector2d> x{Vector2d(0.0, 0.0), Vector2d(10.0, 0.0)};
  const std::vector<Vector2d> y{Vector2d(10.0, 4.0), Vector2d(0.0, 3.0)};
  REQUIRE(dabench::ospa_distance(x, y, 100.0, 1.0) == Approx(3.5));
  REQUIRE(dabench::ospa_distance(x, y, 100.0, 2.0) == Approx(std::sqrt(12.5)));
  REQUIRE(dabench::ospa_distance(y, x, 100.0, 2.0) == Approx(std::sqrt(12.5)));
}

TEST_CASE("ospa takes the optimal assignment not the listed order") {
  // Listed order pairs at 1.1 and 0.9 (sum 2.0); the optimal pairing has 0.1 and 0.1.
  const std::vector<Vector2d> x{Vector2d(0.0, 0.0), Vector2d(1.0, 0.0)};
  const std::vector<Vector2d> y{Vector2d(1.1, 0.0), Vector2d(0.1, 0.0)};
  REQUIRE(dabench::ospa_distance(x, y, 100.0, 1.0) == Approx(0.1));
}

TEST_CASE("ospa cut-off caps distances and charges unmatched points") {
  // One truth at distance 3 from a track, a second track far away: cost min(c, d) per pair,
  // c per unmatched point, n = 2. c = 5: p = 1 → (3 + 5)/2 = 4; p = 2 → √((9 + 25)/2) = √17.
  const std::vector<Vector2d> x{Vector2d(0.0, 0.0)};
  const std::vector<Vector2d> y{Vector2d(0.0, 3.0), Vector2d(100.0, 100.0)};
  REQUIRE(dabench::ospa_distance(x, y, 5.0, 1.0) == Approx(4.0));
  REQUIRE(dabench::ospa_distance(x, y, 5.0, 2.0) == Approx(std::sqrt(17.0)));
  // A pair farther apart than c costs c, as a miss and a false point would: p = 2, c = 2 → 2.
  REQUIRE(dabench::ospa_distance(x, {Vector2d(0.0, 3.0)}, 2.0, 2.0) == Approx(2.0));
}

TEST_CASE("a perfect tracker has ideal metrics") { require_ideal(metrics_of(perfect())); }

TEST_CASE("a false track counts in NFT and in MOSPA") {
  TrackSet set = perfect();
  set.tracks.push_back(track_at(7, 0, 9, 1500.0, 0.48));  // 200 km from target 0, beyond gate and c
  const TrackingMetrics m = metrics_of(set);
  REQUIRE(m.false_tracks == 1.0);
  REQUIRE(m.ghost_tracks == 0.0);
  REQUIRE(m.nft == 1.0);
  REQUIRE(m.nvt == 2.0);
  REQUIRE(m.tpd == Approx(1.0));
  // Scans 0..8: {t0} vs {t0, false} → c·√(1/2); scan 9: {t0, t1} vs {t0, t1, false} → c·√(1/3);
  // other scans 0. c = 50, p = 2.
  const double c = 50.0;
  REQUIRE(m.mospa_km == Approx((9.0 * c * std::sqrt(0.5) + c * std::sqrt(1.0 / 3.0)) / kScans));
}

TEST_CASE("a late track raises TTL and lowers TPD") {
  TrackSet set = perfect();
  set.tracks[0] = on_target(1, 0, 3, 19);  // target 0 born at scan 0, tracked from scan 3
  const TrackingMetrics m = metrics_of(set);
  REQUIRE(m.ttl_scans == Approx((3.0 + 0.0) / 2.0));
  REQUIRE(m.tpd == Approx((17.0 / 20.0 + 1.0) / 2.0));
  REQUIRE(m.nvt == 2.0);
  REQUIRE(m.nft == 0.0);
  // Scans 0..2: one target, no track → c each.
  REQUIRE(m.mospa_km == Approx(3.0 * 50.0 / kScans));
}

TEST_CASE("a broken track makes the target not validly tracked") {
  TrackSet set = perfect();
  set.tracks[0] = on_target(1, 0, 0, 9);
  set.tracks.push_back(on_target(3, 0, 12, 19));  // gap at scans 10 and 11
  const TrackingMetrics m = metrics_of(set);
  REQUIRE(m.nvt == 1.0);
  REQUIRE(m.broken_targets == 1.0);
  REQUIRE(m.nft == 0.0);
  REQUIRE(m.tpd == Approx((18.0 / 20.0 + 1.0) / 2.0));
  REQUIRE(m.ttl_scans == 0.0);
  // Scans 10, 11: {t0, t1} vs {t1} → c·√(1/2).
  REQUIRE(m.mospa_km == Approx(2.0 * 50.0 * std::sqrt(0.5) / kScans));
}

TEST_CASE("a ghost track on a tracked target counts in NFT") {
  TrackSet set = perfect();
  set.tracks.push_back(on_target(4, 0, 5, 14, 2.0));  // redundant, 2 km off, overlapping track 1
  const TrackingMetrics m = metrics_of(set);
  REQUIRE(m.ghost_tracks == 1.0);
  REQUIRE(m.false_tracks == 0.0);
  REQUIRE(m.nft == 1.0);
  REQUIRE(m.nvt == 2.0);
  REQUIRE(m.broken_targets == 0.0);
  REQUIRE(m.aee_range_km == Approx(0.0).margin(1e-12));  // errors from the nearest track
  // Scans 5..8: {t0} vs {track 1, ghost} → track 1 matches exactly, the ghost costs c: c·√(1/2);
  // scans 9..14: {t0, t1} vs three tracks → c·√(1/3).
  const double c = 50.0;
  REQUIRE(m.mospa_km == Approx((4.0 * c * std::sqrt(0.5) + 6.0 * c * std::sqrt(1.0 / 3.0)) / kScans));
}

TEST_CASE("short and tentative tracks are excluded") {
  TrackSet set = perfect();
  set.tracks.push_back(track_at(5, 0, 3, 1500.0, 0.48));                 // 4 scans: too short
  set.tracks.push_back(track_at(6, 0, 29, 1500.0, 0.48, false));         // tentative
  set.tracks.push_back(on_target(8, 1, 2, 5));                           // 4 scans, before t1's birth
  require_ideal(metrics_of(set));
  set.tracks.push_back(track_at(9, 20, 24, 1500.0, 0.48));               // 5 scans: counted
  REQUIRE(metrics_of(set).false_tracks == 1.0);
}

TEST_CASE("AEE averages hand-computed range and bearing errors") {
  TrackSet set = perfect();
  // Target 0: +1 km for scans 0..9, −3 km for 10..19, bearing +0.002 rad throughout (3.4 km
  // cross-range at 1700 km, inside the 20 km gate). Target 1 (21 scans) exact.
  set.tracks[0] = on_target(1, 0, 0, 19, 0.0, 0.002);
  for (int c = 0; c < 20; ++c) set.tracks[0].states(0, c) += c < 10 ? 1.0 : -3.0;
  const TrackingMetrics m = metrics_of(set);
  REQUIRE(m.aee_range_km == Approx((10.0 * 1.0 + 10.0 * 3.0) / 41.0));
  REQUIRE(m.aee_bearing_rad == Approx(20.0 * 0.002 / 41.0));
  REQUIRE(m.nvt == 2.0);
  REQUIRE(m.tpd == Approx(1.0));
}

TEST_CASE("a track beyond the gate of its target is false and the target missed") {
  TrackSet set = perfect();
  set.tracks[0] = on_target(1, 0, 0, 19, 25.0);  // 25 km > 20 km gate
  const TrackingMetrics m = metrics_of(set);
  REQUIRE(m.false_tracks == 1.0);
  REQUIRE(m.nvt == 1.0);
  REQUIRE(m.tpd == Approx(0.5));
  REQUIRE(m.ttl_scans == 0.0);  // only target 1 is followed
}

TEST_CASE("the follow gate and the OSPA cut-off are options that change the metrics as computed") {
  // Target 0's track 25 km out in range over its whole life (scans 0..19); target 1 exact.
  TrackSet set = perfect();
  set.tracks[0] = on_target(1, 0, 0, 19, 25.0);
  TrackingMetricsOptions options;
  // OSPA per scan (p = 2): scans 0..8 {t0} vs {off}: min(c, 25); scans 9..19 {t0, t1} vs
  // {off, t1}: min(c, 25)/√2; scans 20..29: 0.
  const auto mospa = [](double c) { return (9.0 * std::min(c, 25.0) + 11.0 * std::min(c, 25.0) / std::sqrt(2.0)) / kScans; };
  // Default gate 20 km < 25: a false track, target 0 missed (as in the test above).
  TrackingMetrics m = dabench::compute_tracking_metrics(two_targets(), set, options);
  REQUIRE(m.nvt == 1.0);
  REQUIRE(m.false_tracks == 1.0);
  REQUIRE(m.aee_range_km == Approx(0.0).margin(1e-12));
  REQUIRE(m.mospa_km == Approx(mospa(50.0)));
  // gate_km = 50: it follows target 0; AEE-R takes its 20 scans of 25 km over 41 pairs.
  options.gate_km = 50.0;
  m = dabench::compute_tracking_metrics(two_targets(), set, options);
  REQUIRE(m.nvt == 2.0);
  REQUIRE(m.nft == 0.0);
  REQUIRE(m.tpd == Approx(1.0));
  REQUIRE(m.aee_range_km == Approx(20.0 * 25.0 / 41.0));
  REQUIRE(m.mospa_km == Approx(mospa(50.0)));  // OSPA does not use the gate
  // ospa_cutoff_km = 10 caps the 25 km error at 10; 100 leaves MOSPA as at 50 here ...
  options.ospa_cutoff_km = 10.0;
  REQUIRE(dabench::compute_tracking_metrics(two_targets(), set, options).mospa_km == Approx(mospa(10.0)));
  options.ospa_cutoff_km = 100.0;
  REQUIRE(dabench::compute_tracking_metrics(two_targets(), set, options).mospa_km == Approx(mospa(100.0)));
  // ... but doubles what a missed target costs: target 0 untracked at scans 0..2.
  TrackSet late = perfect();
  late.tracks[0] = on_target(1, 0, 3, 19);
  REQUIRE(dabench::compute_tracking_metrics(two_targets(), late, options).mospa_km == Approx(3.0 * 100.0 / kScans));
  // Bad values are InputErrors naming the key.
  options.gate_km = 0.0;
  REQUIRE(options.validate() == "gate_km must be finite and > 0");
  REQUIRE_THROWS_AS(dabench::compute_tracking_metrics(two_targets(), set, options), dabench::InputError);
}

TEST_CASE("aee_assigned averages the errors of every scan a labelled track shares with its target") {
  // Target 0's track is exact on scans 0..9 and 30 km off in range on 10..14 (beyond the 20 km
  // gate), then exact on 15..19: it follows on 15 of 20 scans (≥ half), so it is labelled with
  // target 0 and the target counts as covered on those 15. Target 1 exact.
  TrackSet set = perfect();
  for (int c = 10; c < 15; ++c) set.tracks[0].states(0, c) += 30.0;
  TrackingMetricsOptions options;
  TrackingMetrics followed = dabench::compute_tracking_metrics(two_targets(), set, options);
  REQUIRE(followed.nvt == 2.0);
  REQUIRE(followed.tpd == Approx((15.0 / 20.0 + 1.0) / 2.0));
  REQUIRE(followed.aee_range_km == Approx(0.0).margin(1e-12));  // the excursion is not followed
  options.aee_assigned = true;
  const TrackingMetrics assigned = dabench::compute_tracking_metrics(two_targets(), set, options);
  // 5 scans of 30 km among 20 + 21 assigned (target, scan) pairs; nothing else changes.
  REQUIRE(assigned.aee_range_km == Approx(5.0 * 30.0 / 41.0));
  REQUIRE(assigned.aee_bearing_rad == Approx(0.0).margin(1e-12));
  REQUIRE(assigned.tpd == followed.tpd);
  REQUIRE(assigned.nvt == followed.nvt);
  REQUIRE(assigned.ttl_scans == followed.ttl_scans);
  REQUIRE(assigned.mospa_km == followed.mospa_km);
  // A track beyond the gate on more than half of its scans is false: it has no assigned pairs.
  TrackSet far = perfect();
  far.tracks[0] = on_target(1, 0, 0, 19, 25.0);
  REQUIRE(dabench::compute_tracking_metrics(two_targets(), far, options).aee_range_km == Approx(0.0).margin(1e-12));
}

TEST_CASE("mean over runs skips undefined fields") {
  TrackingMetrics a, b;
  a.nvt = 4.0, b.nvt = 2.0;
  a.aee_range_km = 1.5, b.aee_range_km = kNaN;
  a.ttl_scans = kNaN, b.ttl_scans = kNaN;
  const TrackingMetrics mean = dabench::mean_over_runs({a, b});
  REQUIRE(mean.nvt == 3.0);
  REQUIRE(mean.aee_range_km == 1.5);
  REQUIRE(std::isnan(mean.ttl_scans));
  REQUIRE_THROWS_AS(dabench::mean_over_runs({}), dabench::InputError);
}

TEST_CASE("tracking metrics reject tracks outside the run and bad options") {
  TrackSet set = perfect();
  set.tracks.push_back(on_target(9, 1, 25, 30));  // scan 30 does not exist (K = 30)
  REQUIRE_THROWS_AS(metrics_of(set), dabench::InputError);
  TrackingMetricsOptions options;
  options.ospa_order = 0.5;
  REQUIRE_THROWS_AS(dabench::compute_tracking_metrics(two_targets(), perfect(), options), dabench::InputError);
}

}  // namespace DABENCH_TEST_FILE
