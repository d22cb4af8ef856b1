#pragma once
// TBD-BP: track-before-detect by belief propagation (Liang, Kropfreiter & Meyer, "A BP method
// for track-before-detect", IEEE SPL 30, 2023; derivations in tbd-bp-supplement), on
// particles. The letter's body was not available: what it leaves open follows
// docs/models/track-before-detect.md, and every such reading [R] is an option below.
//
// One step k:
//  1. Legacy POs: α_n by prediction (algorithms/tbd/particle_object.hpp; r⁻ = p_s r̃). At
//     k = 0 the problem's initial objects, if any, are the legacy POs' α.
//  2. L iterations of the message passing of algorithms/tbd/cell_messages.hpp among the legacy
//     POs (the Gaussian κ̃ of the supplement's eqs (5), (9), or the exact κ with
//     `exact_kappa`). Schedule [R], `schedule`: serial (default: the POs in order of creation,
//     each against the others' newest messages) or flooding (every PO's β^(ℓ) from the
//     others' κ̃^(ℓ−1); it oscillates with period 2 where two POs can explain the same energy).
//  3. New POs: one per data cell j (the letter's "new object hypothesis for each data cell"),
//     α(x,1) ∝ (μ_B/J) f_B,j(x), α(x,0) ∝ 1, so r⁻ = (μ_B/J)/(1 + μ_B/J); f_B,j is uniform
//     over cell j's square with velocity ~ N(0, σ_v² I₂), evaluated as a `birth_grid`²
//     midpoint quadrature of the cell. Schedule [R]: each new PO is evaluated against the
//     legacy POs' messages β^(L+1) to the cells; those with r̃ ≥ pruning_threshold are then
//     taken serially in decreasing r̃, each re-evaluated against the legacy POs and the new POs
//     already kept (their beliefs added to the cells' totals), and kept if still above.
//     (Flooding over the new POs oscillates with period 2: duplicates at odd L, none at even L.)
//  4. Beliefs f̃(x^(i),1) ∝ w^(i) Π_j κ̃^(L)_{n,j}(x^(i),1), existence r̃ (log-odds form).
//     Legacy POs with r̃ < pruning_threshold are deleted, the others resampled to P particles
//     (systematic). A kept new PO becomes a legacy PO: P particles drawn from its α (uniform in
//     the cell, velocity prior) and weighted by Π_j κ̃ at their positions (the messages it was
//     evaluated with), then resampled.
//  5. Duplicates [R] (`merge_distance`, off by default): in decreasing r̃, a PO whose mean lies
//     within merge_distance of a PO already kept is deleted.
//  6. Estimates: every PO with r̃ > detection_threshold, at its particle mean.
// Schedule `joint` [R], closer to the letter: iteration ℓ is a serial sweep over the legacy POs,
// then the stage of step 3, whose kept new POs enter the field with their extrinsic messages
// β_{n,j} ∝ α_n Π_{j'≠j} κ̃_{n,j'} instead of their beliefs, and leave it before the stage at
// ℓ + 1; so from ℓ = 2 on the legacy POs see the new POs.
// Cost per step: O(L Σ_n P |W_n| + J Q² |W|) (`joint`: L J Q² |W|), linear in the number of POs
// (supplement §3).
// Randomness: RandomStream(algorithm_stream_seed(trial_key.seed, seed), point, trial).
// Background and our readings (schedules, duplicates, particle count):
// docs/models/track-before-detect.md §3.
#include <string>
#include <string_view>
#include <vector>

#include "algorithms/tbd/cell_messages.hpp"
#include "algorithms/tbd/particle_object.hpp"
#include "harness/core/params.hpp"
#include "harness/tbd/tracker.hpp"

