#pragma once
// JDT-VB: variational-Bayes joint detection and tracking with multipath data association
// (jdt-vb-multipath-othr, Sec. III, Table I). Tracker `jdt-vb`.
//
// Mean field q(X, S, A) = q(X) q(S) q(A) (eqs 7, 22–23) maximising the free energy B of eq (6)
// by coordinate ascent over three modules, run 3 → 2 → 1 in each iteration (Table I):
//  - Module 3 (association): per scan, E[a^{i,j,τ}] by loopy BP on eq (44)
//    (algorithms/tracking/multipath_association.hpp) with the evidence χ of eq (43) over the
//    gated pairs of eq (33) (gate probability p_g) and V_k of eqs (34)–(35).
//  - Module 2 (detection): per track, q(s_{1:K}) by forward–backward on eqs (38)–(40)
//    (algorithms/tracking/meta_state_chain.hpp), p(s_k = s_{k−1}) = `stay`. An active target's
//    detection probability in eqs (39) and (43) is p^τ_d p_g (eq 15 has no p_g).
//  - Module 1 (tracking): per track, eq (36)'s synthetic measurements per path and an unscented
//    RTS smoother (algorithms/tracking/ukf.hpp) from the track's head as p(x_first). Default
//    `joint_fusion = 1`: one filter takes all paths' synthetic measurements of a scan (eq 31's
//    maximiser up to the unscented approximation); `joint_fusion = 0`: per-path smoothers
//    fused by eq (32).
// The run (Sec. III-E):
//  1. Sequential pass: each live track is predicted and gated per path (eq 33); Module 3 with
//     the predictive likelihood N(y | h^τ(x̂⁻), S); a stacked UKF update and a forward step of
//     the meta-state chain. Measurements outside every gate start heads
//     (algorithms/tracking/track_heads.hpp; thresholds ρ = head_range, head_range_rate,
//     head_azimuth; p(s = 1) = min(1, (|Y|/N_P)²); `alternative_heads`: also every equally good
//     path reading). Deletion: q(s_k = 1) < δ_s at each of three successive scans after the
//     first (default), or their mean < δ_s (`delete_on_mean = 1`).
//  2. Batch VB over the tracks that reached q(s = 1) ≥ δ_s, over their spans: Modules 3 → 2 → 1
//     until B changes by < δ_T or after r_max iterations. Gates only grow across iterations.
//  3. Output: per batch track the scans from the first to the last with smoothed
//     q(s_k = 1) ≥ δ_s, confirmed (from its head scan with `report_from = head`); a track
//     without such a scan whole, unconfirmed.
// `literal = 1` forces joint_fusion = 0 and alternative_heads = 0; the other keys keep theirs.
//
// Invariant: B (SolveReport::free_energy, free_energy_history()) never decreases. Modules 3
// and 2 maximise it exactly; a Module-1 update that would lower it is rejected (q(X) kept,
// counted in rejected_updates()). B is eq (6) under eq (43)'s linearisation, H(q(A)) in Bethe
// form, clutter density λ = N_c / V, up to a constant of the measurements alone:
//   B = Σ_k [Σ_j E[a^{0,j}] log λ + Σ_{ijτ} E[a^{i,j,τ}] E log N(y_j | h^τ(x_i), R) + H_Bethe(q(A_k))]
//     + Σ_i [E log p(s_i) + Σ_k E ξ_{i,k}(s_{i,k}) + H(q(s_i))] + Σ_i [E log p(x_i) + H(q(x_i))],
// q(x_i) a Gauss–Markov chain (RTS couplings; for eq 32 algorithms/tracking/gauss_markov_coupling.hpp).
// Edge cases: p_d p_g ≤ 1 − 10⁻⁹; no clutter is read as 10⁻⁶ clutter measurements per scan.
// Background and our readings: docs/algorithms/tracking.md, "JDT-VB".
#include <string>
#include <string_view>
#include <vector>

#include "algorithms/tracking/multipath_association.hpp"
#include "harness/core/params.hpp"
#include "harness/tracking/tracker.hpp"

namespace dabench {

struct JdtVbOptions {
  double convergence = 1e-5;       // δ_T: stop when B changes by less (Sec. IV-A2)
  int max_iterations = 20;         // r_max (Sec. IV-A2)
  double confirm = 0.85;           // δ_s: track confirmation and deletion threshold (Sec. IV-A2)
  double stay = 0.85;              // p(s_k = s_{k−1}) of the meta-state chain (Sec. IV-A2)
  double dormant_pd = 0.01;        // p^τ_d(s = 0), every path ("relatively small", Sec. II-B3; not given)
  bool delete_on_mean = false;     // deletion reading: mean of three scans' q(s=1) (1) or each of three (0), see above
  double gate_probability = 0.971; // p_g of eq (33) (Sec. IV-A2)
  double head_range = 80.0;        // ρ_τ: slant range, km (Sec. IV-A2)
  double head_range_rate = 0.005;  // ρ_τ: slant range rate, km/s
  double head_azimuth = 0.03;      // ρ_τ: azimuth, rad
  double head_bearing_rate_sd = 2e-4;  // s.d. of ϑ̇ (not measured by eq 57) in a new track, rad/s
  bool joint_fusion = true;        // Module 1: true = one smoother on all paths (eq 31); false = eq (32)
  bool alternative_heads = true;   // a head for every equally good path reading of a new group (not in the paper)
  static constexpr int kFromConfirmation = 0, kFromHead = 1;
  int report_from = kFromConfirmation;  // a confirmed track is output from its confirmation (first q(s=1) >= δ_s) or its head
  bool literal = false;            // the paper-literal set: joint_fusion = 0, alternative_heads = 0
  MultipathAssociationOptions association;  // Module 3 LBP: tolerance 1e-9, 1000 iterations

  void bind(ParamList& p);
  std::string validate() const;
  // These options with `literal` applied (what the tracker runs).
  JdtVbOptions resolved() const;
};

class JdtVbTracker final : public Tracker {
 public:
  using Options = JdtVbOptions;
  static constexpr std::string_view kName = "jdt-vb";
  static constexpr std::string_view kSummary =
      "JDT-VB (Sec. III): VB joint detection and tracking, multipath association by loopy BP";

  explicit JdtVbTracker(const Options& options);
  void run(const TrackingProblem& problem, TrackSet& tracks, SolveReport& report) override;

  // B after each VB iteration of the last run (non-decreasing), how many Module-1 updates were
  // rejected because they would have lowered B, and the most any of them would have lowered it
  // (0 when none was rejected). By default the rejected ones are updates of tracks whose
  // smoother has converged, each within rounding and the unscented approximation of the kept
  // q(x) (measured below 10⁻⁷, against δ_T = 10⁻⁵); eq (32)'s fusion is no maximiser of B, and
  // its rejected updates would lower B by up to a few units.
  const std::vector<double>& free_energy_history() const { return free_energy_history_; }
  int rejected_updates() const { return rejected_updates_; }
  double largest_rejected_decrease() const { return largest_rejected_decrease_; }

 private:
  Options options_;
  std::vector<double> free_energy_history_;
  int rejected_updates_ = 0;
  double largest_rejected_decrease_ = 0.0;
};

}  // namespace dabench
