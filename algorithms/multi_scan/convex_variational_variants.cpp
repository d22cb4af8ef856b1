#include "algorithms/multi_scan/convex_variational_variants.hpp"

#include <cmath>

#include "harness/multi_scan/registry.hpp"

namespace dabench {

namespace {

std::string check_pdca(double tolerance, double belief_tolerance, int max_sweeps, double beta_tilde) {
  if (!(tolerance > 0.0)) return "tolerance must be > 0";
  if (!(belief_tolerance >= 0.0)) return "belief_tolerance must be >= 0";
  if (max_sweeps < 1) return "max_sweeps must be >= 1";
  // Theorem 1 needs β̃ > 0.5 and Algorithm 1 needs β̃ >= γ̃, and γ̃ < 1 can come close to 1.
  if (!(beta_tilde >= 1.0) || !std::isfinite(beta_tilde)) return "beta_tilde must be >= 1 and finite";
  return {};
}

}  // namespace

std::string ConvexSolverOptions::validate() const {
  if (!(residual_tolerance > 0.0)) return "residual_tolerance must be > 0";
  if (max_iterations < 1) return "max_iterations must be >= 1";
  if (newton_limit < 0) return "newton_limit must be >= 0";
  return check_pdca(tolerance, belief_tolerance, max_sweeps, beta_tilde);
}

std::string PdcaOptions::validate() const { return check_pdca(tolerance, belief_tolerance, max_sweeps, beta_tilde); }

std::string SequentialConvexVariationalOptions::validate() const {
  if (!(gamma >= 0.0 && gamma < 1.0)) return "gamma must be in [0, 1) (Lemma 4 needs the sum of gammas < 1)";
  return ConvexSolverOptions::validate();
}

std::string HeuristicSequentialOptions::validate() const {
  if (!(gamma >= 0.0 && gamma <= 1.0)) return "gamma must be in [0, 1]";
  if (gamma == 1.0 && (solver == kNewton || solver == kLbfgs)) {
    return "gamma = 1 needs solver=pdca (the column-dual solvers need the sum of gammas < 1)";
  }
  return ConvexSolverOptions::validate();
}

std::string SingleSweepOptions::validate() const {
  if (!(gamma >= 0.0 && gamma <= 1.0)) return "gamma must be in [0, 1]";
  return check_pdca(1.0, 0.0, 1, beta_tilde);
}

namespace {

// Appends scans, sets (γ, β) and solves, with either engine: both take the same calls.
template <class Engine, class Settings>
void run_schedule(const ConvexVariationalSchedule& schedule, Engine& engine, const Settings& settings,
                  const MultiScanProblem& problem, MultiScanBeliefs& beliefs, SolveReport& report) {
  const int scans = problem.scan_count();
  engine.start(problem);
  // Per-scan γ for the scans present, then β_t' = β̃·K1_t'; reweight applies eq (91) to the
  // scans already solved (sequential steps only).
  auto set_coefficients = [&](std::vector<double> gamma) {
    std::vector<double> beta(gamma.size());
    for (int t = 0; t < static_cast<int>(gamma.size()); ++t) {
      beta[t] = schedule.beta_tilde * ConvexVariationalPdca::block_scale(schedule.settings.weights, gamma, t);
    }
    engine.reweight(gamma, beta);
  };
  if (schedule.sequential) {
    for (int k = 0; k < scans; ++k) {
      engine.append_scan(problem.scans[k]);
      std::vector<double> gamma(k + 1, 0.0);
      gamma[k] = schedule.gamma;
      set_coefficients(gamma);
      if (!engine.feasible()) break;
      engine.solve(settings, report);
      if (!report.skipped.empty()) return;
    }
  } else {
    for (const ScanFactors& scan : problem.scans) engine.append_scan(scan);
    set_coefficients(std::vector<double>(scans, schedule.bethe ? 1.0 : 1.0 / (scans + 1.0)));
    if (engine.feasible()) engine.solve(settings, report);
    if (!report.skipped.empty()) return;
  }
  if (!engine.feasible()) {
    report.skipped = "zero_partition";
    return;
  }
  engine.write_beliefs(beliefs);
}

}  // namespace

void solve_convex_variational(const ConvexVariationalSchedule& schedule, ConvexVariationalEngines& engines,
                              const MultiScanProblem& problem, MultiScanBeliefs& beliefs, SolveReport& report) {
  report.reset();
  if (schedule.column_dual && ColumnDualSolver::applicable(problem)) {
    run_schedule(schedule, engines.dual, schedule.dual, problem, beliefs, report);
  } else {
    run_schedule(schedule, engines.pdca, schedule.settings, problem, beliefs, report);
  }
}

namespace {

PdcaSettings pdca_settings(KappaWeights weights, double tolerance, double belief_tolerance, int max_sweeps) {
  PdcaSettings settings;
  settings.weights = weights;
  settings.tolerance = tolerance;
  settings.belief_tolerance = belief_tolerance;
  settings.max_sweeps = max_sweeps;
  return settings;
}

// The schedule of a convex method (cv, cvs, cvh, cvsh); `gamma` is the newest scan's γ of a
// sequential one (auto falls back to Algorithm 2 at γ = 1, where (63) is not strictly convex).
ConvexVariationalSchedule convex(KappaWeights weights, bool sequential, double gamma, const ConvexSolverOptions& options) {
  ConvexVariationalSchedule schedule;
  schedule.sequential = sequential;
  schedule.gamma = gamma;
  schedule.beta_tilde = options.beta_tilde;
  schedule.settings = pdca_settings(weights, options.tolerance, options.belief_tolerance, options.max_sweeps);
  schedule.column_dual = options.solver != ConvexSolverOptions::kPdca && !(sequential && gamma >= 1.0);
  schedule.dual.method = options.solver == ConvexSolverOptions::kNewton  ? DualMethod::kNewton
                         : options.solver == ConvexSolverOptions::kLbfgs ? DualMethod::kLbfgs
                                                                         : DualMethod::kAuto;
  schedule.dual.tolerance = options.residual_tolerance;
  schedule.dual.max_iterations = options.max_iterations;
  schedule.dual.newton_limit = options.newton_limit;
  return schedule;
}

}  // namespace

ConvexVariationalSchedule CvMethod::schedule(const Options& options) {
  return convex(KappaWeights::kLemma4, false, 0.0, options);
}
ConvexVariationalSchedule CvsMethod::schedule(const Options& options) {
  return convex(KappaWeights::kLemma4, true, options.gamma, options);
}
ConvexVariationalSchedule CvhMethod::schedule(const Options& options) {
  return convex(KappaWeights::kHeuristic, false, 0.0, options);
}
ConvexVariationalSchedule CvshMethod::schedule(const Options& options) {
  return convex(KappaWeights::kHeuristic, true, options.gamma, options);
}
ConvexVariationalSchedule Cvsh1Method::schedule(const Options& options) {
  ConvexVariationalSchedule schedule;
  schedule.sequential = true;
  schedule.gamma = options.gamma;
  schedule.beta_tilde = options.beta_tilde;
  schedule.settings = pdca_settings(KappaWeights::kHeuristic, 1e-9, 0.0, 1);
  return schedule;
}
ConvexVariationalSchedule MsbpMethod::schedule(const Options& options) {
  ConvexVariationalSchedule schedule;
  schedule.bethe = true;
  schedule.beta_tilde = options.beta_tilde;
  schedule.settings =
      pdca_settings(KappaWeights::kHeuristic, options.tolerance, options.belief_tolerance, options.max_sweeps);
  return schedule;
}

DABENCH_REGISTER_MULTI_SCAN_ALGORITHM(ConvexVariational);
DABENCH_REGISTER_MULTI_SCAN_ALGORITHM(ConvexVariationalSequential);
DABENCH_REGISTER_MULTI_SCAN_ALGORITHM(ConvexVariationalHeuristic);
DABENCH_REGISTER_MULTI_SCAN_ALGORITHM(ConvexVariationalSequentialHeuristic);
DABENCH_REGISTER_MULTI_SCAN_ALGORITHM(ConvexVariationalSingleSweep);
DABENCH_REGISTER_MULTI_SCAN_ALGORITHM(MultipleScanBp);

}  // namespace dabench
