#pragma once
// MPTF: multipath track fusion, the simple baseline of jdt-vb-multipath-othr (Sec. IV;
// parameters Sec. IV-A2: M/N 2/2 & 1/3, deletion after 3 or 5 scans with an empty gate,
// P_G = 0.971; results Table IV). Its ref. [11] (Percival & White's multihypothesis fusion of
// multipath OTHR tracks) was found only as abstracts: the equations below are ours.
//
// 1. Slant tracks, one PDA filter each, paths unknown to it. s = [r, ṙ, ζ, ζ̇], near-constant
//    velocity: F_s = I₂ ⊗ [[1, T], [0, 1]], Q_s = diag(q_r, q_ζ) ⊗ [[T³/3, T²/2], [T²/2, T]],
//    q_r, q_ζ = slant_psd_scale × the problem's ground PSDs (Q(1,1)/T, Q(3,3)/T); y = [I₃ 0] s + v,
//    v ~ N(0, R of path 0). Linear, so the paper's UKF is this Kalman filter. PDA with gate
//    ν_jᵀS⁻¹ν_j ≤ γ = χ²₃(P_G), e_j = exp(−ν_jᵀS⁻¹ν_j / 2), ν = Σ β_j ν_j, K = P⁻Hᵀ S⁻¹:
//      b = λ (2π)^{3/2} |S|^{1/2} (1 − P_D P_G) / P_D,  β_j = e_j / (b + Σe),  β_0 = b / (b + Σe),
//      m = m⁻ + K ν,  P = P⁻ − (1 − β_0) K S Kᵀ + K (Σ β_j ν_j ν_jᵀ − ν νᵀ) Kᵀ,
//    λ the clutter density, P_D the paths' mean detection probability; empty gate: prediction.
// 2. Track logic "2/2 & 1/3" as a cascade. A measurement y₁ in no gate at scan k−1 and y₂ in
//    no gate at k start a tentative track when (u = r₂ − r₁ − T(ṙ₁ + ṙ₂)/2, v = ṙ₂ − ṙ₁)
//      u²/(2σ_r² + T²σ_ṙ²/2) + v²/(2σ_ṙ²) ≤ χ²₂(P_G),  |ζ₂ − ζ₁| ≤ T ζ̇_max + √χ²₁(P_G) √2 σ_ζ,
//    with two-point-differenced states at both scans. confirm_hits hits in the next
//    confirm_scans scans confirm it, else it is deleted; a confirmed track is deleted after
//    miss_limit consecutive empty gates (deletion_misses; 0 = 3 if N_c ≤ 200 else 5). A track
//    within squared Mahalanobis distance duplicate_distance of an older one in (r, ṙ, ζ) is deleted.
// 3. Slant → ground under path τ: x solves S^τ(x) = m by Gauss–Newton from x = m, where
//    S^τ(x) = [h^τ(x) (eq 57), ∇h^τ_ζ(x)·[ġ, 0, ϑ̇, 0]]; covariance J⁻¹ P J⁻ᵀ.
// 4. Fusion. A group G of confirmed slant tracks with distinct paths τ_i, ground estimates
//    (x_i, P_i) under them:
//      P_G⁻¹ = Σ_i P_i⁻¹,  x_G = P_G Σ_i P_i⁻¹ x_i,  χ²(G) = Σ_i (x_i − x_G)ᵀ P_i⁻¹ (x_i − x_G);
//    its labels are the injective labelling with least χ² (ties keep the current ones). Each
//    scan: (a) deleted members leave (an empty group ends its fused track); (b) each newly
//    confirmed slant track is a group of one; (c) every group is relabelled; (d) greedily, the
//    pair (A, B) with least Δχ² = χ²(A ∪ B) − χ²(A) − χ²(B) merges while Δχ² ≤ χ²₄(fusion_pg)
//    (at most N_P members, within kMergeWindowRange / kMergeWindowBearing; the older fused track
//    survives); (e) x_G, diag P_G is the fused track's output. A new fused track is back-filled
//    from its members' slant histories.
// 5. A fused track is confirmed once it fuses confirm_members (default 3) slant tracks at one
//    scan; its history is then rewritten under that scan's labels. Unconfirmed fused tracks are
//    output with confirmed = false.
// Background and our readings: docs/algorithms/tracking.md, "MPTF".
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "algorithms/tracking/scan_index.hpp"
#include "harness/core/params.hpp"
#include "harness/tracking/tracker.hpp"

namespace dabench {

struct MptfOptions {
  double pg = 0.971;               // P_G, PDA gate probability (paper: 0.971), in (0, 1)
  int confirm_hits = 1;            // M of the second M/N stage (paper: 1/3)
  int confirm_scans = 3;           // N of the second M/N stage (paper: 1/3)
  int deletion_misses = 0;         // scans without gated measurement before deletion; 0 = 3 if N_c ≤ 200 else 5
  double max_azimuth_rate = 3e-4;  // ζ̇_max of the initiation gate, rad/s (≈ 3.4× the scenario's ϑ̇)
  double slant_psd_scale = 1.0;    // slant process PSDs = this × the problem's ground PSDs
  double fusion_pg = 0.99;         // merge gate: Δχ² ≤ χ²₄ quantile at fusion_pg, in (0, 1)
  double duplicate_distance = 4.0; // squared Mahalanobis distance under which slant tracks duplicate
  int ground_iterations = 20;      // Gauss–Newton cap of the slant → ground conversion
  int confirm_members = 3;         // a fused track is confirmed once it fuses this many slant tracks

