#pragma once
// Linear multitarget integrated PDA (LMIPDA) association probabilities:
//   D. Mušicki and B. La Scala, "Multi-target tracking in clutter without measurement
//   assignment", IEEE Trans. Aerosp. Electron. Syst. 44(3):877–896, July 2008,
// the "LMIPDA" baseline of Williams & Lau 2014 (bp-marginal-association, ref. [15], Sec. V-A,
// Fig. 6), run there with every track's existence probability set to 1.
//
// One track at a time: the other tracks' possible detections are folded into a per-measurement
// "modulated clutter density" Ω, and the track gets the single-target (I)PDA update with Ω in
// place of the clutter density ρ. With existence 1 and eq (11)'s ψ, ρ cancels (ψ-only form, what
// is implemented; P_D detection, P_G gating probability):
//   P^η_i          = P_D P_G ψ_ηi / Σ_j ψ_ηj                    a-priori P(y_i is a detection of η)
//   Ω^τ_i / ρ_i    = 1 + (1 − P_D)/(P_D P_G) · Σ_{η≠τ} ψ_ηi P^η_i / (1 − P^η_i)
//   β^τ_i / β^τ_0  = ψ_τi · (1 − P_D)/(1 − P_D P_G) / (Ω^τ_i / ρ_i)
// and the row β^τ is normalised. P ≤ P_D P_G < 1, so 1 − P > 0. A track alone on its
// measurements gets plain PDA, p_0 = 1/(1 + Σψ), p_j = ψ_j/(1 + Σψ). With pg = 1 this is the
// brief's ψ form. We found no copy of the paper, so its published form (from recollection) and
// its equation numbers could not be checked.
//
// Options: `pg` = P_G, 1 by default (the model of eqs (9)–(11) has no gating probability);
// pg = 1 − gate_miss gives the literal filter. `pd` = P_D when set, else problem.context.pd (the
// scenario's Pd in a run, `dabench solve --pd P` for a bare file). Pd cannot change the result
// when no measurement is gated by two or more targets and pg = 1 (every track is then plain PDA),
// so such problems are solved without it; otherwise, without a Pd in (0, 1) the solve is refused
// with skipped:needs_pd.
//
// ψ is the normalised weight w_ij / (w_i0 w_0j) (SingleScanProblem::normalized_weight); w_i0 and
// w_0j enter only through it.
//
// Cost O(n + m + edges) per solve: sums over "other tracks" are leave-one-out sums per
// measurement from prefix and suffix sums (no subtraction, so no cancellation), and row sums
// use weights scaled by 1/max(1, max_j ψ_ij), so any finite ψ is safe.
// Background and our readings: docs/algorithms/single-scan.md, "LMIPDA".
#include <cmath>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "algorithms/single_scan/association_graph.hpp"
#include "harness/core/params.hpp"
#include "harness/single_scan/solver.hpp"

namespace dabench {

struct LmipdaOptions {
  double pd = std::numeric_limits<double>::quiet_NaN();  // P_D; unset (NaN) = problem.context.pd
  double pg = 1.0;  // P_G, gating probability of the published filter; 1 = model of eqs (9)-(11)

  void bind(ParamList& params) {
    params.add("pd", pd, "detection probability in (0,1); unset = the problem's (scenario's) Pd");
    params.add("pg", pg, "gating probability P_G in (0,1] (1 = BP paper's model, eq 11)");
  }
  std::string validate() const;
};

class Lmipda final : public SingleScanSolver {
 public:
  using Options = LmipdaOptions;
  static constexpr std::string_view kName = "lmipda";
  static constexpr std::string_view kSummary =
      "LMIPDA (Musicki & La Scala 2008), existence 1: PDA per track with other tracks as modulated clutter; needs Pd";

  explicit Lmipda(const Options& options) : options_(options) {}
  void solve(const SingleScanProblem& problem, MarginalTable& marginals, SolveReport& report) override;

 private:
  Options options_;
  AssociationGraph graph_;
  std::vector<double> clutter_share_;  // per edge: ψ_ηi P^η_i / (1 − P^η_i)
  std::vector<double> others_;         // per edge (τ, i): Σ_{η≠τ} of clutter_share_ at i
};

}  // namespace dabench
