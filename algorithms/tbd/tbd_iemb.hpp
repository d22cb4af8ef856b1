#pragma once
// TBD-IEMB: the information-exchange multi-Bernoulli filter of Davies & García-Fernández,
// "Information Exchange Track-Before-Detect Multi-Bernoulli Filter for Superpositional Sensors",
// IEEE TSP 72:607–621, 2024 (doi 10.1109/TSP.2024.3349769), the TBD-BP letter's baseline
// (tbd-bp-supplement, Fig. 3; ../shared/tbd-bp-model.md §4.2). The paper's body was not read;
// the update follows the authors' MATLAB code ([C]: github.com/ESDavies/IPLF-IEMB-filter,
// TBDkFil.m, sigma_approximation.m, dist_kullback.m), applied to this kind's model
// (harness/tbd/problem.hpp). Tags: [C] as the code does, [R] our reading (no source states it).
//
// Model. A Gaussian multi-Bernoulli density: Bernoulli i has existence r_i and, if it exists,
// x_i ~ N(m_i, P_i), x = [p_x, p_y, v_x, v_y].
//
// One step k:
//  1. Prediction [C]: m ← F m, P ← F P Fᵀ + Q (the problem's NCV model, Q = σ_a² W Wᵀ),
//     r ← p_s r, with p_s = 0 once the PREDICTED mean is outside the region ([C] tests the
//     predicted mean; TBD-BP's particle_object tests the previous posterior mean). At k = 0 the
//     problem's initial objects are the predicted Bernoullis (as TBD-BP); a covariance that is
//     not positive definite (a known velocity, δ(v)) has its eigenvalues raised to
//     kCovarianceJitter, so that its Cholesky factor, P⁻¹ in the SLR and the KL divergence
//     exist [R] (likewise the new Bernoullis' covariance if σ_v = 0).
//  2. New Bernoullis [R] (tbd-bp-model.md §4.2 "For the letter"; [C] uses a few fixed birth
//     means, r = 1e-4): one per data cell, as TBD-BP has one new PO per cell, so the two
//     trackers see the same birth model. Mean: the cell centre, zero velocity; covariance
//     diag(Δ²/12, Δ²/12, σ_v², σ_v²) (the moments of a position uniform over the cell; σ_v =
//     filter.birth_speed_sd); r = (μ_B/J)/(1 + μ_B/J).
//  3. Predicted measurement moments of every Bernoulli u (legacy and new) over its window W_u,
//     from its 2n + 1 = 9 sigma points (centre weight W₀ = 1/3, the others (1 − W₀)/(2n),
//     m ± the columns of the Cholesky factor of n/(1 − W₀)·P) [C]:
//       ȳ_u,j = E[h_j(x_u)],  Y_u,j = E[h_j h_jᵀ + Cov(h_j | x_u)],
//     and per data cell the totals  M_j = Σ_u r_u ȳ_u,j,  V_j = Σ_u (r_u Y_u,j − r_u² ȳ_u,j ȳ_u,jᵀ)
//     (the new Bernoullis' part is the same every step and formed once, in start()).
//  4. Information exchange [C]: Bernoulli i sees the others as extra mean and covariance,
//       z_corr,i = Σ_{u≠i} r_u ȳ_u,   S_corr,i = Σ_{u≠i} (r_u Y_u − r_u² ȳ_u ȳ_uᵀ),
//     formed per cell as the totals minus i's own term, so a step costs O(Σ_u |W_u|) — linear
//     in the number of Bernoullis. [R]: S_corr is kept per cell (block diagonal): the
//     cross-cell covariances of the OTHER Bernoullis' contributions are dropped (the code's
//     S_corr is the full matrix; its cell sums would cost |W|² per pair), as TBD-BP's eq (9)
//     keeps per-cell terms only. Bernoulli i's OWN contribution keeps its full cross-cell
//     covariance over W_i (the IPLF below).
//  5. IPLF update [C] of every legacy Bernoulli, in parallel (each against the others'
//     PREDICTED terms, as [C]), against the measurement over its window: at most
//     `iterations` (20) statistical linear regressions (SLR) about the current iterate (u, W),
//     each giving A = Ψᵀ W⁻¹, b = ȳ − A u, Ω = Φ − A W Aᵀ + E[Cov(z | x)] (the state-dependent
//     conditional covariance enters Ω [R], the SLR of conditional moments), then
//     S = A P Aᵀ + Ω + S_corr, ẑ = A m + b + z_corr, and the Kalman update of the PRIOR (m, P);
//     stop once KL(N(u, W) ‖ N(u', W')) < `kl_threshold` (0.1) [C], else keep the last iterate
//     [C]. (Where two objects are close the IPLF can oscillate between them with period 2 and
//     reach the cap: in one default `tbd` run, at 4 of 50 steps.)
//     Existence [C]: r' = r L₁ / ((1 − r) L₀ + r L₁), L₁ = N(z; ẑ, S) of the last iteration,
//     L₀ = N(z; z_corr, R + S_corr) — for the power measurement see `power_likelihood` below.
//     Legacy Bernoullis with r < pruning_threshold (0.01 [C]) are deleted.
//  6. New Bernoullis [R], against the legacy Bernoullis' POSTERIOR terms (the field of step 3
//     with the legacy part re-formed from the updated Bernoullis) and each other's predicted
//     terms: screening — one pass (a UKF update) each, to keep the J of them cheap; those
//     reaching r ≥ pruning_threshold are candidates. Then serially, in decreasing log L₁/L₀ of
//     the screening pass (r saturates at 1), each candidate takes the full IPLF against the
//     field, which by then holds the candidates kept before it (their posterior terms in place
//     of their predicted ones); it is kept if r ≥ pruning_threshold and its mean is not within
//     `merge_distance` (1 m) of a kept one's. Why not the parallel schedule of [C] (where a few
//     birth means far apart make it harmless): an object lights the new Bernoullis of the
//     3 × 3 or more cells around it, and each, seeing the others' tiny predicted existence,
//     takes the whole object (r ≈ 1, its mean barely moved by one pass, so the merge distance
//     does not catch them); at the next step each sees the others' claims and all give the
//     object up — measured on 20 runs of a new object (D2), every other step had no estimate
//     and the others several. The serial schedule is TBD-BP's for its new POs
//     (algorithms/tbd/tbd_bp.hpp), so both trackers meet the same birth problem the same way.
//  7. Estimates: every Bernoulli with r ≥ detection_threshold (0.5 [C]), at its mean.
//
// The measurement (`measurement` option) [R] — tbd-bp-model.md §1.3:
//  - complex (the default of D2 and D3, the readings with a mean): z_j ∈ R² itself, two rows per cell. h_j(x) = μ_j(x), and
//    Cov(z_j | x) = (σ² + c_j(x)) I₂ + S_corr,j; absent: N(z_j; z_corr,j, σ² I₂ + S_corr,j).
//  - power (reading D1's default): under D1, μ_j ≡ 0, so E[z_j | x] = 0 carries no position
//    information — the SLR gives A = 0 and the mean would never move. The cell powers
//    y_j = ‖z_j‖²/2 do: given the objects, z_j ~ N(0, s_j I₂) with s_j = σ² + Σ_n r_n c_j(x_n),
//    so y_j is exponential with mean s_j and variance s_j². One row per cell, Gaussian with the
//    same two moments: h_j(x) = c_j(x); the others' exchange terms are z_corr,j = Σ r_u E[c_j],
//    S_corr,j = Σ (r_u E[c_j²] − r_u² E[c_j]²); and averaging s_j² over the others,
//       E[y_j | x] = σ² + c_j(x) + z_corr,j,   Var[y_j | x] = (σ² + c_j(x) + z_corr,j)² + 2 S_corr,j
//    (law of total variance: E[s²] + Var s = (E s)² + 2 Var s) — power_moments(). Absent:
//    c_j = 0. The cells stay conditionally independent given the objects (the others'
//    cross-cell terms are dropped as above). Power needs D1 (μ_j = 0: under D2 the objects'
//    means would interfere in ‖z_j‖²); a D2 or D3 problem with measurement=power is skipped.
//    Under D1, measurement=complex is allowed: its means never move (A = 0), only r updates.
//  - power_likelihood [R] (power only): `gaussian` takes L₁, L₀ from the IPLF's Gaussians as
//    [C] does; `gamma` (default) keeps the IPLF's state update and moments but takes each
//    cell's density as the Gamma with the same mean μ and variance v (shape μ²/v, scale v/μ;
//    the exact exponential when S_corr = 0), L₀ = Π_j Gamma(y_j; absent moments) and, by the
//    Laplace identity at the IPLF posterior (m', P'), L₁ = p(y | m') N(m'; m, P) / N(m'; m', P').
//    Why: the Gaussian's tails are far too light for exponential data — a cell at 3 to 5 times
//    its mean costs the absent hypothesis (y − μ)²/(2μ²) = 2 to 8 nats instead of the
//    exponential's 2 to 4 — so residual fluctuation energy near a track reads as a new object:
//    measured, a new Bernoulli beside a lagging track with log L₁/L₀ = 18.9 under the
//    Gaussians against −0.1 under the exponential densities at the same state. Gaussian: 83
//    estimates in 40 noise-only runs of 10 steps (32 × 32, μ_B = 0.01), gamma: 0; on the
//    default `tbd` run (20 trials, GOSPA p = 1, c = 2 m, α = 2) mean GOSPA 1.61 against 1.40.
//
// Window [R]: the cells whose centre lies within support_sigmas·σ_h + position_sigmas·√P_aa of
// the predicted mean along each axis a (4σ_h + 3 s.d.: beyond 4σ_h, g_j < e^{−8}), at most
// max_window cells per side (centred on the mean's cell). Outside it a Bernoulli's h_j = 0.
//
// Cost: with block-diagonal R + S_corr + E[C_j], S = (diagonal blocks) + U Uᵀ with U = [the
// SLR residuals at the 9 sigma points, A·chol(P)], rank 13, so S⁻¹ and det S come from the
// Woodbury identity: O(13² |W|) per iteration and Bernoulli, no |W|³ solve. A step costs
// O(Σ_legacy iterations·|W| + J·|W_new|): linear in the number of Bernoullis.
// Deterministic: sigma points, no random numbers.
//
// Reported per step: iterations = the most IPLF iterations a legacy Bernoulli took; converged
// = false if one stopped at the cap with KL ≥ kl_threshold.
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "algorithms/tbd/iemb_cells.hpp"
#include "algorithms/tbd/iplf.hpp"
#include "harness/core/params.hpp"
#include "harness/tbd/tracker.hpp"

