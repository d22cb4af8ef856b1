#pragma once
// TBD-MB: the Poisson/multi-Bernoulli track-before-detect baseline of Kropfreiter, Williams &
// Meyer, "A Scalable Track-Before-Detect Method With Poisson/Multi-Bernoulli Model", FUSION
// 2021 (arXiv 2109.01490), the letter's baseline that "does not systematically model object
// interaction". RECONSTRUCTION [R]: that paper's body was not available; this is our reading,
// built from its abstract (multi-Bernoulli approximation of the posterior, data association by
// the sum-product algorithm, recycling) and the separable TBD likelihood. Every choice is an
// option below.
//
// Model: an object at p contributes to the cells of its support S(p) (centres within
// `support_radius`, default 2σ_h) and to no other; supports of present objects are disjoint
// ("each cell explained by at most one object"), so p(z | X) ∝ Π_{x∈X} ℓ(z | x) (ℓ of
// support_likelihood.hpp) times that exclusivity constraint.
//
// One step k:
//  1. Prediction: legacy Bernoullis as in TBD-BP (particle_object.hpp: NCV, r⁻ = p_s r); the
//     Poisson intensity of undetected objects, a mass Λ_j per data cell (uniform within the
//     cell, velocity prior N(0, σ_v² I₂)): Λ_j ← p_s Λ_j + μ_B/J, not moved by the motion [R].
//  2. Likelihood: every particle of every legacy Bernoulli, and the Q × Q quadrature of every
//     cell's new Bernoulli (prior r = Λ_j/(1 + Λ_j), odds alone ξ_j = Λ_j ℓ̄_j), alone
//     against the frame on its support.
//  3. Exclusivity (cell_exclusion.hpp): the sum-product algorithm over the legacy Bernoullis
//     and the new ones that could survive alone (serial sweeps: legacy first, then new by
//     decreasing ξ) gives each its messages ν_{j→i} and belief.
//  4. Update: a Bernoulli's particles are weighted by ℓ Π_{j∈S(x)} ν_{j→i}, r̃ from its belief;
//     the cell's Poisson mass has become its new Bernoulli (Λ_j = 0).
//  5. Recycling: Bernoullis with r̃ < recycle_threshold leave the multi-Bernoulli; with
//     `recycling` their mass returns to the Poisson intensity (a legacy one's r̃ w_p to the
//     cell of each particle, a new one's r̃_j to cell j), else it is dropped. Kept new
//     Bernoullis get P particles drawn in their cell and weighted by ℓ Π ν (new_objects.hpp).
//  6. Estimates: every Bernoulli with r̃ > detection_threshold, at its particle mean.
// Reading `association` [R]: `objects` (default) is steps 3–4 as above; `none` skips the
// exclusivity — every Bernoulli, legacy and each cell's new one, is updated alone (weights w ℓ,
// r̃ = r T / (r T + 1 − r), T = Σ w ℓ; a new one r̃ = ξ_j / (1 + ξ_j)), so nothing stops two
// Bernoullis from explaining one object.
// Randomness: RandomStream(algorithm_stream_seed(trial_key.seed, seed), point, trial).
// Background and our readings: docs/models/track-before-detect.md §4.1.
#include <string>
#include <string_view>
#include <vector>

#include "algorithms/tbd/cell_exclusion.hpp"
#include "algorithms/tbd/particle_object.hpp"
#include "algorithms/tbd/support_likelihood.hpp"
#include "harness/core/params.hpp"
#include "harness/tbd/tracker.hpp"

namespace dabench {

struct TbdMbOptions {
  int particles = 2000;              // P per Bernoulli (as TBD-BP)
  int birth_grid = 4;                // Q: new Bernoullis' cell quadrature (as TBD-BP)
  double support_radius = 0.0;       // m; an object's support: cells with centres this near; 0: 2σ_h [R]
  int sweeps = 100;                  // cap on the exclusivity SPA's serial sweeps
  double detection_threshold = 0.5;  // report r̃ above
  double recycle_threshold = 0.1;    // Bernoullis below leave the multi-Bernoulli (Williams' hybrid PMB)
  bool recycling = true;             // their mass returns to the Poisson intensity (else dropped)
  int association = 0;               // 0 objects: exclusivity by the SPA (step 3); 1 none: each Bernoulli alone
  std::int64_t seed = 0;             // stream selector

  void bind(ParamList& p) {
    p.add("particles", particles, "particles per Bernoulli, in 10..1e6");
    p.add("birth_grid", birth_grid, "new Bernoullis: Q x Q quadrature points in their cell, in 1..16");
    p.add("support_radius", support_radius, "an object explains the cells whose centre is within this distance, m, in [0, 100]; 0: 2 sigma_h");
    p.add("sweeps", sweeps, "cap on the exclusivity sum-product sweeps, in 1..10000");
    p.add("detection_threshold", detection_threshold, "report Bernoullis with existence above, in (0, 1)");
    p.add("recycle_threshold", recycle_threshold, "Bernoullis with existence below leave the multi-Bernoulli, in (0, detection_threshold)");
    p.add("recycling", recycling, "their mass returns to the Poisson intensity of undetected objects (false: dropped)");
    p.add_choice("association", association, {"objects", "none"},
                 "objects: disjoint supports by the sum-product algorithm; none: every Bernoulli updated alone");
    p.add("seed", seed, "stream selector: another value draws other particles on the same trial");
  }
  std::string validate() const;  // "" if valid
};

class TbdMb final : public TbdTracker {
 public:
  using Options = TbdMbOptions;
  static constexpr std::string_view kName = "tbd-mb";
  static constexpr std::string_view kSummary =
      "TBD-MB (Kropfreiter, Williams & Meyer 2021), reconstructed: particle PMB, likelihood on disjoint object "
      "supports, exclusivity by SPA, recycling";

  static constexpr int kObjects = 0, kNone = 1;  // TbdMbOptions::association

  explicit TbdMb(const Options& options) : options_(options) {}
  void start(const TbdProblem& problem) override;
  void step(int k, std::vector<TbdEstimate>& estimates, SolveReport& report) override;
  void beliefs(std::vector<TbdBeliefSample>& samples) const override;

  const std::vector<ParticleObject>& objects() const { return legacy_; }
  const std::vector<double>& undetected_mass() const { return undetected_; }  // Λ_j per cell

 private:
  int cell_of(double px, double py) const;  // −1 outside the region
  void recycle(const ParticleObject& object);
  double update_alone(ParticleObject& object, const Eigen::Matrix2Xd& frame);  // returns r̃
  static void fail(SolveReport& report, int k, const std::string& what);
  // Node of the exclusivity SPA from a Bernoulli's particles and log weights log w_p + log ℓ.
  void add_node(const ParticleObject& object, const Eigen::Matrix2Xd& frame, double pad);

  Options options_;
  const TbdProblem* problem_ = nullptr;
  SupportLikelihood likelihood_;
  RandomStream rng_{0, 0, 0};
  int next_label_ = 0;
  std::vector<ParticleObject> legacy_;
  std::vector<double> undetected_;      // Λ_j
  std::vector<ParticleObject> births_;  // one per cell: the quadrature of step 2
  std::vector<double> log_new_odds_;    // log ξ_j
  std::vector<int> candidates_;         // cells whose new Bernoulli enters the exclusivity SPA
  std::vector<double> log_weight_;      // scratch: one node's log w_p ℓ
  ParticleObject scratch_;
  CellExclusion exclusion_;
};

}  // namespace dabench