  void bind(ParamList& p) {
    p.add("pg", pg, "PDA gate probability P_G, in (0, 1)");
    p.add("confirm_hits", confirm_hits, "M of the second M/N stage (1/3), in 1..confirm_scans");
    p.add("confirm_scans", confirm_scans, "N of the second M/N stage (1/3), in 1..50");
    p.add("deletion_misses", deletion_misses,
          "consecutive scans without gated measurement before deletion, 0..100; 0 = 3 if clutter <= 200 else 5");
    p.add("max_azimuth_rate", max_azimuth_rate, "largest azimuth rate of the initiation gate, rad/s, > 0");
    p.add("slant_psd_scale", slant_psd_scale, "slant process PSDs as a multiple of the ground ones, > 0");
    p.add("fusion_pg", fusion_pg, "gate probability of the track-fusion (merge) test, in (0, 1)");
    p.add("duplicate_distance", duplicate_distance, "squared Mahalanobis distance of duplicate slant tracks, >= 0");
    p.add("ground_iterations", ground_iterations, "Gauss-Newton iterations of slant-to-ground conversion, 1..200");
    p.add("confirm_members", confirm_members, "slant tracks a fused track needs to be confirmed, 1..8");
  }
  std::string validate() const;  // "" if valid, else which field breaks which rule
};

namespace mptf {

using Vector4 = Eigen::Vector4d;
using Matrix4 = Eigen::Matrix4d;

struct Estimate {
  Vector4 mean;
  Matrix4 covariance;
};

// The model a PDA update needs.
struct PdaModel {
  Eigen::Matrix3d noise;   // R
  double pd = 1.0;         // P_D
  double pg = 0.971;       // P_G
  double gate = 0.0;       // γ, χ²₃ quantile at P_G
  double clutter_density = 0.0;  // λ per unit measurement volume
};

// Gated measurements of one update (reused storage).
struct PdaScratch {
  std::vector<int> columns;
  std::vector<Eigen::Vector3d> innovations;
  std::vector<double> weights;
};

// PDA update of the predicted slant estimate `track` with the scan (eqs of item 1); marks
// gated measurements in `gated` (size = scan columns); returns how many fell in the gate.
int pda_update(Estimate& track, const Eigen::MatrixXd& scan, const ScanIndex& index, const PdaModel& model,
               PdaScratch& scratch, std::vector<char>& gated);

// Second M/N stage and deletion (item 2), after the 2/2 stage of initiation.
class TrackLogic {
 public:
  TrackLogic(int confirm_hits, int confirm_scans, int miss_limit)
      : needed_(confirm_hits), window_(confirm_scans), miss_limit_(miss_limit) {}
  void record(bool hit);  // one scan: a measurement in the gate or not
  bool confirmed() const { return confirmed_; }
  bool deleted() const { return deleted_; }

 private:
  int needed_, window_, miss_limit_;
  int hits_ = 0, misses_ = 0;
  bool confirmed_ = false, deleted_ = false;
};

// S^τ(x) of item 3 and its Jacobian.
Vector4 slant_state(const MultipathMeasurementModel& sensor, int path, const Vector4& ground);
Matrix4 slant_state_jacobian(const MultipathMeasurementModel& sensor, int path, const Vector4& ground);

// Ground estimate of a slant estimate under path τ (item 3); false if Gauss–Newton does not
// reach a relative step of 1e-10 within `iterations`.
[[nodiscard]] bool ground_from_slant(const MultipathMeasurementModel& sensor, int path, const Estimate& slant, int iterations,
                       Estimate& ground);

// Information-weighted fusion of ground estimates (item 4); returns χ²(G).
double fuse(const Estimate* const* members, int count, Estimate& fused);

}  // namespace mptf

class MultipathTrackFusion final : public Tracker {
 public:
  using Options = MptfOptions;
  static constexpr std::string_view kName = "mptf";
  static constexpr std::string_view kSummary =
      "MPTF (JDT-VB Sec. IV, ref. [11]): per-path slant PDA tracks, M/N 2/2 & 1/3, fused to ground tracks by mode hypotheses";
  // Groups merge only if their ground estimates are this close (km in g, rad in ϑ): wider than
  // any path-labelling error of the OTHR geometry (≤ ~70 km, ~0.02 rad).
  static constexpr double kMergeWindowRange = 150.0;
  static constexpr double kMergeWindowBearing = 0.05;

  explicit MultipathTrackFusion(const Options& options) : options_(options) {}
  void run(const TrackingProblem& problem, TrackSet& tracks, SolveReport& report) override;

 private:
  Options options_;
};

}  // namespace dabench
