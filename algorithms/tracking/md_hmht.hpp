#pragma once
// MD-HMHT: the multi-detection hypothesis-oriented MHT that the JDT-VB paper
// (jdt-vb-multipath-othr, Sec. IV-B; parameters in Sec. IV-A2) uses as a baseline. Its source,
// MD-MHT [16], was not available: the paper gives the structure and four numbers (n, the window,
// the 3 / 5 empty-gate deletion rule, p_g); the rest is our reading, each open choice an option.
//
// Model: ground state x = [g, ġ, ϑ, ϑ̇] with the problem's F and Q; per path τ a detection with
// probability p^τ_d, measured as h^τ(x) + w, w ~ N(0, R^τ); Poisson clutter of density λ = N_c / V.
// The tracker uses the problem's p^τ_d and λ. Filter: UKF (md_hmht_tracks.hpp).
//
// Per scan, for each parent hypothesis h:
//  - rows are h's (track, path) pseudo-targets, columns the measurements; a row takes at most one
//    gated measurement, a measurement goes to at most one row (eq (3) read "at most one",
//    multipath_association.hpp). Gate d² ≤ γ, the χ²_{n_y} quantile at p_g. A gated pair costs
//      c_pj = −ln ψ_pj,   ψ_pj = p^τ_d N(y_j; ŷ^τ, S^τ) / ((1 − p^τ_d p_g) λ),
//    any other pair +∞.
//  - assignment = joint: rows sharing measurements form clusters; Murty's n best per cluster
//    (algorithms/assignment/murty.hpp, n = `hypotheses`) are merged into h's n best events.
//    assignment = per_path: paths EE, EF, FE, FF in turn, each over the measurements the earlier
//    paths left, a beam of n partial events.
//  - the child of h under event a scores (an LLR against "all clutter", common terms dropped)
//      s(child) = s(h) + Σ_{rows p of h} ln(1 − p^τ_d p_g) − Σ_{(p,j)∈a} c_pj.
// Selection: the n best children overall (per_parent = 0) or of each parent (1); then N-scan
// pruning keeps the children whose ancestor `window` scans back is the best child's.
//
// Tracks: LLR ℓ = 0 at the head, plus Σ_τ ln(1 − p^τ_d p_g) + Σ_{assigned τ} ln ψ per scan;
// confirmed once ℓ ≥ confirm_llr; deleted after deletion_misses successive scans with no
// measurement in any path's gate (a tentative track is dropped, a confirmed one ended). Heads:
// form_track_heads (track_heads.hpp) on the measurements outside every gate of every hypothesis,
// so every child gets the same heads; the path readings of one return group are a family, of
// which one confirmed member stays (largest ℓ, then the oldest).
//
// Invariants: track nodes are immutable and shared by hypotheses; each distinct node is predicted
// and gated once per scan, each (node, assignment) updated once. Scores are relative to the
// scan's best hypothesis (0; the others ≤ 0). Output: the best hypothesis' confirmed tracks, live
// and ended, filtered estimates from the head's scan (report_from = head) or the confirmation
// scan; an ended track stops at its last assigned measurement. literal = 1 forces
// alternative_heads = 0, report_from = confirmation, assignment = per_path (resolved()).
//
// Background and our readings: docs/models/md-hmht.md
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "harness/core/params.hpp"
#include "harness/tracking/tracker.hpp"

namespace dabench {

struct MdHmhtOptions {
  enum ReportFrom : int { kFromHead = 0, kFromConfirmation = 1 };
  enum Assignment : int { kJoint = 0, kPerPath = 1 };

  int hypotheses = 0;              // n best hypotheses kept; 0 = the paper's 3 if N_c ≤ 200 else 2
  int window = 3;                  // W of N-scan pruning (paper: window length 3)
  int deletion_misses = 0;         // scans with an empty gate before deletion; 0 = 3 if N_c ≤ 200 else 5
  double gate_probability = 0.971; // p_g (paper: 0.971)
  bool per_parent = false;         // 0: n best children overall (reading A); 1: n best per parent (B)
  double confirm_llr = 6.9;        // track LLR that confirms it (SPRT bound ln((1 − β)/α), α = 1e-3, β = 0.01)
  bool alternative_heads = true;   // a head for every equally good path reading of a return group
  double head_range = 80.0;        // ρ: slant range, km (paper: as JDT-VB)
  double head_range_rate = 0.005;  // ρ: slant range rate, km/s
  double head_azimuth = 0.03;      // ρ: azimuth, rad
  double head_bearing_rate_sd = 2e-4;  // s.d. of ϑ̇ in a new track, rad/s (as jdt-vb)
  int report_from = kFromHead;     // a confirmed track is output from its head's scan or from its confirmation
  int assignment = kJoint;         // one assignment over all (track, path) rows, or path-dependent ones
  bool literal = false;            // the paper-literal set: alternative_heads = 0, report_from = confirmation, assignment = per_path

  void bind(ParamList& p);
  std::string validate() const;  // "" if valid, else which field breaks which rule
  // These options with `literal` applied (what the tracker runs).
  MdHmhtOptions resolved() const;
};

class MdHmhtTracker final : public Tracker {
 public:
  using Options = MdHmhtOptions;
  static constexpr std::string_view kName = "md-hmht";
  static constexpr std::string_view kSummary =
      "MD-HMHT (JDT-VB Sec. IV-B): hypothesis-oriented MHT over (target, path) pseudo-targets, Murty's n best, N-scan window";

  explicit MdHmhtTracker(const Options& options) : options_(options.resolved()) {}
  void run(const TrackingProblem& problem, TrackSet& tracks, SolveReport& report) override;

 private:
  Options options_;
};

// What the tests of the hypothesis machinery observe (tests/tracking/test_md_hmht_hypotheses.cpp).
namespace md_hmht {

struct TrackHistory {
  long track = 0;           // the track's id
  int first_scan = 0;       // its head's scan
  int confirmed_scan = -1;  // the scan its LLR reached confirm_llr, −1 while tentative
  double llr = 0.0;         // its log-likelihood ratio now
  int empty_gates = 0;      // successive scans, up to now, with no measurement in any of its gates
  // assigned[s][τ]: the measurement (column of scan first_scan + 1 + s) path τ took, −1 none.
  std::vector<std::vector<int>> assigned;
};

struct HypothesisSnapshot {
  double score = 0.0;               // log-likelihood ratio minus the best hypothesis' (≤ 0)
  std::vector<TrackHistory> live;   // by increasing track id
  std::vector<TrackHistory> ended;  // deleted confirmed tracks, in order of deletion
};

// Called after each scan k with the surviving hypotheses, best first.
using ScanObserver = std::function<void(int k, const std::vector<HypothesisSnapshot>& hypotheses)>;

// MdHmhtTracker::run (with options.resolved()) that also reports every scan's hypotheses.
void run_observed(const MdHmhtOptions& options, const TrackingProblem& problem, TrackSet& tracks,
                  const ScanObserver& observer);

}  // namespace md_hmht

}  // namespace dabench
