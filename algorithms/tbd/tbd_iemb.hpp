#pragma once
// TBD-IEMB: the information-exchange multi-Bernoulli filter of Davies & García-Fernández,
// "Information Exchange Track-Before-Detect Multi-Bernoulli Filter for Superpositional Sensors",
// IEEE TSP 72:607–621, 2024, the TBD-BP letter's baseline (tbd-bp-supplement, Fig. 3). The update
// follows the authors' MATLAB code ([C]: github.com/ESDavies/IPLF-IEMB-filter, TBDkFil.m),
// applied to this kind's model (harness/tbd/problem.hpp); [R] marks our readings.
//
// Bernoulli i: existence r_i and x_i ~ N(m_i, P_i), x = [p_x, p_y, v_x, v_y]. One step k:
//  1. Prediction [C]: m ← F m, P ← F P Fᵀ + Q (the problem's NCV), r ← p_s r, p_s = 0 once the
//     predicted mean is outside the region. At k = 0 the problem's initial objects; a covariance
//     that is not positive definite has its eigenvalues raised to kCovarianceJitter [R].
//  2. New Bernoullis [R]: one per data cell, mean at its centre with zero velocity, covariance
//     diag(Δ²/12, Δ²/12, σ_v², σ_v²), r = (μ_B/J)/(1 + μ_B/J), as TBD-BP's new POs.
//  3. Measurement moments of every Bernoulli u over its window W_u from 9 sigma points (W₀ = 1/3)
//     [C]: ȳ_u,j = E[h_j(x_u)], Y_u,j = E[h_j h_jᵀ + Cov(h_j | x_u)], and per cell the totals
//     M_j = Σ_u r_u ȳ_u,j, V_j = Σ_u (r_u Y_u,j − r_u² ȳ_u,j ȳ_u,jᵀ) (the new part formed once).
//  4. Information exchange [C]: z_corr,i = M_j − r_i ȳ_i,j, S_corr,i = V_j − (own term), per cell
//     [R] (block diagonal: the others' cross-cell covariances dropped, as eq (9) does).
//  5. IPLF (iplf.hpp) of every legacy Bernoulli against the others' predicted terms [C]: at most
//     `iterations` SLRs about the current iterate, A = Ψᵀ W⁻¹, b = ȳ − A u, Ω = Φ − A W Aᵀ +
//     E[Cov(z | x)], S = A P Aᵀ + Ω + S_corr, ẑ = A m + b + z_corr, Kalman update of the prior,
//     until KL(successive iterates) < `kl_threshold`. Existence r' = r L₁ / ((1 − r) L₀ + r L₁),
//     L₁ = N(z; ẑ, S), L₀ = N(z; z_corr, σ² I + S_corr). Delete r < `pruning_threshold`.
//  6. New Bernoullis [R], against the legacy Bernoullis' posterior terms: screened by one UKF
//     pass each; candidates with r ≥ pruning_threshold then take the full IPLF serially, in
//     decreasing screening log L₁/L₀, each seeing the candidates kept before it, and are kept if
//     still r ≥ pruning_threshold and not within `merge_distance` of a kept one (a parallel
//     schedule makes every cell around an object claim it, then all give it up).
//  7. Estimates: every Bernoulli with r ≥ `detection_threshold`, at its mean.
// The measurement (`measurement`, iemb_cells.hpp) [R]: `complex` filters z_j ∈ R² (h_j = μ_j);
// `power` filters y_j = ‖z_j‖²/2, since under D1 E[z_j | x] = 0 carries no position (A = 0):
// h_j = c_j, z_corr,j = Σ r_u E[c_j], S_corr,j = Σ (r_u E[c_j²] − r_u² E[c_j]²), and
// power_moments() gives E[y_j | x] = s, Var[y_j | x] = s² + 2 S_corr,j with s = σ² + c_j(x) +
// z_corr,j (the exponential's moments averaged over the others). `auto`: power for a zero-mean
// reading, else complex; power on a reading with a mean is skipped. `power_likelihood = gamma` takes L₁, L₀
// from Gamma densities with the Gaussian's moments (L₁ by the Laplace identity at the IPLF
// posterior); `gaussian` takes them from the IPLF's Gaussians as [C] does.
// Window [R]: cells within support_sigmas·σ_h + position_sigmas·√P_aa of the mean per axis, at
// most max_window per side. Invariants: with the Woodbury identity a step costs O(Σ_legacy
// iterations·|W| + J·|W_new|), linear in the Bernoullis; no random numbers. Reported per step:
// iterations (the most a legacy Bernoulli took); converged = false if one hit the cap.
// Background and our readings: docs/models/track-before-detect.md (§4.2 TBD-IEMB, §6).
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
