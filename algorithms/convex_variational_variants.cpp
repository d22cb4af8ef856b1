#include "algorithms/convex_variational_variants.hpp"

#include <cmath>

#include "harness/registry.hpp"

namespace dabench {

namespace {

std::string check_common(double tolerance, double belief_tolerance, int max_sweeps, double beta_tilde) {
  if (!(tolerance > 0.0)) return "tolerance must be > 0";
  if (!(belief_tolerance >= 0.0)) return "belief_tolerance must be >= 0";
  if (max_sweeps < 1) return "max_sweeps must be >= 1";
  // Theorem 1 needs β̃ > 0.5 and Algorithm 1 needs β̃ >= γ̃, and γ̃ < 1 can come close to 1.
  if (!(beta_tilde >= 1.0) || !std::isfinite(beta_tilde)) return "beta_tilde must be >= 1 and finite";
  return {};
}

}  // namespace

std::string ConvexVariationalOptions::validate() const { return check_common(tolerance, belief_tolerance, max_sweeps, beta_tilde); }

std::string SequentialConvexVariationalOptions::validate() const {
  if (!(gamma >= 0.0 && gamma < 1.0)) return "gamma must be in [0, 1) (Lemma 4 needs the sum of gammas < 1)";
  return check_common(tolerance, belief_tolerance, max_sweeps, beta_tilde);
}

std::string HeuristicSequentialOptions::validate() const {
  if (!(gamma >= 0.0 && gamma <= 1.0)) return "gamma must be in [0, 1]";
  return check_common(tolerance, belief_tolerance, max_sweeps, beta_tilde);
}

std::string SingleSweepOptions::validate() const {
  if (!(gamma >= 0.0 && gamma <= 1.0)) return "gamma must be in [0, 1]";
  return check_common(1.0, 0.0, 1, beta_tilde);
}

void solve_convex_variational(const ConvexVariationalSchedule& schedule, ConvexVariationalPdca& pdca,
                              const MultiScanProblem& problem, MultiScanBeliefs& beliefs, SolveReport& report) {
  report.reset();
  const int scans = problem.scan_count();
  pdca.start(problem);
  // Per-scan γ for the scans present, then β_t' = β̃·K1_t'; reweight applies eq (91) to the
  // scans already solved (sequential steps only).
  auto set_coefficients = [&](std::vector<double> gamma) {
    std::vector<double> beta(gamma.size());
    for (int t = 0; t < static_cast<int>(gamma.size()); ++t) {
      beta[t] = schedule.beta_tilde * ConvexVariationalPdca::block_scale(schedule.settings.weights, gamma, t);
    }
    pdca.reweight(gamma, beta);
  };
  if (schedule.sequential) {
    for (int k = 0; k < scans; ++k) {
      pdca.append_scan(problem.scans[k]);
      std::vector<double> gamma(k + 1, 0.0);
      gamma[k] = schedule.gamma;
      set_coefficients(gamma);
      if (!pdca.feasible()) break;
      pdca.solve(schedule.settings, report);
      if (!report.skipped.empty()) return;
    }
  } else {
    for (const ScanFactors& scan : problem.scans) pdca.append_scan(scan);
    set_coefficients(std::vector<double>(scans, schedule.bethe ? 1.0 : 1.0 / (scans + 1.0)));
    if (pdca.feasible()) pdca.solve(schedule.settings, report);
    if (!report.skipped.empty()) return;
  }
  if (!pdca.feasible()) {
    report.skipped = "zero_partition";
    return;
  }
  pdca.write_beliefs(beliefs);
}

namespace {

ConvexVariationalSchedule batch(KappaWeights weights, bool bethe, const ConvexVariationalOptions& options) {
  ConvexVariationalSchedule schedule;
  schedule.settings.weights = weights;
  schedule.bethe = bethe;
  schedule.beta_tilde = options.beta_tilde;
  schedule.settings.tolerance = options.tolerance;
  schedule.settings.belief_tolerance = options.belief_tolerance;
  schedule.settings.max_sweeps = options.max_sweeps;
  return schedule;
}

ConvexVariationalSchedule sequential(KappaWeights weights, const SequentialConvexVariationalOptions& options) {
  ConvexVariationalSchedule schedule;
  schedule.settings.weights = weights;
  schedule.sequential = true;
  schedule.gamma = options.gamma;
  schedule.beta_tilde = options.beta_tilde;
  schedule.settings.tolerance = options.tolerance;
  schedule.settings.belief_tolerance = options.belief_tolerance;
  schedule.settings.max_sweeps = options.max_sweeps;
  return schedule;
}

}  // namespace

ConvexVariationalSchedule CvMethod::schedule(const Options& options) {
  return batch(KappaWeights::kLemma4, false, options);
}
ConvexVariationalSchedule CvsMethod::schedule(const Options& options) {
  return sequential(KappaWeights::kLemma4, options);
}
ConvexVariationalSchedule CvhMethod::schedule(const Options& options) {
  return batch(KappaWeights::kHeuristic, false, options);
}
ConvexVariationalSchedule CvshMethod::schedule(const Options& options) {
  return sequential(KappaWeights::kHeuristic, options);
}
ConvexVariationalSchedule Cvsh1Method::schedule(const Options& options) {
  SequentialConvexVariationalOptions one_sweep;
  one_sweep.gamma = options.gamma;
  one_sweep.beta_tilde = options.beta_tilde;
  one_sweep.max_sweeps = 1;
  return sequential(KappaWeights::kHeuristic, one_sweep);
}
ConvexVariationalSchedule MsbpMethod::schedule(const Options& options) {
  return batch(KappaWeights::kHeuristic, true, options);
}

DABENCH_REGISTER_MULTI_SCAN(ConvexVariational);
DABENCH_REGISTER_MULTI_SCAN(ConvexVariationalSequential);
DABENCH_REGISTER_MULTI_SCAN(ConvexVariationalHeuristic);
DABENCH_REGISTER_MULTI_SCAN(ConvexVariationalSequentialHeuristic);
DABENCH_REGISTER_MULTI_SCAN(ConvexVariationalSingleSweep);
DABENCH_REGISTER_MULTI_SCAN(MultipleScanBp);

}  // namespace dabench
