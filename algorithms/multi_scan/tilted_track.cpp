#include "algorithms/multi_scan/tilted_track.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "harness/core/special_values.hpp"
#include "harness/core/target_clones.hpp"

namespace dabench {

namespace {

// A factor below this fraction of its row's largest is not a candidate for the Newton matrix's
// cross-scan sums (track_newton_matrix.hpp).
constexpr double kCandidateFloor = 1e-16;
constexpr double kSmallComplement = TrackNewtonMatrix::kSmallComplement;

// log(e^a + e^b).
double log_add(double a, double b) {
  if (a < b) std::swap(a, b);
  if (b == kMinusInfinity) return a;
  return a + std::log1p(std::exp(b - a));
}

// out[j − 1] = log Σ_{a ≠ j} e^{x(a)}, j = 1..m, from prefix and suffix log-sums (never the
// log of a difference); `tail` is workspace.
void log_sums_without(const Vector& x, Vector& out, Vector& tail) {
  const Eigen::Index count = x.size();
  out.resize(count - 1);
  tail.resize(count + 1);
  tail[count] = kMinusInfinity;
  for (Eigen::Index a = count - 1; a >= 0; --a) tail[a] = log_add(tail[a + 1], x[a]);
  double prefix = x[0];  // log Σ_{a < j}: a = 0 is always included since j ≥ 1
  for (Eigen::Index j = 1; j < count; ++j) {
    out[j - 1] = log_add(prefix, tail[j + 1]);
    prefix = log_add(prefix, x[j]);
  }
}

// The two passes over a column-major factor table F (rows × columns), by blocks of hypotheses
// so that each block's evidence and ratios stay in L1 while the table streams once.
constexpr Eigen::Index kBlock = 512;

// s(A) = Σ_c F(A, c) w(c) into `evidence`, and product(A) *= scale · s(A); returns the largest product.
DABENCH_AVX2_CLONES double evidence_pass(const double* __restrict table, Eigen::Index rows,
                                        int columns, const double* __restrict weight,
                                        double scale, double* __restrict evidence,
                                        double* __restrict product) {
  double top = 0.0;
  for (Eigen::Index start = 0; start < rows; start += kBlock) {
    const Eigen::Index end = std::min(rows, start + kBlock);
    const double w0 = weight[0];
    for (Eigen::Index a = start; a < end; ++a) evidence[a] = table[a] * w0;
    for (int c = 1; c < columns; ++c) {
      const double* column = table + c * rows;
      const double w = weight[c];
      for (Eigen::Index a = start; a < end; ++a) evidence[a] += column[a] * w;
    }
    for (Eigen::Index a = start; a < end; ++a) {
      product[a] *= scale * evidence[a];
      top = product[a] > top ? product[a] : top;
    }
  }
  return top;
}

// U(c) = Σ_A F(A, c) product(A) / s(A) (terms with s = 0 are 0), with eight partial sums per
// column (`partial`: columns × 8 workspace) in a fixed order for any vector width.
DABENCH_AVX2_CLONES void marginal_pass(const double* __restrict table, Eigen::Index rows,
                                      int columns, const double* __restrict evidence,
                                      const double* __restrict product,
                                      double* __restrict partial, double* __restrict out) {
  double ratio[kBlock];
  for (int k = 0; k < columns * 8; ++k) partial[k] = 0.0;
  for (Eigen::Index start = 0; start < rows; start += kBlock) {
    const Eigen::Index count = std::min(rows - start, kBlock);
    for (Eigen::Index a = 0; a < count; ++a) {
      const double s = evidence[start + a];
      ratio[a] = s > 0.0 ? product[start + a] / s : 0.0;
    }
    const Eigen::Index whole = count - count % 8;
    for (int c = 0; c < columns; ++c) {
      const double* column = table + c * rows + start;
      double* sums = partial + 8 * c;
      for (Eigen::Index a = 0; a < whole; a += 8) {
        for (int k = 0; k < 8; ++k) sums[k] += column[a + k] * ratio[a + k];
      }
      for (Eigen::Index a = whole; a < count; ++a) sums[a - whole] += column[a] * ratio[a];
    }
  }
  for (int c = 0; c < columns; ++c) {
    const double* sums = partial + 8 * c;
    out[c] = ((sums[0] + sums[1]) + (sums[2] + sums[3])) + ((sums[4] + sums[5]) + (sums[6] + sums[7]));
  }
}

// U(c) = Σ_A F(A, c) w(A), eight partial sums per column (`partial`: columns × 8 workspace).
DABENCH_AVX2_CLONES void column_sums(const double* __restrict table, Eigen::Index rows,
                                    int columns, const double* __restrict weight,
                                    double* __restrict partial, double* __restrict out) {
  for (int k = 0; k < columns * 8; ++k) partial[k] = 0.0;
  const Eigen::Index whole = rows - rows % 8;
  for (int c = 0; c < columns; ++c) {
    const double* column = table + c * rows;
    double* sums = partial + 8 * c;
    for (Eigen::Index a = 0; a < whole; a += 8) {
      for (int k = 0; k < 8; ++k) sums[k] += column[a + k] * weight[a + k];
    }
    for (Eigen::Index a = whole; a < rows; ++a) sums[a - whole] += column[a] * weight[a];
    out[c] = ((sums[0] + sums[1]) + (sums[2] + sums[3])) + ((sums[4] + sums[5]) + (sums[6] + sums[7]));
  }
}

// Σ_A x(A), eight partial sums.
double pairwise_sum(const Vector& x) {
  double partial[8] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  const Eigen::Index rows = x.size();
  Eigen::Index a = 0;
  for (; a + 8 <= rows; a += 8) {
    for (int k = 0; k < 8; ++k) partial[k] += x[a + k];
  }
  double sum = 0.0;
  for (; a < rows; ++a) sum += x[a];
  return sum + (((partial[0] + partial[1]) + (partial[2] + partial[3])) + ((partial[4] + partial[5]) + (partial[6] + partial[7])));
}

}  // namespace

void TiltedTrack::start(const Vector& prior) {
  prior_ = prior;
  scan_count_ = 0;
  newton_.invalidate();
  repack();
}

void TiltedTrack::append_scan(const RowMatrix& factor) {
  if (scan_count_ == static_cast<int>(scans_.size())) scans_.emplace_back();
  Scan& scan = scans_[scan_count_++];
  scan.measurements = static_cast<int>(factor.cols()) - 1;
  scan.gamma = 0.0;
  scan.original = &factor;
  scan.offset.setZero(scan.measurements);
  scan.inner_log_complement.setZero(scan.measurements);
  scan.log_marginal.setConstant(scan.measurements + 1, kMinusInfinity);
  scan.log_complement.setZero(scan.measurements);
  bool drops = false;
  for (int h : kept_) drops = drops || !(factor.row(h).maxCoeff() > 0.0);
  newton_.invalidate();
  if (drops) {
    repack();
    return;
  }
  pack(scan);
  evidence_.resize(kept_.size() * static_cast<std::size_t>(scans()));
}

void TiltedTrack::repack() {
  kept_.clear();
  for (Eigen::Index h = 0; h < prior_.size(); ++h) {
    bool alive = prior_[h] > 0.0;
    for (int t = 0; t < scans(); ++t) alive = alive && scans_[t].original->row(h).maxCoeff() > 0.0;
    if (alive) kept_.push_back(static_cast<int>(h));
  }
  const auto kept = static_cast<Eigen::Index>(kept_.size());
  weight_.resize(kept);
  for (Eigen::Index k = 0; k < kept; ++k) weight_[k] = prior_[kept_[k]];
  const double top = kept > 0 ? weight_.maxCoeff() : 1.0;
  weight_ /= top;
  log_weight_scale_ = std::log(top);
  for (int t = 0; t < scans(); ++t) pack(scans_[t]);
  evidence_.resize(kept_.size() * static_cast<std::size_t>(scans()));
}

void TiltedTrack::pack(Scan& scan) const {
  const RowMatrix& original = *scan.original;
  const auto kept = static_cast<Eigen::Index>(kept_.size());
  const int m = scan.measurements;
  scan.factor.resize(static_cast<std::size_t>(kept) * static_cast<std::size_t>(m + 1));
  Eigen::Map<ColumnMatrix> table(scan.factor.data(), kept, m + 1);
  scan.candidate_start.assign(1, 0);
  scan.candidate_column.clear();
  scan.candidate_factor.clear();
  for (Eigen::Index k = 0; k < kept; ++k) {
    const auto row = original.row(kept_[k]);
    table.row(k) = row;
    const double floor = row.maxCoeff() * kCandidateFloor;
    for (int j = 1; j <= m; ++j) {
      if (row[j] > floor) {
        scan.candidate_column.push_back(j);
        scan.candidate_factor.push_back(row[j]);
      }
    }
    scan.candidate_start.push_back(static_cast<int>(scan.candidate_column.size()));
  }
  scan.possible.assign(m, 0);
  for (int j = 1; j <= m; ++j) scan.possible[j - 1] = (table.col(j).array() > 0.0).any();
}

void TiltedTrack::set_tilts(int t, const Vector& sigma) {
  Scan& scan = scans_[t];
  const int m = scan.measurements;
  scan.log_tilt.resize(m + 1);
  scan.log_tilt[0] = 0.0;
  for (int j = 1; j <= m; ++j) {
    double tau = -sigma[j - 1] + scan.offset[j - 1];
    if (is_inner(scan, j - 1)) tau -= scan.gamma * (1.0 + scan.inner_log_complement[j - 1]);
    scan.log_tilt[j] = tau;
  }
  scan.shift = std::max(0.0, scan.log_tilt.maxCoeff());
  scan.log_tilt.array() -= scan.shift;
  scan.tilt = scan.log_tilt.array().exp();
}

bool TiltedTrack::multiply_evidence(int t, Vector& product, double& log_scale, double& pending) {
  // The product is rescaled by an exact power of two after every scan, the factor applied
  // lazily in the next pass (`pending`); the caller applies the last one.
  const Scan& scan = scans_[t];
  const double top = evidence_pass(scan.factor.data(), kept_rows(), scan.measurements + 1, scan.tilt.data(), pending,
                                   evidence(t), product.data());
  if (!(top > 0.0) || !std::isfinite(top)) return false;
  int exponent = 0;
  std::frexp(top, &exponent);
  pending = std::ldexp(1.0, -exponent);  // the heaviest hypothesis back in [0.5, 1)
  log_scale += scan.shift + exponent * std::numbers::ln2;
  return true;
}

void TiltedTrack::scan_marginals(int t) {
  Scan& scan = scans_[t];
  const Eigen::Index rows = kept_rows();
  pass_work_.column_sums.resize(scan.measurements + 1);
  pass_work_.column_partial_sums.resize(8 * (scan.measurements + 1));
  marginal_pass(scan.factor.data(), rows, scan.measurements + 1, evidence(t), product_.data(), pass_work_.column_partial_sums.data(),
                pass_work_.column_sums.data());
  scan.log_marginal = scan.log_tilt.array() + pass_work_.column_sums.array().log() - log_total_;
  log_sums_without(scan.log_marginal, scan.log_complement, pass_work_.suffix_log_sums);
}

bool TiltedTrack::inner_pass(const std::vector<Vector>& sigma) {
  if (inner_scans_.size() == 1) {
    // One scan g in the inner set: q(A) ∝ rest(A) s_g(A), so μ_g(a) = e^{τ(a)} U(a) / Σ_b e^{τ(b)} U(b)
    // with U(a) = Σ_A rest(A) ψ_g(A, a) fixed by the other scans (rest_sums_): no pass over the
    // hypotheses. product_ is formed by finish() when needed.
    const int g = inner_scans_[0];
    Scan& scan = scans_[g];
    set_tilts(g, sigma[g]);
    scan.log_marginal = scan.log_tilt + log_rest_sums_;
    const double top = scan.log_marginal.maxCoeff();
    if (!std::isfinite(top)) return false;
    const double log_sum = top + std::log((scan.log_marginal.array() - top).exp().sum());
    scan.log_marginal.array() -= log_sum;
    log_sums_without(scan.log_marginal, scan.log_complement, pass_work_.suffix_log_sums);
    log_partition_ = rest_log_scale_ + scan.shift + log_sum;
    product_valid_ = false;
    return std::isfinite(log_partition_);
  }
  form_product(sigma);
  if (!product_valid_) return false;
  for (int t : inner_scans_) scan_marginals(t);
  return true;
}

void TiltedTrack::form_product(const std::vector<Vector>& sigma) {
  product_valid_ = false;
  product_ = rest_;
  product_log_scale_ = rest_log_scale_;
  double pending = 1.0;
  for (int t : inner_scans_) {
    set_tilts(t, sigma[t]);
    if (!multiply_evidence(t, product_, product_log_scale_, pending)) return;
  }
  if (pending != 1.0) product_ *= pending;
  const double total = pairwise_sum(product_);
  if (!(total > 0.0) || !std::isfinite(total)) return;
  log_total_ = std::log(total);
  log_partition_ = product_log_scale_ + log_total_;
  product_valid_ = true;
}

void TiltedTrack::inner_unknowns(Vector& v) const {
  Eigen::Index size = 0;
  for (int t : inner_scans_) size += scans_[t].measurements;
  v.resize(size);
  Eigen::Index k = 0;
  for (int t : inner_scans_) {
    v.segment(k, scans_[t].measurements) = scans_[t].inner_log_complement;
    k += scans_[t].measurements;
  }
}

void TiltedTrack::set_inner_unknowns(const Vector& v) {
  Eigen::Index k = 0;
  for (int t : inner_scans_) {
    scans_[t].inner_log_complement = v.segment(k, scans_[t].measurements);
    k += scans_[t].measurements;
  }
}

double TiltedTrack::inner_residual(Vector& residual) const {
  Eigen::Index size = 0;
  for (int t : inner_scans_) size += scans_[t].measurements;
  residual.setZero(size);
  double largest = 0.0;
  Eigen::Index k = 0;
  for (int t : inner_scans_) {
    const Scan& scan = scans_[t];
    for (int j = 0; j < scan.measurements; ++j, ++k) {
      if (!is_inner(scan, j)) continue;
      residual[k] = scan.inner_log_complement[j] - scan.log_complement[j];
      largest = std::max(largest, std::abs(residual[k]));
    }
  }
  return largest;
}

void TiltedTrack::inner_step(const Vector& residual, bool refresh, Vector& step) {
  // J = ∂F/∂v = I − G diag(1/(1 − μ)) Σ over the inner unknowns. Within a scan Σ is closed form
  // (Σ_jj = μ_j (1 − μ_j), Σ_jk = −μ_j μ_k: J_jj = 1 − γ μ_j, J_jk = γ μ_j μ_k / (1 − μ_j)); across
  // scans (several γ-scans, as in cv) it is summed over the hypotheses by covariance(), with the
  // Newton matrix's rules (hypotheses above a mass floor; no cross terms where 1 − μ is small).
  // That sum costs about a pass over the tables, so with several γ-scans J is kept for the
  // following steps of the same solve unless `refresh` (a chord step). Rows of unknowns whose
  // association is all but impossible (μ < kActiveFloor) differ from the identity by O(μ) and
  // are taken as identity rows, so the dense solve is over the active unknowns only.
  const bool cross = inner_scans_.size() > 1;
  step = -residual;
  if (!(cross && !refresh && inner_work_.jacobian_factor.rows() == static_cast<Eigen::Index>(inner_work_.active.size()))) {
    inner_work_.scan_of.clear();
    inner_work_.measurement_of.clear();
    inner_work_.active.clear();
    for (int t : inner_scans_) {
      const Scan& scan = scans_[t];
      for (int j = 0; j < scan.measurements; ++j) {
        if (is_inner(scan, j) && scan.log_marginal[j + 1] >= TrackNewtonMatrix::kLogActiveFloor) {
          inner_work_.active.push_back(static_cast<int>(inner_work_.scan_of.size()));
        }
        inner_work_.scan_of.push_back(t);
        inner_work_.measurement_of.push_back(j);
      }
    }
    if (cross) {
      inner_work_.scan_offsets.resize(static_cast<std::size_t>(scans()));
      int total = 0;
      for (int t = 0; t < scans(); ++t) {
        inner_work_.scan_offsets[t] = total;
        total += scans_[t].measurements;
      }
      newton_.covariance(*this, inner_work_.scan_offsets, total);
    }
    const auto count = static_cast<Eigen::Index>(inner_work_.active.size());
    inner_work_.jacobian.setIdentity(count, count);
    for (Eigen::Index r = 0; r < count; ++r) {
      const Scan& scan = scans_[inner_work_.scan_of[inner_work_.active[r]]];
      const int j = inner_work_.measurement_of[inner_work_.active[r]];
      const double log_mu = scan.log_marginal[j + 1];
      const double log_complement = scan.log_complement[j];
      for (Eigen::Index c = 0; c < count; ++c) {
        const Scan& other = scans_[inner_work_.scan_of[inner_work_.active[c]]];
        const int l = inner_work_.measurement_of[inner_work_.active[c]];
        if (inner_work_.scan_of[inner_work_.active[c]] == inner_work_.scan_of[inner_work_.active[r]]) {
          inner_work_.jacobian(r, c) = l == j ? 1.0 - scan.gamma * std::exp(log_mu)
                                   : scan.gamma * std::exp(log_mu + other.log_marginal[l + 1] - log_complement);
        } else if (cross && std::exp(log_complement) >= kSmallComplement &&
                   std::exp(other.log_complement[l]) >= kSmallComplement) {
          const int row = newton_.active_position()[inner_work_.scan_offsets[inner_work_.scan_of[inner_work_.active[r]]] + j];
          const int column = newton_.active_position()[inner_work_.scan_offsets[inner_work_.scan_of[inner_work_.active[c]]] + l];
          if (row >= 0 && column >= 0) inner_work_.jacobian(r, c) = -scan.gamma * newton_.covariance()(row, column) * std::exp(-log_complement);
        }
      }
    }
    inner_work_.jacobian_factor.compute(inner_work_.jacobian);
  }
  inner_work_.active_residual.resize(static_cast<Eigen::Index>(inner_work_.active.size()));
  for (std::size_t r = 0; r < inner_work_.active.size(); ++r) inner_work_.active_residual[static_cast<Eigen::Index>(r)] = -residual[inner_work_.active[r]];
  inner_work_.active_step = inner_work_.jacobian_factor.solve(inner_work_.active_residual);
  for (std::size_t r = 0; r < inner_work_.active.size(); ++r) step[inner_work_.active[r]] = inner_work_.active_step[static_cast<Eigen::Index>(r)];
}

TrackEvaluation TiltedTrack::inner_solve(const std::vector<Vector>& sigma, const InnerSolveSettings& settings) {
  TrackEvaluation result;
  if (!inner_pass(sigma)) {
    result.finite = false;
    return result;
  }
  // Damped Newton on F(v) = v − log(1 − μ(v)); J is nonsingular (the Hessian of a partial
  // minimum of a strictly convex function), so a decrease of ‖F‖ at every step leads to the root.
  double largest = inner_residual(inner_work_.residual);
  double previous_merit = std::numeric_limits<double>::infinity();
  while (largest > settings.tolerance && result.inner_iterations < settings.max_iterations) {
    // A new Jacobian on the first step and whenever the last step cut ‖F‖² by less than 100×.
    inner_step(inner_work_.residual, result.inner_iterations == 0 || inner_work_.residual.squaredNorm() > 1e-2 * previous_merit, inner_work_.step);
    previous_merit = inner_work_.residual.squaredNorm();
    inner_unknowns(inner_work_.unknowns);
    const double merit = inner_work_.residual.squaredNorm();
    double alpha = 1.0;
    bool accepted = false;
    while (alpha > 1e-12) {
      inner_work_.trial_unknowns = inner_work_.unknowns + alpha * inner_work_.step;
      set_inner_unknowns(inner_work_.trial_unknowns);
      if (inner_pass(sigma)) {
        const double trial_largest = inner_residual(inner_work_.trial_residual);
        if (inner_work_.trial_residual.squaredNorm() <= (1.0 - 1e-4 * alpha) * merit || trial_largest <= settings.tolerance) {
          inner_work_.residual.swap(inner_work_.trial_residual);
          largest = trial_largest;
          accepted = true;
          break;
        }
      }
      alpha *= 0.5;
    }
    ++result.inner_iterations;
    if (!accepted) {  // no decrease at floating-point resolution: keep the last accepted point
      set_inner_unknowns(inner_work_.unknowns);
      if (!inner_pass(sigma)) result.finite = false;
      largest = inner_residual(inner_work_.residual);
      break;
    }
  }
  result.inner_residual = largest;
  return result;
}

TrackEvaluation TiltedTrack::evaluate(const std::vector<Vector>& sigma, const InnerSolveSettings& settings,
                                      int extra_inner_scan) {
  inner_scans_.clear();
  other_scans_.clear();
  for (int t = 0; t < scans(); ++t) {
    Scan& scan = scans_[t];
    bool inner = t == extra_inner_scan;
    for (int j = 0; j < scan.measurements && !inner; ++j) inner = is_inner(scan, j);
    scan.inner = inner;
    (inner ? inner_scans_ : other_scans_).push_back(t);
  }
  rest_ = weight_;
  rest_log_scale_ = log_weight_scale_;
  double pending = 1.0;
  for (int t : other_scans_) {
    set_tilts(t, sigma[t]);
    if (!multiply_evidence(t, rest_, rest_log_scale_, pending)) {
      TrackEvaluation failed;
      failed.finite = false;
      return failed;
    }
  }
  if (pending != 1.0) rest_ *= pending;
  if (inner_scans_.size() == 1) {
    const Scan& scan = scans_[inner_scans_[0]];
    rest_sums_.resize(scan.measurements + 1);
    pass_work_.column_partial_sums.resize(8 * (scan.measurements + 1));
    column_sums(scan.factor.data(), kept_rows(), scan.measurements + 1, rest_.data(), pass_work_.column_partial_sums.data(), rest_sums_.data());
    log_rest_sums_ = rest_sums_.array().log();
  }
  return inner_solve(sigma, settings);
}

TrackEvaluation TiltedTrack::evaluate_inner(const std::vector<Vector>& sigma, const InnerSolveSettings& settings) {
  return inner_solve(sigma, settings);
}

void TiltedTrack::finish(const std::vector<Vector>& sigma) {
  if (!product_valid_) {
    form_product(sigma);  // the inner set's tilts are those of the last inner pass
    log_partition_ = product_log_scale_ + log_total_;
  }
  for (int t : other_scans_) scan_marginals(t);
}

double TiltedTrack::dual_value() const {
  double value = -log_partition_;
  for (int t : inner_scans_) {
    const Scan& scan = scans_[t];
    for (int j = 0; j < scan.measurements; ++j) {
      if (!is_inner(scan, j)) continue;
      const double log_complement = scan.log_complement[j];
      value -= scan.gamma * ((1.0 + scan.inner_log_complement[j]) * std::exp(scan.log_marginal[j + 1]) +
                             std::exp(log_complement) * log_complement);
    }
  }
  return value;
}

void TiltedTrack::add_newton_matrix(const std::vector<int>& offsets, Eigen::MatrixXd& matrix) {
  newton_.add(*this, offsets, matrix);
}

void TiltedTrack::add_block_matrix(int t, int offset, Eigen::MatrixXd& matrix) const {
  TrackNewtonMatrix::add_block(*this, t, offset, matrix);
}

void TiltedTrack::guess_inner(const Vector& step) { newton_.guess_inner(*this, step); }

void TiltedTrack::write_belief(Vector& belief) const {
  belief = Vector::Zero(prior_.size());
  const double inverse_total = std::exp(-log_total_);
  for (std::size_t k = 0; k < kept_.size(); ++k) belief[kept_[k]] = product_[static_cast<Eigen::Index>(k)] * inverse_total;
}

void TiltedTrack::write_marginals(int t, double* row) const {
  const Scan& scan = scans_[t];
  for (int a = 0; a <= scan.measurements; ++a) row[a] = std::exp(scan.log_marginal[a]);
}

RowMatrix TiltedTrack::pair_belief(int t) const {
  const Scan& scan = scans_[t];
  RowMatrix pair = RowMatrix::Zero(prior_.size(), scan.measurements + 1);
  const double inverse_total = std::exp(-log_total_);
  for (std::size_t k = 0; k < kept_.size(); ++k) {
    const auto a = static_cast<Eigen::Index>(k);
    const double s = evidence(t)[a];
    if (!(s > 0.0)) continue;
    const double q = product_[a] * inverse_total;
    for (int b = 0; b <= scan.measurements; ++b) pair(kept_[k], b) = q * scan.factor[b * kept_.size() + k] * scan.tilt[b] / s;
  }
  return pair;
}

}  // namespace dabench
