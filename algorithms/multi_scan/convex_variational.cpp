#include "algorithms/multi_scan/convex_variational.hpp"
#include "harness/core/special_values.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>

namespace dabench {

namespace {

constexpr double kWeightFloor = -600.0;  // log of the smallest relative weight given to Algorithm 1
constexpr double kShiftLimit = 100.0;    // largest |log| of a row maximum or clutter weight given to it
const double kLogProbabilityFloor = std::log(DBL_MIN);

// log Σ_r exp x(r, c) per column into `out` (−∞ for a column that is all −∞). `work` holds the
// exponentials: one vectorised exp over the whole matrix, no allocation once sized.
void column_log_sum_exp(const RowMatrix& x, RowMatrix& work, Eigen::RowVectorXd& shift, Eigen::Ref<Eigen::RowVectorXd> out) {
  shift = x.colwise().maxCoeff();
  shift = (shift.array() == kMinusInfinity).select(0.0, shift);
  work.noalias() = x.rowwise() - shift;
  work.array() = work.array().exp();  // a plain matrix: Eigen's packet exp (a broadcast would go scalar)
  out = shift.array() + work.colwise().sum().array().log();
}

// log Σ_c exp x(r, c) per row into `out` (−∞ for a row that is all −∞).
void row_log_sum_exp(const RowMatrix& x, RowMatrix& work, Vector& shift, Vector& out) {
  shift = x.rowwise().maxCoeff();
  shift = (shift.array() == kMinusInfinity).select(0.0, shift);
  work.noalias() = x.colwise() - shift;
  work.array() = work.array().exp();
  out = shift.array() + work.rowwise().sum().array().log();
}

// log of a normalised distribution from unnormalised log weights.
Vector log_normalize(const Vector& x) {
  const double top = x.maxCoeff();
  return x.array() - (top + std::log((x.array() - top).exp().sum()));
}

// The same, in place.
void normalize_log(Vector& x) {
  const double top = x.maxCoeff();
  x.array() -= top + std::log((x.array() - top).exp().sum());
}

// λ = φ − κ log q where φ is finite; 0 where the entry is a structural zero (φ = −∞). Returns
// the largest change from the previous λ.
template <class Lambda, class Phi, class LogQ>
double update_dual(Lambda& lambda, const Phi& phi, const LogQ& log_q, double kappa) {
  double change = 0.0;
  for (Eigen::Index r = 0; r < lambda.rows(); ++r) {
    for (Eigen::Index c = 0; c < lambda.cols(); ++c) {
      const double value = phi(r, c) == kMinusInfinity ? 0.0 : phi(r, c) - kappa * log_q(r, c);
      change = std::max(change, std::abs(value - lambda(r, c)));
      lambda(r, c) = value;
    }
  }
  return change;
}

}  // namespace

ConvexVariationalPdca::Kappas ConvexVariationalPdca::kappas(KappaWeights weights, const std::vector<double>& gamma,
                                                            int scan) {
  if (weights == KappaWeights::kHeuristic) return {1.0, 1.0, -1.0, 0.0, 0.0, 0.0};  // (93)–(95)
  double eta = 1.0;  // η = 1 − Σγ (64)
  for (double g : gamma) eta -= g;
  const double c = eta / (static_cast<double>(gamma.size()) + 1.0);
  const double g = gamma[scan];
  return {c, c, -c, g + c, -(1.0 - g - 2.0 * c), 1.0 - g - 2.0 * c};  // (69)–(73)
}

double ConvexVariationalPdca::block_scale(KappaWeights weights, const std::vector<double>& gamma, int scan) {
  const Kappas k = kappas(weights, gamma, scan);
  return k.f_t + k.one_t;
}

void ConvexVariationalPdca::start(const MultiScanProblem& problem) {
  const int n = problem.tracks();
  log_prior_.resize(n);
  lambda_sum_.resize(n);
  log_belief_.resize(n);
  for (int i = 0; i < n; ++i) {
    log_prior_[i] = problem.prior[i].array().log();
    lambda_sum_[i] = Vector::Zero(problem.hypotheses(i));
    log_belief_[i] = log_normalize(log_prior_[i]);
  }
  scans_.clear();
}

void ConvexVariationalPdca::append_scan(const ScanFactors& factors) {
  const int n = static_cast<int>(log_prior_.size());
  Scan scan;
  scan.measurements = factors.measurements;
  scan.log_factor.resize(n);
  scan.lambda1_a.resize(n);
  scan.lambda2_a.resize(n);
  scan.lambda1_t.resize(n);
  scan.lambda2_t.resize(n);
  scan.association = RowMatrix::Zero(n, factors.measurements + 1);
  scan.clutter = Vector::Zero(factors.measurements);
  scan.row_shift = Vector::Zero(n);
  scan.column_shift = Vector::Zero(factors.measurements);
  for (int i = 0; i < n; ++i) {
    const RowMatrix& factor = factors.factor[i];
    scan.log_factor[i] = factor.array().log();
    // A hypothesis no association of this scan can follow has probability 0: remove it.
    for (Eigen::Index h = 0; h < factor.rows(); ++h) {
      if (!(factor.row(h).maxCoeff() > 0.0)) log_prior_[i][h] = kMinusInfinity;
    }
    scan.lambda1_a[i] = scan.lambda2_a[i] = Vector::Zero(factor.rows());
    scan.lambda1_t[i] = scan.lambda2_t[i] = RowMatrix::Zero(factor.rows(), factor.cols());
  }
  scans_.push_back(std::move(scan));
}

bool ConvexVariationalPdca::feasible() const {
  for (const Vector& log_prior : log_prior_) {
    if (log_prior.maxCoeff() == kMinusInfinity) return false;
  }
  return true;
}

void ConvexVariationalPdca::reweight(const std::vector<double>& gamma, const std::vector<double>& beta) {
  for (int t = 0; t < scans(); ++t) {
    Scan& scan = scans_[t];
    const double delta_gamma = gamma[t] - scan.gamma;
    const double delta_beta = beta[t] - scan.beta;
    scan.gamma = gamma[t];
    scan.beta = beta[t];
    if (!scan.solved || (delta_gamma == 0.0 && delta_beta == 0.0)) continue;
    // Theorem 3, eq (91): a shift per (i, j > 0), the same for every hypothesis A.
    for (int i = 0; i < static_cast<int>(scan.log_factor.size()); ++i) {
      for (int j = 1; j <= scan.measurements; ++j) {
        const double log_complement = std::max(std::log1p(-scan.association(i, j)), kLogProbabilityFloor);
        const double log_clutter = std::log(scan.clutter[j - 1]);
        const double shift = delta_gamma * (1.0 + log_complement) - delta_beta * (1.0 + log_clutter);
        scan.log_factor[i].col(j).array() += shift;  // −∞ stays −∞
      }
    }
  }
}

double ConvexVariationalPdca::block_one(int t, const Kappas& k, const PdcaSettings& settings, double kernel_tolerance) {
  Scan& scan = scans_[t];
  const int n = static_cast<int>(log_prior_.size());
  const int m = scan.measurements;
  const double k1 = k.f_t + k.one_t;
  // φ̃(a) of (78) per track, from X = (φ(A) + φ_t'(A, a)) / K1.
  scaled_.resize(n);
  log_column_.resize(n, m + 1);
  for (int i = 0; i < n; ++i) {
    phi_a_ = log_prior_[i] - (lambda_sum_[i] - scan.lambda1_a[i]);  // (76)
    scaled_[i] = ((scan.log_factor[i] - scan.lambda2_t[i]).colwise() + phi_a_) / k1;  // (77), /K1
    column_log_sum_exp(scaled_[i], exp_work_, column_shift_, log_column_.row(i));
  }
  // The single-scan problem (79): w^{i,j} = exp φ̃(j), w^{0,j} = 1, rescaled by the duals of
  // this scan's previous kernel solution (row i by e^{r_i}, column j by e^{s_j} with w^{0,j} by
  // e^{s_j/β̃}), which leaves (79) unchanged and starts Algorithm 1 near its fixed point.
  const double beta_tilde = scan.beta / k1;
  kernel_weight_.resize(n, m);
  kernel_miss_.resize(n);
  kernel_clutter_.resize(m);
  for (int j = 0; j < m; ++j) {
    scan.column_shift[j] = std::clamp(scan.column_shift[j], -kShiftLimit * beta_tilde, kShiftLimit * beta_tilde);
    kernel_clutter_[j] = std::exp(scan.column_shift[j] / beta_tilde);
  }
  for (int i = 0; i < n; ++i) {
    Eigen::RowVectorXd log_w = log_column_.row(i);
    log_w[0] += scan.row_shift[i];
    log_w.tail(m) += (scan.column_shift.array() + scan.row_shift[i]).matrix().transpose();
    const double top = log_w.maxCoeff();
    if (std::abs(top) > kShiftLimit) {
      scan.row_shift[i] -= top;
      log_w.array() -= top;
    }
    const double floor = std::min(log_w.maxCoeff(), 0.0) + kWeightFloor;
    log_w[0] = std::max(log_w[0], floor);
    for (int a = 0; a <= m; ++a) {
      const double w = log_w[a] == kMinusInfinity ? 0.0 : std::exp(std::max(log_w[a], floor));
      if (a == 0) kernel_miss_[i] = w;
      else kernel_weight_(i, a - 1) = w;
    }
  }
  FractionalBpOptions options;
  options.gamma = scan.gamma / k1;
  options.alpha = 1.0;
  options.beta = beta_tilde;
  options.tolerance = kernel_tolerance;
  options.max_iterations = settings.kernel_max_iterations;
  const FractionalBpOutcome outcome = kernel_.solve(kernel_weight_, kernel_miss_, kernel_clutter_, options);
  if (!outcome.converged) kernel_failed_ = true;
  if (!kernel_.target_marginals().allFinite() || !kernel_.clutter_marginals().allFinite()) {
    numerical_failure_ = true;
    return 0.0;
  }
  scan.association = kernel_.target_marginals();
  scan.clutter = kernel_.clutter_marginals().cwiseMax(DBL_MIN);
  // The duals of this solution (eqs 154-155 with α = 1): λ̄_i = log(q^{i,0}/w^{i,0}),
  // μ̄_j = β̃ log(q^{0,j}/w^{0,j}); they become the next call's scaling.
  for (int i = 0; i < n; ++i) {
    scan.row_shift[i] += std::max(std::log(scan.association(i, 0)), kLogProbabilityFloor) - std::log(kernel_miss_[i]);
  }
  for (int j = 0; j < m; ++j) scan.column_shift[j] += beta_tilde * (std::log(scan.clutter[j]) - std::log(kernel_clutter_[j]));

  double change = 0.0;
  for (int i = 0; i < n; ++i) {
    // log q_t'(A, a) = log q(a) + X(A, a) − φ̃(a) (75), q(a) floored where w > 0.
    Eigen::RowVectorXd offset(m + 1);
    for (int a = 0; a <= m; ++a) {
      const double log_w = log_column_(i, a);
      offset[a] = log_w == kMinusInfinity ? 0.0 : std::max(std::log(scan.association(i, a)), kLogProbabilityFloor) - log_w;
    }
    RowMatrix& log_q = scaled_[i];
    log_q.rowwise() += offset;
    row_log_sum_exp(log_q, exp_work_, row_shift_, log_q_a_);  // (82)
    phi_a_ = log_prior_[i] - (lambda_sum_[i] - scan.lambda1_a[i]);
    lambda_sum_[i] -= scan.lambda1_a[i];
    change = std::max(change, update_dual(scan.lambda1_a[i], phi_a_, log_q_a_, k.f_a));  // (80)
    lambda_sum_[i] += scan.lambda1_a[i];
    change = std::max(change, update_dual(scan.lambda1_t[i], scan.log_factor[i] - scan.lambda2_t[i], log_q, k.f_t));  // (81)
  }
  return change;
}

double ConvexVariationalPdca::block_two(int t, const Kappas& k) {
  Scan& scan = scans_[t];
  const int n = static_cast<int>(log_prior_.size());
  const double k2 = k.f_t + k.two_t;
  const double k_total = k.f_a + k.f_t + k.two_a + k.two_t;
  double change = 0.0;
  for (int i = 0; i < n; ++i) {
    phi_a_ = log_prior_[i] - (lambda_sum_[i] - scan.lambda2_a[i]);  // (86)
    phi_t_ = scan.log_factor[i] - scan.lambda1_t[i];                // (87)
    log_q_ = phi_t_ / k2;
    row_log_sum_exp(log_q_, exp_work_, row_shift_, phi_tilde_);      // (88): φ̃/K2
    log_belief_[i] = (phi_a_ + k2 * phi_tilde_) / k_total;            // (84)
    normalize_log(log_belief_[i]);
    log_q_.colwise() += log_belief_[i] - phi_tilde_;                  // (85)
    lambda_sum_[i] -= scan.lambda2_a[i];
    change = std::max(change, update_dual(scan.lambda2_a[i], phi_a_, log_belief_[i], k.f_a));  // (89)
    lambda_sum_[i] += scan.lambda2_a[i];
    change = std::max(change, update_dual(scan.lambda2_t[i], phi_t_, log_q_, k.f_t));  // (90)
  }
  return change;
}

void ConvexVariationalPdca::solve(const PdcaSettings& settings, SolveReport& report) {
  const int count = scans();
  weights_ = settings.weights;
  numerical_failure_ = false;
  std::vector<double> gamma(count);
  for (int t = 0; t < count; ++t) gamma[t] = scans_[t].gamma;
  for (Scan& scan : scans_) {
    for (std::size_t i = 0; i < scan.lambda1_a.size(); ++i) {
      scan.lambda1_a[i].setZero();
      scan.lambda2_a[i].setZero();
      scan.lambda1_t[i].setZero();
      scan.lambda2_t[i].setZero();
    }
  }
  for (std::size_t i = 0; i < log_prior_.size(); ++i) {
    lambda_sum_[i].setZero();
    log_belief_[i] = log_normalize(log_prior_[i]);
  }
  // A backward–forward sweep: newest → oldest → newest.
  std::vector<int> order;
  for (int t = count - 1; t >= 0; --t) order.push_back(t);
  for (int t = 1; t < count; ++t) order.push_back(t);
  bool converged = count == 0;
  int sweeps = 0;
  double previous_belief_change = std::numeric_limits<double>::infinity();
  double previous_change = std::numeric_limits<double>::infinity();
  double previous_rate = 1.0;
  while (!converged && sweeps < settings.max_sweeps) {
    snapshot_beliefs();
    // Inexact blocks while the duals still move a lot: Algorithm 1 runs to 1e-3 of the last
    // sweep's largest λ change (at most 1e-3), never tighter than kernel_tolerance, so the
    // last sweeps use the full accuracy.
    const double kernel_tolerance = std::max(settings.kernel_tolerance, std::min(1e-3, 1e-3 * previous_change));
    double change = 0.0;
    kernel_failed_ = false;
    for (int t : order) {
      const Kappas k = kappas(settings.weights, gamma, t);
      change = std::max(change, block_one(t, k, settings, kernel_tolerance));
      if (numerical_failure_) {
        report.skipped = "numerical";
        return;
      }
      change = std::max(change, block_two(t, k));
    }
    ++sweeps;
    // Belief rule: the ascent converges linearly, so with ρ the observed rate (the larger of the
    // last two ratios of successive belief changes, which guards against a lucky sweep while
    // the blocks are still inexact), the beliefs are within change·ρ/(1 − ρ) of their limit.
    const double belief_change = belief_change_since_snapshot();
    const double latest_rate = belief_change / previous_belief_change;
    const double rate = std::max(latest_rate, previous_rate);
    previous_belief_change = belief_change;
    previous_rate = latest_rate;
    const bool beliefs_settled =
        settings.belief_tolerance > 0.0 && sweeps > 3 &&
        (belief_change == 0.0 || (rate < 1.0 && belief_change * rate / (1.0 - rate) < settings.belief_tolerance));
    converged = change < settings.tolerance || beliefs_settled;
    previous_change = change;
  }
  for (Scan& scan : scans_) scan.solved = true;
  report.iterations += sweeps;
  if (!converged || kernel_failed_) report.converged = false;
}

void ConvexVariationalPdca::snapshot_beliefs() {
  last_belief_.resize(log_belief_.size());
  for (std::size_t i = 0; i < log_belief_.size(); ++i) last_belief_[i] = log_belief_[i].array().exp();
  last_association_.resize(scans_.size());
  for (std::size_t t = 0; t < scans_.size(); ++t) last_association_[t] = scans_[t].association;
}

double ConvexVariationalPdca::belief_change_since_snapshot() const {
  double change = 0.0;
  for (std::size_t i = 0; i < log_belief_.size(); ++i) {
    change = std::max(change, (log_belief_[i].array().exp() - last_belief_[i].array()).abs().maxCoeff());
  }
  for (std::size_t t = 0; t < scans_.size(); ++t) {
    change = std::max(change, (scans_[t].association - last_association_[t]).cwiseAbs().maxCoeff());
  }
  return change;
}

void ConvexVariationalPdca::write_beliefs(MultiScanBeliefs& beliefs) const {
  const int n = static_cast<int>(log_prior_.size());
  beliefs.track.resize(n);
  for (int i = 0; i < n; ++i) beliefs.track[i] = log_belief_[i].array().exp();
  beliefs.association.resize(scans());
  for (int t = 0; t < scans(); ++t) {
    const Scan& scan = scans_[t];
    beliefs.association[t].reshape(n, scan.measurements);
    beliefs.association[t].view() = scan.association;
  }
}

void ConvexVariationalPdca::recover_primal(Primal& primal) const {
  const int n = static_cast<int>(log_prior_.size());
  std::vector<double> gamma(scans());
  for (int t = 0; t < scans(); ++t) gamma[t] = scans_[t].gamma;
  const Kappas k = kappas(weights_, gamma, 0);  // κ_{f,A}, κ_{f,t'} are the same for every scan
  primal.track.resize(n);
  for (int i = 0; i < n; ++i) primal.track[i] = log_normalize((log_prior_[i] - lambda_sum_[i]) / k.f_a).array().exp();
  primal.pair.assign(scans(), std::vector<RowMatrix>(n));
  for (int t = 0; t < scans(); ++t) {
    for (int i = 0; i < n; ++i) {
      const Scan& scan = scans_[t];
      RowMatrix log_q = (scan.log_factor[i] - scan.lambda1_t[i] - scan.lambda2_t[i]) / k.f_t;
      for (Eigen::Index h = 0; h < log_q.rows(); ++h) {
        if (log_prior_[i][h] == kMinusInfinity) log_q.row(h).setConstant(kMinusInfinity);
      }
      const double top = log_q.maxCoeff();
      RowMatrix q = (log_q.array() - top).exp();
      primal.pair[t][i] = q / q.sum();
    }
  }
}

}  // namespace dabench