namespace dabench {

// ---- the tracker ------------------------------------------------------------------------------

struct TbdIembOptions {
  int measurement = 0;               // auto | complex | power (see the header; auto: D1 power, D2 complex)
  int power_likelihood = 1;          // existence update under power: gaussian [C] | gamma [R] (see the header)
  int iterations = 20;               // IPLF iterations at most per legacy Bernoulli [C]
  double kl_threshold = 0.1;         // stop the IPLF once the KL divergence of successive iterates is below [C]
  double support_sigmas = 4.0;       // window margin in σ_h [R]
  double position_sigmas = 3.0;      // plus this many position standard deviations [R]
  int max_window = 15;               // cells per window side at most [R]
  double detection_threshold = 0.5;  // report r ≥ this [C]
  double pruning_threshold = 0.01;   // delete r below; keep a new Bernoulli at or above [C]
  double merge_distance = 1.0;       // m: drop a new Bernoulli this close to one kept before it [R]

  void bind(ParamList& p) {
    p.add_choice("measurement", measurement, {"auto", "complex", "power"},
                 "what the update uses: z_j, or the cell power |z_j|^2/2 (needs D1); auto: power for D1, complex for D2");
    p.add_choice("power_likelihood", power_likelihood, {"gaussian", "gamma"},
                 "power: L1, L0 of the existence update from the IPLF's Gaussians, or from Gamma densities");
    p.add("iterations", iterations, "IPLF iterations at most per legacy Bernoulli, in 1..100");
    p.add("kl_threshold", kl_threshold, "IPLF stops once KL(successive posteriors) is below, > 0");
    p.add("support_sigmas", support_sigmas, "window margin in sigma_h around the mean, in [1, 10]");
    p.add("position_sigmas", position_sigmas, "window: plus this many position s.d., in [0, 10]");
    p.add("max_window", max_window, "window cells per side at most, in 3..64");
    p.add("detection_threshold", detection_threshold, "report Bernoullis with existence at or above, in (0, 1)");
    p.add("pruning_threshold", pruning_threshold, "delete Bernoullis with existence below, in [0, detection_threshold)");
    p.add("merge_distance", merge_distance, "m: drop a new Bernoulli within this distance of one kept before it, in [0, 1000]");
  }
  std::string validate() const;  // "" if valid
};

struct GaussianBernoulli {
  Eigen::Vector4d mean = Eigen::Vector4d::Zero();
  Eigen::Matrix4d covariance = Eigen::Matrix4d::Identity();
  double existence = 0.0;
  int label = -1;
};

class TbdIemb final : public TbdTracker {
 public:
  using Options = TbdIembOptions;
  static constexpr std::string_view kName = "tbd-iemb";
  static constexpr std::string_view kSummary =
      "TBD-IEMB (Davies & Garcia-Fernandez 2024): Gaussian multi-Bernoulli, IPLF with information exchange";
  static constexpr double kCovarianceJitter = 1e-9;  // least eigenvalue of a prior covariance [R]