namespace dabench {

struct TbdBpOptions {
  int iterations = 2;                // L, message-passing iterations per step (letter: 1 and 2)
  int particles = 2000;              // P, per legacy PO ([K] uses 10 000; why: docs/models/track-before-detect.md §3.1)
  int birth_grid = 4;                // Q: a new PO's cell is a Q × Q midpoint quadrature
  double support_sigmas = 4.0;       // window margin around a PO's particles, in σ_h
  double detection_threshold = 0.5;  // report r̃ above ([K], [C])
  double pruning_threshold = 1e-4;   // delete r̃ below ([K])
  bool exact_kappa = false;          // exact κ of eq (5) instead of κ̃ (at most two POs per cell)
  bool interaction = true;           // false: the Σ_{n'≠n} terms of eqs (5), (9) are dropped
  int schedule = 0;                  // 0 serial, 1 flooding (legacy POs), 2 joint (see the header)
  double merge_distance = 0.0;       // m; > 0: of POs whose means are closer, keep the likeliest (off)
  std::int64_t seed = 0;             // stream selector

  void bind(ParamList& p) {
    p.add("iterations", iterations, "message-passing iterations L per step, in 1..20");
    p.add("particles", particles, "particles per potential object, in 10..1e6");
    p.add("birth_grid", birth_grid, "new POs: Q x Q quadrature points in their cell, in 1..16");
    p.add("support_sigmas", support_sigmas, "window of a PO: cells within this many sigma_h of its particles, in [1, 10]");
    p.add("detection_threshold", detection_threshold, "report POs with existence above, in (0, 1)");
    p.add("pruning_threshold", pruning_threshold, "delete POs with existence below, in [0, detection_threshold)");
    p.add("exact_kappa", exact_kappa, "exact messages of eq (5) (small problems: at most two POs per cell)");
    p.add("interaction", interaction, "false drops the other POs' terms of eqs (5), (9)");
    p.add_choice("schedule", schedule, {"serial", "flooding", "joint"},
                 "serial/flooding: L iterations among legacy POs, then the new POs; joint: L iterations of both");
    p.add("merge_distance", merge_distance, "delete a PO whose mean is within this distance (m) of a PO with higher existence, in [0, 100]; 0: off");
    p.add("seed", seed, "stream selector: another value draws other particles on the same trial");
  }
  std::string validate() const;  // "" if valid
};

class TbdBp final : public TbdTracker {
 public:
  using Options = TbdBpOptions;
  static constexpr std::string_view kName = "tbd-bp";
  static constexpr std::string_view kSummary =
      "TBD-BP (Liang, Kropfreiter & Meyer 2023): particle BP with the Gaussian messages of eqs (5), (9)";

  static constexpr int kSerial = 0, kFlooding = 1, kJoint = 2;  // TbdBpOptions::schedule

  explicit TbdBp(const Options& options) : options_(options) {}
  void start(const TbdProblem& problem) override;
  void step(int k, std::vector<TbdEstimate>& estimates, SolveReport& report) override;

  void beliefs(std::vector<TbdBeliefSample>& samples) const override;

  // The legacy POs after the last step (beliefs, for plots and tests).
  const std::vector<ParticleObject>& objects() const { return legacy_; }

 private:
  void make_new_objects();
  int new_object_stage(bool joint);
  static void fail(SolveReport& report, int k, const std::string& what);
  double keep_log_odds() const;  // log-odds of pruning_threshold
  void merge_duplicates();
  double support_radius() const;  // window margin, m

  Options options_;
  const TbdProblem* problem_ = nullptr;
  RandomStream rng_{0, 0, 0};
  int next_label_ = 0;
  std::vector<ParticleObject> legacy_;
  std::vector<ParticleObject> births_;  // one per cell, the same every step
  std::vector<CellMessages::Work> birth_work_;
  std::vector<ParticleObject*> all_;
  std::vector<int> order_;
  std::vector<int> kept_births_;          // new POs kept this step, in the order they were kept
  std::vector<bool> keep_;                // per legacy PO of this step's run
  std::vector<Eigen::Vector2d> kept_means_;  // merge_distance: means of the POs kept so far
  ParticleObject scratch_;
  CellMessages messages_;
};

}  // namespace dabench
