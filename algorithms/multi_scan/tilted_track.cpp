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

// Hypotheses with q(A) below this (normalised) are left out of the Newton matrix's cross-scan sums.
constexpr double kMatrixMassFloor = 1e-8;
// Association probabilities p_t(j | A) below this are left out of the cross-scan sums (an
// absolute error below 1e-9 of the entry's own marginal: the matrix only steers the Newton step).
constexpr double kMatrixEntryFloor = 1e-9;
// Hypotheses contribute the entries with √q(A) p_t(j | A) above this to the cross-scan sums.
constexpr double kMatrixWeightFloor = 1e-8;
// A factor below this fraction of its row's largest is not a candidate for the cross-scan sums.
constexpr double kCandidateFloor = 1e-16;
// Below this 1 − μ_t(j), the γ-column j carries no cross-scan terms in the matrix (see covariance()).
constexpr double kSmallComplement = 1e-6;
// Associations less likely than this for a track (μ_t(j) < 1e-12) change its Newton matrix and
// inner Jacobian by O(μ) only: they take no part in their dense solves.
const double kLogActiveFloor = std::log(1e-12);

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
  sensitivity_valid_ = false;
  repack();
}

void TiltedTrack::append_scan(const RowMatrix& factor) {
  if (scan_count_ == static_cast<int>(scans_.size())) scans_.emplace_back();
  Scan& scan = scans_[scan_count_++];
  scan.measurements = static_cast<int>(factor.cols()) - 1;
  scan.gamma = 0.0;
  scan.original = &factor;
  scan.offset.setZero(scan.measurements);
  scan.log_unused.setZero(scan.measurements);
  scan.log_marginal.setConstant(scan.measurements + 1, kMinusInfinity);
  scan.log_complement.setZero(scan.measurements);
  bool drops = false;
  for (int h : kept_) drops = drops || !(factor.row(h).maxCoeff() > 0.0);
  sensitivity_valid_ = false;
  candidates_valid_ = false;
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

void TiltedTrack::build_candidates() {
  const auto kept = static_cast<Eigen::Index>(kept_.size());
  candidate_start_.assign(1, 0);
  candidates_.clear();
  for (Eigen::Index a = 0; a < kept; ++a) {
    for (int t = 0; t < scans(); ++t) {
      const Scan& scan = scans_[t];
      for (int c = scan.candidate_start[a]; c < scan.candidate_start[a + 1]; ++c) {
        candidates_.push_back({t, scan.candidate_column[c], scan.candidate_factor[c]});
      }
    }
    candidate_start_.push_back(static_cast<int>(candidates_.size()));
  }
  candidates_valid_ = true;
}

void TiltedTrack::set_tilts(int t, const Vector& sigma) {
  Scan& scan = scans_[t];
  const int m = scan.measurements;
  scan.log_tilt.resize(m + 1);
  scan.log_tilt[0] = 0.0;
  for (int j = 1; j <= m; ++j) {
    double tau = -sigma[j - 1] + scan.offset[j - 1];
    if (is_inner(scan, j - 1)) tau -= scan.gamma * (1.0 + scan.log_unused[j - 1]);
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
  column_sum_.resize(scan.measurements + 1);
  partial_.resize(8 * (scan.measurements + 1));
  marginal_pass(scan.factor.data(), rows, scan.measurements + 1, evidence(t), product_.data(), partial_.data(),
                column_sum_.data());
  scan.log_marginal = scan.log_tilt.array() + column_sum_.array().log() - log_total_;
  log_sums_without(scan.log_marginal, scan.log_complement, tail_);
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
    log_sums_without(scan.log_marginal, scan.log_complement, tail_);
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
    v.segment(k, scans_[t].measurements) = scans_[t].log_unused;
    k += scans_[t].measurements;
  }
}

void TiltedTrack::set_inner_unknowns(const Vector& v) {
  Eigen::Index k = 0;
  for (int t : inner_scans_) {
    scans_[t].log_unused = v.segment(k, scans_[t].measurements);
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
      residual[k] = scan.log_unused[j] - scan.log_complement[j];
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
  if (!(cross && !refresh && jacobian_factor_.rows() == static_cast<Eigen::Index>(active_.size()))) {
    scan_of_.clear();
    index_of_.clear();
    active_.clear();
    for (int t : inner_scans_) {
      const Scan& scan = scans_[t];
      for (int j = 0; j < scan.measurements; ++j) {
        if (is_inner(scan, j) && scan.log_marginal[j + 1] >= kLogActiveFloor) {
          active_.push_back(static_cast<int>(scan_of_.size()));
        }
        scan_of_.push_back(t);
        index_of_.push_back(j);
      }
    }
    if (cross) {
      local_offsets_.resize(static_cast<std::size_t>(scans()));
      int total = 0;
      for (int t = 0; t < scans(); ++t) {
        local_offsets_[t] = total;
        total += scans_[t].measurements;
      }
      covariance(local_offsets_, total);
    }
    const auto count = static_cast<Eigen::Index>(active_.size());
    jacobian_.setIdentity(count, count);
    for (Eigen::Index r = 0; r < count; ++r) {
      const Scan& scan = scans_[scan_of_[active_[r]]];
      const int j = index_of_[active_[r]];
      const double log_mu = scan.log_marginal[j + 1];
      const double log_complement = scan.log_complement[j];
      for (Eigen::Index c = 0; c < count; ++c) {
        const Scan& other = scans_[scan_of_[active_[c]]];
        const int l = index_of_[active_[c]];
        if (scan_of_[active_[c]] == scan_of_[active_[r]]) {
          jacobian_(r, c) = l == j ? 1.0 - scan.gamma * std::exp(log_mu)
                                   : scan.gamma * std::exp(log_mu + other.log_marginal[l + 1] - log_complement);
        } else if (cross && std::exp(log_complement) >= kSmallComplement &&
                   std::exp(other.log_complement[l]) >= kSmallComplement) {
          const int row = active_position_[local_offsets_[scan_of_[active_[r]]] + j];
          const int column = active_position_[local_offsets_[scan_of_[active_[c]]] + l];
          if (row >= 0 && column >= 0) jacobian_(r, c) = -scan.gamma * active_covariance_(row, column) * std::exp(-log_complement);
        }
      }
    }
    jacobian_factor_.compute(jacobian_);
  }
  active_residual_.resize(static_cast<Eigen::Index>(active_.size()));
  for (std::size_t r = 0; r < active_.size(); ++r) active_residual_[static_cast<Eigen::Index>(r)] = -residual[active_[r]];
  active_step_ = jacobian_factor_.solve(active_residual_);
  for (std::size_t r = 0; r < active_.size(); ++r) step[active_[r]] = active_step_[static_cast<Eigen::Index>(r)];
}

TrackEvaluation TiltedTrack::inner_solve(const std::vector<Vector>& sigma, const InnerSolveSettings& settings) {
  TrackEvaluation result;
  if (!inner_pass(sigma)) {
    result.finite = false;
    return result;
  }
  // Damped Newton on F(v) = v − log(1 − μ(v)); J is nonsingular (the Hessian of a partial
  // minimum of a strictly convex function), so a decrease of ‖F‖ at every step leads to the root.
  double largest = inner_residual(residual_);
  double previous_merit = std::numeric_limits<double>::infinity();
  while (largest > settings.tolerance && result.inner_iterations < settings.max_iterations) {
    // A new Jacobian on the first step and whenever the last step cut ‖F‖² by less than 100×.
    inner_step(residual_, result.inner_iterations == 0 || residual_.squaredNorm() > 1e-2 * previous_merit, step_);
    previous_merit = residual_.squaredNorm();
    inner_unknowns(unknowns_);
    const double merit = residual_.squaredNorm();
    double alpha = 1.0;
    bool accepted = false;
    while (alpha > 1e-12) {
      trial_ = unknowns_ + alpha * step_;
      set_inner_unknowns(trial_);
      if (inner_pass(sigma)) {
        const double trial_largest = inner_residual(trial_residual_);
        if (trial_residual_.squaredNorm() <= (1.0 - 1e-4 * alpha) * merit || trial_largest <= settings.tolerance) {
          residual_.swap(trial_residual_);
          largest = trial_largest;
          accepted = true;
          break;
        }
      }
      alpha *= 0.5;
    }
    ++result.inner_iterations;
    if (!accepted) {  // no decrease at floating-point resolution: keep the last accepted point
      set_inner_unknowns(unknowns_);
      if (!inner_pass(sigma)) result.finite = false;
      largest = inner_residual(residual_);
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
    partial_.resize(8 * (scan.measurements + 1));
    column_sums(scan.factor.data(), kept_rows(), scan.measurements + 1, rest_.data(), partial_.data(), rest_sums_.data());
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
      value -= scan.gamma * ((1.0 + scan.log_unused[j]) * std::exp(scan.log_marginal[j + 1]) +
                             std::exp(log_complement) * log_complement);
    }
  }
  return value;
}

void TiltedTrack::covariance(const std::vector<int>& offsets, int size) {
  // Σ over the active associations (μ ≥ kActiveFloor; the others' entries are O(μ)): within a
  // scan closed form, across scans E[p_k(A) p_l(A)] − μ_k μ_l with the sums over the hypotheses
  // that carry mass, from each hypothesis's candidate associations,
  // p_t(j | A) = ψ_t(A, j) e^{τ_t(j) − c_t} / s̃_t(A). Entries come in scan order, so the pairs
  // across scans are those with an entry of an earlier scan.
  if (!candidates_valid_) build_candidates();
  active_index_.clear();
  active_position_.assign(static_cast<std::size_t>(size), -1);
  for (int t = 0; t < scans(); ++t) {
    for (int j = 0; j < scans_[t].measurements; ++j) {
      if (scans_[t].log_marginal[j + 1] < kLogActiveFloor) continue;
      active_position_[offsets[t] + j] = static_cast<int>(active_index_.size());
      active_index_.push_back(offsets[t] + j);
    }
  }
  const auto active = static_cast<Eigen::Index>(active_index_.size());
  const auto kept = static_cast<Eigen::Index>(kept_.size());
  const double inverse_total = std::exp(-log_total_);
  entry_index_.resize(static_cast<std::size_t>(active));
  entry_value_.resize(static_cast<std::size_t>(active));
  cross_.assign(static_cast<std::size_t>(active) * static_cast<std::size_t>(active), 0.0);
  const int scan_count = scans();
  tilt_of_scan_.resize(static_cast<std::size_t>(scan_count));
  for (int t = 0; t < scan_count; ++t) tilt_of_scan_[t] = scans_[t].tilt.data();
  inverse_evidence_.resize(static_cast<std::size_t>(kept) * static_cast<std::size_t>(scan_count));
  for (int t = 0; t < scan_count; ++t) {
    const double* column = evidence(t);
    for (Eigen::Index a = 0; a < kept; ++a) inverse_evidence_[a * scan_count + t] = 1.0 / column[a];
  }
  for (Eigen::Index a = 0; a < kept; ++a) {
    const double q = product_[a] * inverse_total;
    if (q < kMatrixMassFloor) continue;
    // An entry enters if √q p ≥ kMatrixWeightFloor: the pairs left out change an entry of the
    // matrix by at most kMatrixWeightFloor Σ_A √q(A) ≤ kMatrixWeightFloor √H.
    const double entry_floor = std::max(kMatrixEntryFloor, kMatrixWeightFloor / std::sqrt(q));
    if (entry_floor > 1.0) continue;
    int count = 0, scan = -1, scan_first = 0;
    double inverse = 0.0;
    for (int c = candidate_start_[a]; c < candidate_start_[a + 1]; ++c) {
      const Candidate& candidate = candidates_[c];
      if (candidate.scan != scan) {
        scan = candidate.scan;
        scan_first = count;
        inverse = inverse_evidence_[a * scan_count + scan];
      }
      const int position = active_position_[offsets[scan] + candidate.column - 1];
      if (position < 0) continue;
      const double p = candidate.factor * tilt_of_scan_[scan][candidate.column] * inverse;
      if (p < entry_floor) continue;
      const double qp = q * p;
      double* row = cross_.data() + static_cast<std::size_t>(position) * static_cast<std::size_t>(active);
      for (int y = 0; y < scan_first; ++y) row[entry_index_[y]] += qp * entry_value_[y];
      entry_index_[count] = position;
      entry_value_[count] = p;
      ++count;
    }
  }
  Eigen::MatrixXd& sigma = active_covariance_;
  sigma.resize(active, active);
  Vector& mu = active_mu_;
  mu.resize(active);
  std::vector<int>& scan_of = active_scan_;
  scan_of.resize(static_cast<std::size_t>(active));
  for (Eigen::Index k = 0; k < active; ++k) {
    int t = 0;
    while (t + 1 < scan_count && offsets[t + 1] <= active_index_[k]) ++t;
    scan_of[k] = t;
    mu[k] = std::exp(scans_[t].log_marginal[active_index_[k] - offsets[t] + 1]);
  }
  for (Eigen::Index k = 0; k < active; ++k) {
    const Scan& scan = scans_[scan_of[k]];
    const int j = active_index_[k] - offsets[scan_of[k]];
    for (Eigen::Index l = 0; l < k; ++l) {
      sigma(k, l) = scan_of[l] == scan_of[k] ? -mu[k] * mu[l]
                                             : cross_[static_cast<std::size_t>(k) * static_cast<std::size_t>(active) + l] - mu[k] * mu[l];
      sigma(l, k) = sigma(k, l);
    }
    sigma(k, k) = std::exp(scan.log_marginal[j + 1] + scan.log_complement[j]);  // μ(1 − μ)
  }
}

void TiltedTrack::add_newton_matrix(const std::vector<int>& offsets, Eigen::MatrixXd& matrix) {
  covariance(offsets, static_cast<int>(matrix.rows()));
  Eigen::MatrixXd& full = active_covariance_;
  const auto active = static_cast<Eigen::Index>(active_index_.size());
  // The γ-columns (active inner unknowns of the γ-scans): S = Σ_{:,Γ} / (1 − μ_Γ).
  gamma_column_.clear();
  for (Eigen::Index k = 0; k < active; ++k) {
    const Scan& scan = scans_[active_scan_[k]];
    if (is_inner(scan, active_index_[k] - offsets[active_scan_[k]])) gamma_column_.push_back(static_cast<int>(k));
  }
  const auto count = static_cast<Eigen::Index>(gamma_column_.size());
  const auto scatter = [&](const Eigen::MatrixXd& block) {
    for (Eigen::Index c = 0; c < active; ++c) {
      for (Eigen::Index r = 0; r < active; ++r) matrix(active_index_[r], active_index_[c]) += block(r, c);
    }
  };
  if (count == 0) {
    scatter(full);
    sensitivity_valid_ = false;
    return;
  }
  Vector complement(count), gamma(count);
  for (Eigen::Index c = 0; c < count; ++c) {
    const int k = gamma_column_[c];
    const Scan& scan = scans_[active_scan_[k]];
    complement[c] = std::exp(scan.log_complement[active_index_[k] - offsets[active_scan_[k]]]);
    gamma[c] = scan.gamma;
    // Where 1 − μ_t(j) is small, the association is all but certain and Σ_{:,j} lives on that
    // scale: its cross-scan entries are differences of O(1) sums, noise once divided by 1 − μ.
    // They are dropped there; every entry they touch is itself of order 1 − μ_t(j), so the
    // matrix only loses accuracy in directions whose residuals are that small.
    if (complement[c] >= kSmallComplement) continue;
    for (Eigen::Index l = 0; l < active; ++l) {
      if (active_scan_[l] != active_scan_[k]) full(l, k) = full(k, l) = 0.0;
    }
  }
  Eigen::MatrixXd scaled(active, count);  // S_{:,Γ}
  for (Eigen::Index c = 0; c < count; ++c) scaled.col(c) = full.col(gamma_column_[c]) / complement[c];
  Eigen::MatrixXd inner(count, count);  // I − G S_ΓΓᵀ
  Eigen::MatrixXd transposed(count, count);  // I − S_ΓΓᵀ G
  for (Eigen::Index r = 0; r < count; ++r) {
    for (Eigen::Index c = 0; c < count; ++c) {
      const double s = scaled(gamma_column_[c], r);  // S_ΓΓ(c, r)
      inner(r, c) = (r == c ? 1.0 : 0.0) - gamma[r] * s;
      transposed(r, c) = (r == c ? 1.0 : 0.0) - s * gamma[c];
    }
  }
  const Eigen::MatrixXd right = gamma.asDiagonal() * scaled.transpose();  // G S_{:,Γ}ᵀ
  Eigen::MatrixXd columns(active, count);
  for (Eigen::Index c = 0; c < count; ++c) columns.col(c) = full.col(gamma_column_[c]);
  const Eigen::MatrixXd correction = columns * inner.partialPivLu().solve(right);
  scatter(full + 0.5 * (correction + correction.transpose()));
  // ∂v_Γ/∂σ = diag(1/(1 − μ_Γ)) K_i[Γ, :] = (I − S_ΓΓᵀ G)⁻¹ S_{:,Γ}ᵀ for guess_inner(), on the
  // active columns; rows mapped to the inner unknowns (stacked over the inner scans).
  inner_sensitivity_ = transposed.partialPivLu().solve(Eigen::MatrixXd(scaled.transpose()));
  sensitivity_columns_ = active_index_;
  sensitivity_rows_.assign(static_cast<std::size_t>(count), -1);
  int stacked = 0;
  for (int t : inner_scans_) {
    for (int j = 0; j < scans_[t].measurements; ++j, ++stacked) {
      const int position = active_position_[offsets[t] + j];
      if (position < 0) continue;
      const auto found = std::find(gamma_column_.begin(), gamma_column_.end(), position);
      if (found != gamma_column_.end()) sensitivity_rows_[found - gamma_column_.begin()] = stacked;
    }
  }
  inner_unknowns(inner_base_);
  sensitivity_valid_ = true;
}

void TiltedTrack::add_block_matrix(int t, int offset, Eigen::MatrixXd& matrix) const {
  // Σ_tt = diag(μ) − μμᵀ and, if t is a γ-scan, + Σ_tt (I − γ S_ttᵀ)⁻¹ γ S_ttᵀ, S = Σ diag(1/(1 − μ)).
  const Scan& scan = scans_[t];
  const int m = scan.measurements;
  Eigen::MatrixXd sigma(m, m);
  for (int j = 0; j < m; ++j) {
    sigma(j, j) = std::exp(scan.log_marginal[j + 1] + scan.log_complement[j]);
    for (int l = 0; l < j; ++l) sigma(j, l) = sigma(l, j) = -std::exp(scan.log_marginal[j + 1] + scan.log_marginal[l + 1]);
  }
  if (!(scan.gamma > 0.0)) {
    matrix.block(offset, offset, m, m) += sigma;
    return;
  }
  Eigen::MatrixXd scaled_transposed(m, m);  // S_ttᵀ(j, l) = Σ(l, j) / (1 − μ_j) on the inner unknowns
  for (int j = 0; j < m; ++j) {
    for (int l = 0; l < m; ++l) {
      const bool inner = is_inner(scan, j) && is_inner(scan, l);
      scaled_transposed(j, l) = !inner ? 0.0
                                : l == j ? std::exp(scan.log_marginal[j + 1])
                                         : -std::exp(scan.log_marginal[j + 1] + scan.log_marginal[l + 1] - scan.log_complement[j]);
    }
  }
  const Eigen::MatrixXd inner = Eigen::MatrixXd::Identity(m, m) - scan.gamma * scaled_transposed;
  const Eigen::MatrixXd correction = sigma * inner.partialPivLu().solve(scan.gamma * scaled_transposed);
  matrix.block(offset, offset, m, m) += sigma + 0.5 * (correction + correction.transpose());
}

void TiltedTrack::guess_inner(const Vector& step) {
  if (!sensitivity_valid_) return;
  unknowns_ = inner_base_;
  for (Eigen::Index r = 0; r < inner_sensitivity_.rows(); ++r) {
    if (sensitivity_rows_[r] < 0 || sensitivity_rows_[r] >= unknowns_.size()) continue;
    double change = 0.0;
    for (Eigen::Index c = 0; c < inner_sensitivity_.cols(); ++c) change += inner_sensitivity_(r, c) * step[sensitivity_columns_[c]];
    unknowns_[sensitivity_rows_[r]] = std::min(inner_base_[sensitivity_rows_[r]] + change, 0.0);  // v = log(1 − μ) ≤ 0
  }
  set_inner_unknowns(unknowns_);
}

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