  explicit TbdIemb(const Options& options) : options_(options) {}
  void start(const TbdProblem& problem) override;
  void step(int k, std::vector<TbdEstimate>& estimates, SolveReport& report) override;
  // The sigma points of every Bernoulli, weighted (W₀ = 1/3, 1/12): its mean and covariance.
  void beliefs(std::vector<TbdBeliefSample>& samples) const override;

  // The Bernoullis after the last step.
  const std::vector<GaussianBernoulli>& bernoullis() const { return legacy_; }
  // The measurement the run uses (auto resolved); valid after start().
  IembMeasurementKind measurement_kind() const { return model_.kind(); }

 private:
  // One Bernoulli's window and predicted moments in a step.
  struct Work {
    IembWindow window;
    CellMoments own;
  };
  // False if b's covariance has no Cholesky factor (no sigma points).
  [[nodiscard]] bool predicted_moments(const GaussianBernoulli& b, Work& work);
  void covariance_failure(SolveReport& report, int k);
  IplfResult update(const GaussianBernoulli& b, const Work& work, int max_iterations);
  [[nodiscard]] bool births();  // appends the kept new Bernoullis to legacy_; false as predicted_moments

  Options options_;
  const TbdProblem* problem_ = nullptr;
  bool skip_ = false;
  std::string skip_reason_;
  IembCellModel model_;
  double margin_ = 0.0;  // support_sigmas · σ_h
  int frame_ = 0;        // the step being processed
  int next_label_ = 0;
  std::vector<GaussianBernoulli> legacy_;
  std::vector<Work> legacy_work_;
  GaussianBernoulli birth_prior_;  // the mean's position is set per cell
  IembField birth_field_;          // the new Bernoullis' terms: the same every step
  IembField field_;
  std::vector<double> powers_;     // y_j = ‖z_j‖²/2 of the frame (power)
  Work scratch_work_;
  SigmaPoints sigma_;
  SigmaMatrix h_, variance_;
  std::vector<Eigen::Vector2d> zc_;
  std::vector<Eigen::Matrix2d> sc_;
  IembCellMeasurement measurement_;
  IplfUpdate iplf_;
  struct Candidate {
    int cell = 0;            // of the new Bernoulli
    double log_ratio = 0.0;  // log L₁/L₀ of its screening pass
  };
  std::vector<Candidate> candidates_;
  std::vector<int> cell_head_, cell_next_;  // kept new Bernoullis' means, listed per cell
};

}  // namespace dabench
