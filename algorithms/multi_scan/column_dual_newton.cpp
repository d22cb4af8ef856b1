#include "algorithms/multi_scan/column_dual_newton.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>

namespace dabench {

namespace {

constexpr double kArmijo = 1e-4;         // sufficient-increase fraction of the line search
constexpr double kSmallestStep = 1e-12;  // backtracking gives up below this step fraction
constexpr double kInnerForcing = 1e-2;   // inner tolerance during a step: this times the outer residual
// Largest move of any σ_tj in one step. Where every track's indicator of an association is all
// but certain (1 − μ ≈ 1e-30, say, for two tracks that both want measurement j), the tracks' part
// of D is linear in σ_tj for tens of units and the quadratic model's maximiser lies at 1e30: the
// step is scaled down to this trust radius (e^{10} in the tilts) and the next steps go on.
constexpr double kTrustRadius = 10.0;

// Scales `direction` so that no component exceeds kTrustRadius.
void limit_step(Vector& direction) {
  const double largest = direction.size() > 0 ? direction.cwiseAbs().maxCoeff() : 0.0;
  if (largest > kTrustRadius) direction *= kTrustRadius / largest;
}

// K ≻ 0 in exact arithmetic, but the entries of near-certain associations (variances far below
// 1e-16) carry rounding noise: a ridge of this fraction of the largest diagonal keeps the
// factorisation meaningful without touching the directions whose curvature is above it.
constexpr double kRidge = 1e-13;

// Solves (K + ridge) x = b by Cholesky, raising the ridge until the factorisation succeeds.
bool solve_positive(Eigen::MatrixXd& matrix, const Vector& right, Vector& solution) {
  const double scale = std::max(matrix.diagonal().maxCoeff(), 1e-300);
  double ridge = kRidge * scale;
  matrix.diagonal().array() += ridge;
  for (int attempt = 0; attempt < 12; ++attempt) {
    Eigen::LLT<Eigen::MatrixXd> factor(matrix);
    if (factor.info() == Eigen::Success) {
      solution = factor.solve(right);
      if (solution.allFinite()) return true;
    }
    matrix.diagonal().array() += 9.0 * ridge;
    ridge *= 10.0;
  }
  return false;
}

}  // namespace

bool ColumnDualSolver::applicable(const MultiScanProblem& problem) {
  for (int i = 0; i < problem.tracks(); ++i) {
    std::vector<char> alive(problem.hypotheses(i));
    for (int h = 0; h < problem.hypotheses(i); ++h) {
      alive[h] = problem.prior[i][h] > 0.0;
      for (const ScanFactors& scan : problem.scans) alive[h] = alive[h] && scan.factor[i].row(h).maxCoeff() > 0.0;
    }
    for (const ScanFactors& scan : problem.scans) {
      bool can_miss = false;
      for (int h = 0; h < problem.hypotheses(i) && !can_miss; ++h) can_miss = alive[h] && scan.factor[i](h, 0) > 0.0;
      if (!can_miss) return false;
    }
  }
  return true;
}

void ColumnDualSolver::start(const MultiScanProblem& problem) {
  if (static_cast<int>(track_pool_.size()) < problem.tracks()) track_pool_.resize(problem.tracks());
  tracks_ = std::span<TiltedTrack>(track_pool_.data(), static_cast<std::size_t>(problem.tracks()));
  for (int i = 0; i < problem.tracks(); ++i) tracks_[i].start(problem.prior[i]);
  scans_.clear();
  offsets_.clear();
  sigma_.resize(0);
  sigma_by_scan_.clear();
  evaluations_.assign(tracks_.size(), TrackEvaluation{});
  matrix_sigma_.resize(0);
}

void ColumnDualSolver::append_scan(const ScanFactors& factors) {
  Scan scan;
  scan.measurements = factors.measurements;
  scan.offset = static_cast<int>(sigma_.size());
  scans_.push_back(scan);
  offsets_.push_back(scan.offset);
  sigma_.conservativeResize(scan.offset + scan.measurements);
  sigma_.tail(scan.measurements).setZero();
  sigma_by_scan_.emplace_back(scan.measurements);
  for (std::size_t i = 0; i < tracks_.size(); ++i) tracks_[i].append_scan(factors.factor[i]);
  matrix_sigma_.resize(0);
}

bool ColumnDualSolver::feasible() const {
  return std::all_of(tracks_.begin(), tracks_.end(), [](const TiltedTrack& track) { return track.feasible(); });
}

Vector ColumnDualSolver::clutter(int t) const {
  const Scan& scan = scans_[t];
  return (-sigma_.segment(scan.offset, scan.measurements).array() / scan.beta - 1.0).exp();
}

void ColumnDualSolver::reweight(const std::vector<double>& gamma, const std::vector<double>& beta) {
  for (int t = 0; t < scans(); ++t) {
    Scan& scan = scans_[t];
    const double delta_gamma = gamma[t] - scan.gamma;
    const double delta_beta = beta[t] - scan.beta;
    if (scan.solved && (delta_gamma != 0.0 || delta_beta != 0.0)) {
      // Theorem 3: log ψ̄(A, j) += Δγ [1 + log(1 − q^{i,j})] − Δβ [1 + log q^{0,j}] (91), and
      // σ̄_j = σ_j − Δβ [1 + log q^{0,j}] (137), with 1 + log q⁰ = −σ/β (133), exact.
      auto sigma = sigma_.segment(scan.offset, scan.measurements);
      const Vector clutter_term = -sigma / scan.beta;
      for (TiltedTrack& track : tracks_) {
        track.add_offset(t, (delta_gamma * (1.0 + track.log_complement(t).array()) - delta_beta * clutter_term.array()).matrix());
      }
      sigma -= delta_beta * clutter_term;
    }
    scan.gamma = gamma[t];
    scan.beta = beta[t];
    for (TiltedTrack& track : tracks_) track.set_gamma(t, scan.gamma);
  }
  matrix_sigma_.resize(0);
}

void ColumnDualSolver::split(const Vector& sigma) {
  for (int t = 0; t < scans(); ++t) sigma_by_scan_[t] = sigma.segment(scans_[t].offset, scans_[t].measurements);
}

double ColumnDualSolver::clutter_value(const Vector& sigma) const {
  double value = 0.0;
  for (const Scan& scan : scans_) {
    for (int j = 0; j < scan.measurements; ++j) {
      const double s = sigma[scan.offset + j];
      value -= scan.beta * std::exp(-s / scan.beta - 1.0) + s;
    }
  }
  return value;
}

bool ColumnDualSolver::evaluate_value(const Vector& sigma, int extra_inner_scan) {
  split(sigma);
  value_ = clutter_value(sigma);
  for (std::size_t i = 0; i < tracks_.size(); ++i) {
    evaluations_[i] = tracks_[i].evaluate(sigma_by_scan_, settings_.inner, extra_inner_scan);
    if (!evaluations_[i].finite) return false;
    value_ += tracks_[i].dual_value();
  }
  return std::isfinite(value_);
}

bool ColumnDualSolver::evaluate_inner_value(const Vector& sigma) {
  split(sigma);
  value_ = clutter_value(sigma);
  for (std::size_t i = 0; i < tracks_.size(); ++i) {
    evaluations_[i] = tracks_[i].evaluate_inner(sigma_by_scan_, settings_.inner);
    if (!evaluations_[i].finite) return false;
    value_ += tracks_[i].dual_value();
  }
  return std::isfinite(value_);
}

void ColumnDualSolver::finish_gradient() {
  gradient_.setConstant(sigma_by_scan_.empty() ? 0 : offsets_.back() + scans_.back().measurements, -1.0);
  for (TiltedTrack& track : tracks_) {
    track.finish(sigma_by_scan_);
    for (int t = 0; t < scans(); ++t) {
      const Vector& log_marginal = track.log_marginal(t);
      for (int j = 1; j <= scans_[t].measurements; ++j) gradient_[scans_[t].offset + j - 1] += std::exp(log_marginal[j]);
    }
  }
  for (int t = 0; t < scans(); ++t) {
    const Scan& scan = scans_[t];
    for (int j = 0; j < scan.measurements; ++j) gradient_[scan.offset + j] += std::exp(-sigma_by_scan_[t][j] / scan.beta - 1.0);
  }
}

double ColumnDualSolver::largest_inner_residual() const {
  double largest = 0.0;
  for (const TrackEvaluation& e : evaluations_) {
    if (std::isnan(e.inner_residual)) return e.inner_residual;  // std::max would drop it
    largest = std::max(largest, e.inner_residual);
  }
  return largest;
}

void ColumnDualSolver::diagonal_scaling(Vector& scaling) const {
  // diag(K) without the cross terms of the inner solve: Σ_i μ(1 − μ)/(1 − γμ) + q⁰/β.
  scaling.resize(sigma_.size());
  for (int t = 0; t < scans(); ++t) {
    const Scan& scan = scans_[t];
    for (int j = 0; j < scan.measurements; ++j) {
      double diagonal = std::exp(-sigma_[scan.offset + j] / scan.beta - 1.0) / scan.beta;
      for (const TiltedTrack& track : tracks_) {
        const double mu = std::exp(track.log_marginal(t)[j + 1]);
        diagonal += mu * std::exp(track.log_complement(t)[j]) / (1.0 - scan.gamma * mu);
      }
      scaling[scan.offset + j] = 1.0 / std::max(diagonal, 1e-300);
    }
  }
}

void ColumnDualSolver::newton_direction(Vector& direction) {
  // The clutter term C(σ) = −Σ_tj [β_t q⁰_tj + σ_tj], q⁰ = e^{−σ/β − 1}, is separable but has
  // curvature q⁰/β: on past scans of cvs (β ≈ 0.01) a plain Newton step of a few units in σ
  // multiplies q⁰ by e^{hundreds}. So the step maximises the model
  //   m(Δ) = D(σ) + rᵀΔ − ½ Δᵀ K_T Δ − Σ_tj β q⁰ φ(Δ_tj / β),   φ(x) = e^{−x} − 1 + x,
  // which quadratises only the tracks' part (K_T = Σ_i K_i) and keeps C exact; written this way
  // (φ from expm1 or its series) it has no cancellation, so it stays accurate at ‖r‖ ~ 1e-12.
  // m is strictly concave; damped Newton on it (D variables) costs a few small factorisations,
  // and near the solution its first step is the plain Newton step. Since m is concave with
  // ∇m(0) = r, its maximiser Δ* is an ascent direction of D: rᵀΔ* ≥ m(Δ*) − m(0) > 0.
  const Eigen::Index size = sigma_.size();
  matrix_.setZero(size, size);
  for (TiltedTrack& track : tracks_) track.add_newton_matrix(offsets_, matrix_);
  matrix_sigma_ = sigma_;
  Vector beta(size);
  for (const Scan& scan : scans_) {
    for (int j = 0; j < scan.measurements; ++j) beta[scan.offset + j] = scan.beta;
  }
  const Vector clutter = (-sigma_.array() / beta.array() - 1.0).exp();
  const auto phi = [](double x) {  // e^{−x} − 1 + x ≥ 0
    return std::abs(x) < 1e-3 ? x * x * (0.5 - x * (1.0 / 6.0 - x / 24.0)) : std::expm1(-x) + x;
  };
  const auto model = [&](const Vector& delta) {
    double value = gradient_.dot(delta) - 0.5 * delta.dot(matrix_ * delta);
    for (Eigen::Index k = 0; k < size; ++k) value -= beta[k] * clutter[k] * phi(delta[k] / beta[k]);
    return value;
  };
  const double target = std::max(1e-3 * gradient_.cwiseAbs().maxCoeff(), 1e-16);
  direction.setZero(size);
  Vector model_gradient(size), step, candidate;
  Eigen::MatrixXd hessian;
  double value = 0.0;
  for (int iteration = 0; iteration < 50; ++iteration) {
    // ∇m = r − K_T Δ + q⁰ (e^{−Δ/β} − 1), −∇²m = K_T + diag(q⁰ e^{−Δ/β} / β).
    model_gradient = gradient_ - matrix_ * direction;
    for (Eigen::Index k = 0; k < size; ++k) model_gradient[k] += clutter[k] * std::expm1(-direction[k] / beta[k]);
    if (model_gradient.cwiseAbs().maxCoeff() <= target || direction.cwiseAbs().maxCoeff() > kTrustRadius) break;
    hessian = matrix_;
    for (Eigen::Index k = 0; k < size; ++k) hessian(k, k) += clutter[k] * std::exp(-direction[k] / beta[k]) / beta[k];
    if (!solve_positive(hessian, model_gradient, step)) break;
    const double slope = model_gradient.dot(step);
    double alpha = 1.0;
    bool accepted = false;
    while (alpha > 1e-12) {
      candidate = direction + alpha * step;
      const double candidate_value = model(candidate);
      if (std::isfinite(candidate_value) && candidate_value >= value + kArmijo * alpha * slope) {
        direction = candidate;
        value = candidate_value;
        accepted = true;
        break;
      }
      alpha *= 0.5;
    }
    if (!accepted) break;
  }
  limit_step(direction);  // m is concave and m(0) = 0 < m(Δ*): the scaled step still ascends
  if (direction.allFinite() && gradient_.dot(direction) > 0.0) return;
  Vector scaling;
  diagonal_scaling(scaling);
  direction = scaling.cwiseProduct(gradient_);
  limit_step(direction);
}

bool ColumnDualSolver::only_gamma_scan(int t) const {
  for (int u = 0; u < scans(); ++u) {
    if (u != t && scans_[u].gamma > 0.0) return false;
  }
  return true;
}

bool ColumnDualSolver::presolve(int new_scan, SolveReport& report) {
  // Block Newton on σ_focus with the other duals fixed: the other scans' evidence is read once.
  const Scan& scan = scans_[new_scan];
  const int m = scan.measurements;
  if (m == 0 || !evaluate_value(sigma_, new_scan)) return false;
  Eigen::MatrixXd block;
  Vector residual(m), direction, trial;
  for (int iteration = 0; iteration < settings_.max_iterations; ++iteration) {
    for (int j = 0; j < m; ++j) residual[j] = std::exp(-sigma_[scan.offset + j] / scan.beta - 1.0) - 1.0;
    for (const TiltedTrack& track : tracks_) residual += track.log_marginal(new_scan).tail(m).array().exp().matrix();
    if (residual.cwiseAbs().maxCoeff() <= settings_.presolve_tolerance) break;
    block.setZero(m, m);
    for (const TiltedTrack& track : tracks_) track.add_block_matrix(new_scan, 0, block);
    for (int j = 0; j < m; ++j) block(j, j) += std::exp(-sigma_[scan.offset + j] / scan.beta - 1.0) / scan.beta;
    if (!solve_positive(block, residual, direction)) break;
    limit_step(direction);
    const double slope = residual.dot(direction);
    const double value = value_;
    double step = 1.0;
    bool accepted = false;
    while (step >= kSmallestStep) {
      trial = sigma_;
      trial.segment(scan.offset, m) += step * direction;
      if (evaluate_inner_value(trial) && value_ - value >= kArmijo * step * slope) {
        accepted = true;
        break;
      }
      ++report.line_search_steps;
      step *= 0.5;
    }
    if (!accepted) return evaluate_inner_value(sigma_);
    sigma_ = trial;
  }
  return true;
}

bool ColumnDualSolver::evaluate_start(SolveReport& report) {
  const auto unsolved_scans = std::count_if(scans_.begin(), scans_.end(), [](const Scan& scan) { return !scan.solved; });
  // After the presolve the tracks hold σ's evaluation with the new scan in their inner sets; when
  // that is their inner set anyway (the new scan is the γ-scan, as in cvs) the other scans'
  // evidence is reused.
  bool inner_sets_evaluated = false;
  if (settings_.presolve && unsolved_scans == 1 && scans() > 1) {
    const int new_scan = static_cast<int>(
        std::find_if(scans_.begin(), scans_.end(), [](const Scan& scan) { return !scan.solved; }) - scans_.begin());
    inner_sets_evaluated = presolve(new_scan, report) && scans_[new_scan].gamma > 0.0 && only_gamma_scan(new_scan);
  }
  if (!inner_sets_evaluated) return evaluate(sigma_);
  return evaluate_inner_value(sigma_) && (finish_gradient(), gradient_.allFinite());
}

void ColumnDualSolver::solve(const ColumnDualSettings& settings, SolveReport& report) {
  settings_ = settings;
  const Eigen::Index size = sigma_.size();
  const DualMethod method = settings.method != DualMethod::kAuto ? settings.method
                            : size <= settings.newton_limit      ? DualMethod::kNewton
                                                                 : DualMethod::kLbfgs;
  if (report.line_search_steps < 0) report.line_search_steps = 0;
  const auto gamma_scans = std::count_if(scans_.begin(), scans_.end(), [](const Scan& scan) { return scan.gamma > 0.0; });
  if (gamma_scans > 1) settings_.inner.tolerance = std::max(settings.inner.tolerance, kInnerForcing);
  // Every failed evaluation ends the solve as skipped:numerical: the tracks' state is then not a
  // solution at any σ, and no belief may be written from it.
  const auto numerical_failure = [&report] { report.skipped = "numerical"; };
  if (!evaluate_start(report)) return numerical_failure();
  lbfgs_history_.clear();
  int iterations = 0;
  bool converged = false;
  while (true) {
    const double residual = size > 0 ? gradient_.cwiseAbs().maxCoeff() : 0.0;
    // With several γ-scans every inner step reads all tables, so the inner solves are inexact
    // while the outer residual is large (an inexact Newton method: the gradient then errs by about
    // kInnerForcing of the residual, and trial values by its square, far below the gains tested).
    // When the residual has fallen, the current point is re-evaluated with the tighter inner
    // tolerance first, so that its value and gradient compare with the trials'. With one γ-scan
    // the inner solve reads no table (tilted_track.hpp) and is always exact.
    const double inner_target = gamma_scans > 1 ? std::max(settings.inner.tolerance, kInnerForcing * residual)
                                                : settings.inner.tolerance;
    if (inner_target < 0.1 * settings_.inner.tolerance ||
        (residual <= settings.tolerance && settings_.inner.tolerance > settings.inner.tolerance)) {
      settings_.inner.tolerance = residual <= settings.tolerance ? settings.inner.tolerance : inner_target;
      if (!evaluate(sigma_)) return numerical_failure();
      continue;
    }
    if (residual <= settings.tolerance && largest_inner_residual() <= settings.inner.tolerance) {
      converged = true;
      break;
    }
    if (iterations >= settings.max_iterations) break;
    if (method == DualMethod::kNewton) {
      newton_direction(direction_);
    } else {
      lbfgs_direction(direction_);
      limit_step(direction_);
    }
    double slope = gradient_.dot(direction_);
    if (!(slope > 0.0)) {  // not an ascent direction (rounding): scaled gradient instead
      diagonal_scaling(scaling_);
      direction_ = scaling_.cwiseProduct(gradient_);
      limit_step(direction_);
      slope = gradient_.dot(direction_);
      lbfgs_history_.clear();
    }
    previous_gradient_ = gradient_;
    ++iterations;
    if (!line_search(slope, report)) {  // no progress at floating-point resolution: stay at the last point
      if (!evaluate(sigma_)) return numerical_failure();
      break;
    }
    if (method == DualMethod::kLbfgs) remember_step(settings.lbfgs_memory);
    sigma_ = trial_;
  }
  const double residual = size > 0 ? gradient_.cwiseAbs().maxCoeff() : 0.0;
  const double inner = largest_inner_residual();
  if (!std::isfinite(residual) || !std::isfinite(inner)) return numerical_failure();
  for (Scan& scan : scans_) scan.solved = true;
  report.iterations += iterations;
  report.residual = std::isnan(report.residual) ? residual : std::max(report.residual, residual);
  report.inner_residual = std::isnan(report.inner_residual) ? inner : std::max(report.inner_residual, inner);
  if (!converged) report.converged = false;
}

// Two-loop recursion on −D (Nocedal & Wright, Numerical Optimization, Alg. 7.4): gradient −r,
// direction H r with H₀ = diag(K)⁻¹.
void ColumnDualSolver::lbfgs_direction(Vector& direction) {
  diagonal_scaling(scaling_);
  Vector q = gradient_;
  lbfgs_alpha_.resize(lbfgs_history_.size());
  for (std::size_t k = lbfgs_history_.size(); k-- > 0;) {
    const auto& [s, y] = lbfgs_history_[k];
    lbfgs_alpha_[k] = s.dot(q) / y.dot(s);
    q -= lbfgs_alpha_[k] * y;
  }
  direction = scaling_.cwiseProduct(q);
  for (std::size_t k = 0; k < lbfgs_history_.size(); ++k) {
    const auto& [s, y] = lbfgs_history_[k];
    direction += s * (lbfgs_alpha_[k] - y.dot(direction) / y.dot(s));
  }
}

void ColumnDualSolver::remember_step(int memory) {
  Vector s = trial_ - sigma_;
  Vector y = previous_gradient_ - gradient_;
  if (s.dot(y) > 1e-12 * s.norm() * y.norm()) {
    lbfgs_history_.emplace_back(std::move(s), std::move(y));
    if (static_cast<int>(lbfgs_history_.size()) > memory) lbfgs_history_.pop_front();
  }
}

// Backtracking from the full step: the first σ + step · direction_ whose gain in D passes the
// Armijo test, or, where D's change is below its floating-point resolution, whose gradient is
// smaller. Warm-starts the tracks' inner unknowns from their first-order model when it is at hand.
bool ColumnDualSolver::line_search(double slope, SolveReport& report) {
  const double value = value_;
  const double residual_norm = gradient_.norm();
  // D's floating-point resolution: below it, the test is a decrease of ‖r‖.
  const double resolution = 1e-14 * (1.0 + std::abs(value));
  const bool predicted = matrix_sigma_.size() == sigma_.size();
  for (double step = 1.0; step >= kSmallestStep; step *= 0.5) {
    trial_ = sigma_ + step * direction_;
    if (predicted) {
      step_ = trial_ - matrix_sigma_;
      for (TiltedTrack& track : tracks_) track.guess_inner(step_);
    }
    if (evaluate_value(trial_)) {
      bool accepted = false;
      const double gain = value_ - value;
      if (gain >= kArmijo * step * slope) {
        finish_gradient();
        accepted = gradient_.allFinite();
      } else if (std::abs(gain) <= resolution && kArmijo * step * slope <= resolution) {
        finish_gradient();
        accepted = gradient_.allFinite() && gradient_.norm() < residual_norm;
      }
      if (accepted) return true;
    }
    ++report.line_search_steps;
  }
  return false;
}

void ColumnDualSolver::write_beliefs(MultiScanBeliefs& beliefs) const {
  const int n = static_cast<int>(tracks_.size());
  beliefs.track.resize(n);
  for (int i = 0; i < n; ++i) tracks_[i].write_belief(beliefs.track[i]);
  beliefs.association.resize(scans());
  for (int t = 0; t < scans(); ++t) {
    beliefs.association[t].reshape(n, scans_[t].measurements);
    for (int i = 0; i < n; ++i) tracks_[i].write_marginals(t, beliefs.association[t].row(i));
  }
}

}  // namespace dabench
