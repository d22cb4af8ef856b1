#include "algorithms/tbd/cell_messages.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>

#include "harness/core/grow_buffer.hpp"
#include "harness/core/portable_exp.hpp"
#include "harness/core/special_values.hpp"

namespace dabench {

namespace {

// log(exp(extra) + Σ exp(values[i])); NaN if any value is NaN (a non-finite message or frame
// must not read as an impossible PO).
double log_sum_exp(const std::vector<double>& values, int count, double extra) {
  double top = extra;
  for (int i = 0; i < count; ++i) {
    if (std::isnan(values[i])) return std::numeric_limits<double>::quiet_NaN();
    top = std::max(top, values[i]);
  }
  if (top == kMinusInfinity) return kMinusInfinity;
  double sum = std::exp(extra - top);
  for (int i = 0; i < count; ++i) sum += std::exp(values[i] - top);
  return top + std::log(sum);
}

// log N(z; μ, s I₂) in R².
double log_isotropic_normal(double dx, double dy, double s) {
  return -std::log(2.0 * std::numbers::pi * s) - 0.5 * (dx * dx + dy * dy) / s;
}

// One window cell's λ for every particle: the loops the passes spend their time in, written so
// that they vectorise (no calls, no branches; portable_exp). Each adds −½(quad − quad0) to
// total[i] and multiplies det/det0 into product[i]; with kOwn it also stores
// own[i] = exp(−λ) = sqrt(det/det0) exp(½(quad − quad0)).
template <bool kOwn>
void cell_log_ratios(const CellMessages::CellTerms& t, const SpreadCoefficients& k, const double* gx, const double* gy,
                     int p, double* total, double* product, double* own) {
  const double e_x = t.e_x, e_y = t.e_y, v_xx = t.v_xx, v_yy = t.v_yy, v_xy = t.v_xy;
  const double det0 = v_xx * v_yy - v_xy * v_xy;
  const double half_quad0 = 0.5 * (e_x * e_x * v_yy - 2.0 * e_x * e_y * v_xy + e_y * e_y * v_xx) / det0;
  const double inverse_det0 = 1.0 / det0;
  const double cross = 2.0 * e_y * v_xy, e_yy = e_y * e_y, v_xy2 = v_xy * v_xy;
  const double mean = k.mean, variance1 = k.variance, variance2 = k.variance2;
#pragma omp simd
  for (int i = 0; i < p; ++i) {
    // κ̃(x, 1): mean + μ_j(x), covariance + c_j(x) I.
    const double g = gx[i] * gy[i];
    const double ex = e_x - mean * g;
    const double extra = (variance1 + variance2 * g) * g;
    const double a = v_xx + extra;
    const double d = v_yy + extra;
    const double det = a * d - v_xy2;
    const double ratio = det * inverse_det0;
    const double half_quad = 0.5 * (ex * ex * d - ex * cross + e_yy * a) / det - half_quad0;
    if constexpr (kOwn) own[i] = std::sqrt(ratio) * portable_exp(half_quad);
    product[i] *= ratio;
    total[i] -= half_quad;
  }
}

// The same where μ_j ≡ 0 and V = v I₂ (the fluctuating signal D1: then V stays isotropic, as
// every C_j is): with s = (v + c_j(x))/v, det/det0 = s², quad = ‖e‖²/(v + c_j(x)), and
// sqrt(det/det0) = s needs no square root.
template <bool kOwn>
void isotropic_cell_log_ratios(const CellMessages::CellTerms& t, const SpreadCoefficients& k, const double* gx,
                               const double* gy, int p, double* total, double* product, double* own) {
  const double v = t.v_xx;
  const double half_ee = 0.5 * (t.e_x * t.e_x + t.e_y * t.e_y);
  const double half_quad0 = half_ee / v;
  const double inverse_v = 1.0 / v;
  const double variance1 = k.variance, variance2 = k.variance2;
#pragma omp simd
  for (int i = 0; i < p; ++i) {
    const double g = gx[i] * gy[i];
    const double a = v + (variance1 + variance2 * g) * g;
    const double s = a * inverse_v;
    const double half_quad = half_ee / a - half_quad0;
    if constexpr (kOwn) own[i] = s * portable_exp(half_quad);
    product[i] *= s * s;
    total[i] -= half_quad;
  }
}

}  // namespace

void CellMessages::configure(const TbdSensor& sensor, double amplitude, double support_radius) {
  sensor_ = &sensor;
  support_radius_ = support_radius;
  const SpreadCoefficients k = sensor.coefficients(amplitude);  // μ_j and c_j as functions of g_j
  mean_per_spread_ = k.mean;
  variance_per_spread_ = k.variance;
  variance_per_spread2_ = k.variance2;
}

bool CellMessages::run(const TbdSensor& sensor, double amplitude, const Eigen::Matrix2Xd& frame,
                       const std::vector<ParticleObject*>& objects, const CellMessageOptions& options) {
  begin(sensor, amplitude, frame, objects, options.support_radius);
  const int count = static_cast<int>(objects.size());
  if (options.exact) {
    exact_lambda_.resize(count);
    for (int n = 0; n < count; ++n) {  // κ^(0) ≡ 1: λ = 0 for the first exact pass
      const std::size_t pairs = static_cast<std::size_t>(work_[n].window.cells()) * objects[n]->size();
      std::fill_n(work_[n].own_factor.begin(), pairs, 1.0);
      exact_lambda_[n].assign(pairs, 0.0);
    }
    std::vector<int> reach(sensor.cells(), 0);
    for (int n = 0; n < count; ++n) {
      const CellWindow& w = work_[n].window;
      for (int row = w.row_begin; row < w.row_end; ++row) {
        for (int column = w.column_begin; column < w.column_end; ++column) {
          if (++reach[row * sensor.columns + column] > 2) return false;
        }
      }
    }
  }
  if (options.serial && !options.exact && options.interaction) {
    start_serial();
    for (int l = 1; l <= options.iterations; ++l) serial_sweep();
    finish_serial();
    return true;
  }
  const bool totals_needed = options.interaction || options.exact;
  for (int l = 1; l <= options.iterations; ++l) {
    // β^(ℓ) moments of every PO, then the per-cell totals, then every PO's λ^(ℓ).
    if (totals_needed) {
      for (int n = 0; n < count; ++n) moments(*objects[n], work_[n], l == 1);
      std::fill(totals_.begin(), totals_.end(), CellTotals{});
      for (int n = 0; n < count; ++n) accumulate(work_[n], 1.0);
    }
    if (options.exact) {
      exact_log_ratios(objects);
    } else {
      for (int n = 0; n < count; ++n) gaussian_log_ratios(*objects[n], work_[n], options.interaction, true);
    }
  }
  for (int n = 0; n < count; ++n) belief(*objects[n], work_[n]);
  outgoing_moments_ready_ = false;
  return true;
}

void CellMessages::begin(const TbdSensor& sensor, double amplitude, const Eigen::Matrix2Xd& frame,
                         const std::vector<ParticleObject*>& objects, double support_radius) {
  configure(sensor, amplitude, support_radius);
  frame_ = &frame;
  outgoing_moments_ready_ = false;
  objects_.assign(objects.begin(), objects.end());
  const int count = static_cast<int>(objects.size());
  if (static_cast<int>(work_.size()) < count) work_.resize(count);
  for (int n = 0; n < count; ++n) prepare(*objects[n], work_[n]);
  totals_.resize(sensor.cells());
}

void CellMessages::start_serial(const TbdSensor& sensor, double amplitude, const Eigen::Matrix2Xd& frame,
                                const std::vector<ParticleObject*>& objects, double support_radius) {
  begin(sensor, amplitude, frame, objects, support_radius);
  start_serial();
}

// Serial schedule: the totals always hold every PO's newest message; PO n takes its own out,
// computes its κ̃ against the others, then puts its new extrinsic β back.
void CellMessages::start_serial() {
  outgoing_moments_ready_ = false;
  std::fill(totals_.begin(), totals_.end(), CellTotals{});
  for (std::size_t n = 0; n < objects_.size(); ++n) {
    moments(*objects_[n], work_[n], true);
    accumulate(work_[n], 1.0);
  }
}

void CellMessages::serial_sweep() {
  for (std::size_t n = 0; n < objects_.size(); ++n) {
    leave_field(work_[n]);
    gaussian_log_ratios(*objects_[n], work_[n], true, true);
    moments(*objects_[n], work_[n], false);
    accumulate(work_[n], 1.0);
  }
}

void CellMessages::finish_serial() {
  for (std::size_t n = 0; n < objects_.size(); ++n) belief(*objects_[n], work_[n]);
  outgoing_moments_ready_ = true;  // each PO's last moments() followed its last λ: β^(L+1)
}

void CellMessages::leave_field(Work& work) {
  accumulate(work, -1.0);
  std::fill(work.terms.begin(), work.terms.end(), CellTerms{});
}

void CellMessages::enter_field(const ParticleObject& object, Work& work) {
  moments(object, work, false);
  accumulate(work, 1.0);
}

void CellMessages::outgoing_field() {
  std::fill(totals_.begin(), totals_.end(), CellTotals{});
  for (std::size_t n = 0; n < objects_.size(); ++n) {
    if (!outgoing_moments_ready_) moments(*objects_[n], work_[n], false);
    accumulate(work_[n], 1.0);
  }
}

double CellMessages::evaluate(const ParticleObject& object, Work& work, bool interaction, bool own_factors) {
  std::fill(work.terms.begin(), work.terms.end(), CellTerms{});  // its own terms: not in the field
  gaussian_log_ratios(object, work, interaction, own_factors);
  belief(object, work);
  return work.log_odds;
}

void CellMessages::add_to_field(const ParticleObject& object, const Work& work) {
  // Belief moments: weights w_i exp(Σ_j λ_ij), existence r̃.
  const int p = object.size();
  const CellWindow& w = work.window;
  const double existence = 1.0 / (1.0 + std::exp(-work.log_odds));
  shifted_.resize(p);
  double top = kMinusInfinity;
  for (int i = 0; i < p; ++i) top = std::max(top, shifted_[i] = std::log(object.weight[i]) + work.total[i]);
  double sum = 0.0;
  for (int i = 0; i < p; ++i) sum += shifted_[i] = std::exp(shifted_[i] - top);
  for (int c = 0; c < w.cells(); ++c) {
    const double* gx = &work.spread_x[static_cast<std::size_t>(c % w.columns()) * p];
    const double* gy = &work.spread_y[static_cast<std::size_t>(c / w.columns()) * p];
    double sum_m = 0.0, sum_c = 0.0, sum_mm = 0.0;
    for (int i = 0; i < p; ++i) {
      const double g = gx[i] * gy[i];
      const double m = mean_per_spread_ * g;
      sum_m += shifted_[i] * m;
      sum_c += shifted_[i] * (variance_per_spread_ + variance_per_spread2_ * g) * g;
      sum_mm += shifted_[i] * m * m;
    }
    const double scale = existence / sum;
    const double mean = scale * sum_m;
    CellTotals& total = totals_[(w.row_begin + c / w.columns()) * sensor_->columns + w.column_begin + c % w.columns()];
    total.mean_x += mean;
    total.v_xx += scale * (sum_c + sum_mm) - mean * mean;
    total.v_yy += scale * sum_c;
  }
}

// g_j(p) = exp(−(c_x − p_x)²/(2σ_h²)) · exp(−(c_y − p_y)²/(2σ_h²)), tabulated per axis over
// work.window.
void CellMessages::tabulate_spread(const ParticleObject& object, Work& work) const {
  const TbdSensor& s = *sensor_;
  const CellWindow& w = work.window;
  const int p = object.size();
  const double scale = -0.5 / s.spread_variance;
  grow_buffer(work.spread_x, static_cast<std::size_t>(w.columns()) * p);
  grow_buffer(work.spread_y, static_cast<std::size_t>(w.rows()) * p);
  for (int c = 0; c < w.columns(); ++c) {
    const double centre = s.centre_x(w.column_begin + c);
    double* g = &work.spread_x[static_cast<std::size_t>(c) * p];
    const double* x = object.x.data();
#pragma omp simd
    for (int i = 0; i < p; ++i) g[i] = portable_exp(scale * (centre - x[i]) * (centre - x[i]));
  }
  for (int r = 0; r < w.rows(); ++r) {
    const double centre = s.centre_y(w.row_begin + r);
    double* g = &work.spread_y[static_cast<std::size_t>(r) * p];
    const double* y = object.y.data();
#pragma omp simd
    for (int i = 0; i < p; ++i) g[i] = portable_exp(scale * (centre - y[i]) * (centre - y[i]));
  }
}

void CellMessages::prepare(const ParticleObject& object, Work& work) const {
  const TbdSensor& s = *sensor_;
  const int p = object.size();
  double x_low = std::numeric_limits<double>::infinity(), x_high = -x_low, y_low = x_low, y_high = -x_low;
  for (int i = 0; i < p; ++i) {
    x_low = std::min(x_low, object.x[i]);
    x_high = std::max(x_high, object.x[i]);
    y_low = std::min(y_low, object.y[i]);
    y_high = std::max(y_high, object.y[i]);
  }
  // Cells whose centre x_min + (c + ½)Δ lies in [low − radius, high + radius].
  const auto first = [&](double low, double origin, int limit) {
    return std::clamp(static_cast<int>(std::ceil((low - support_radius_ - origin) / s.cell_size - 0.5)), 0, limit);
  };
  const auto last = [&](double high, double origin, int limit) {
    return std::clamp(static_cast<int>(std::floor((high + support_radius_ - origin) / s.cell_size - 0.5)) + 1, 0, limit);
  };
  CellWindow& w = work.window;
  w.column_begin = first(x_low, s.x_min, s.columns);
  w.column_end = std::max(w.column_begin, last(x_high, s.x_min, s.columns));
  w.row_begin = first(y_low, s.y_min, s.rows);
  w.row_end = std::max(w.row_begin, last(y_high, s.y_min, s.rows));
  if (p == 0) w.column_end = w.column_begin;

  tabulate_spread(object, work);
  const std::size_t pairs = static_cast<std::size_t>(w.cells()) * p;
  grow_buffer(work.own_factor, pairs);  // filled by the first pass (κ^(0) ≡ 1 before it: ones_)
  work.total.assign(p, 0.0);
  work.terms.assign(w.cells(), CellTerms{});
}

void CellMessages::moments(const ParticleObject& object, Work& work, bool from_prior) {
  const CellWindow& w = work.window;
  const int p = object.size();
  const double r = object.existence;
  // β(x^(i), 1) ∝ w r Π_{j'≠j} κ̃ ratio = B_i · (κ̃(0)/κ̃(x^(i),1) at j), B_i = w r exp(Σ_j λ),
  // against β(0) ∝ 1 − r; one shift for every cell (the own-cell factor is bounded, header).
  // From the prior, own ≡ 1 (κ^(0) ≡ 1) and B_i = w r.
  shifted_.resize(p);
  double shift = 0.0;
  if (from_prior) {
    if (static_cast<int>(ones_.size()) < p) ones_.assign(p, 1.0);
    for (int i = 0; i < p; ++i) shifted_[i] = object.weight[i] * r;
  } else {
    shift = std::log1p(-r);
    for (int i = 0; i < p; ++i) shift = std::max(shift, shifted_[i] = std::log(object.weight[i] * r) + work.total[i]);
    double* b = shifted_.data();
#pragma omp simd
    for (int i = 0; i < p; ++i) b[i] = portable_exp(b[i] - shift);
  }
  const double absent = from_prior ? 1.0 - r : std::exp(std::log1p(-r) - shift);  // b^0, unnormalised
  const double* b = shifted_.data();
  const double mean_per_spread = mean_per_spread_, variance1 = variance_per_spread_, variance2 = variance_per_spread2_;
  for (int c = 0; c < w.cells(); ++c) {
    const double* gx = &work.spread_x[static_cast<std::size_t>(c % w.columns()) * p];
    const double* gy = &work.spread_y[static_cast<std::size_t>(c / w.columns()) * p];
    const double* own = from_prior ? ones_.data() : &work.own_factor[static_cast<std::size_t>(c) * p];
    double mass = absent;
    double sum_m = 0.0, sum_c = 0.0, sum_mm = 0.0;
    if (mean_per_spread == 0.0) {  // μ_j ≡ 0 (D1): only the mass and E c
#pragma omp simd reduction(+ : mass, sum_c)
      for (int i = 0; i < p; ++i) {
        const double weight = b[i] * own[i];
        const double g = gx[i] * gy[i];
        mass += weight;
        sum_c += weight * ((variance1 + variance2 * g) * g);
      }
    } else {
#pragma omp simd reduction(+ : mass, sum_m, sum_c, sum_mm)
      for (int i = 0; i < p; ++i) {
        const double weight = b[i] * own[i];
        const double g = gx[i] * gy[i];
        const double m = mean_per_spread * g;
        const double variance = (variance1 + variance2 * g) * g;
        mass += weight;
        sum_m += weight * m;
        sum_c += weight * variance;
        sum_mm += weight * m * m;
      }
    }
    // μ_j(x) = (m, 0): μ_{n,j} = (E m, 0), R_{n,j} = E[c] I + diag(E m², 0).
    CellTerms& t = work.terms[c];
    t.mean_x = sum_m / mass;
    t.mean_y = 0.0;
    t.r_xx = (sum_c + sum_mm) / mass;
    t.r_xy = 0.0;
    t.r_yy = sum_c / mass;
  }
}

void CellMessages::accumulate(const Work& work, double sign) {
  const CellWindow& w = work.window;
  for (int c = 0; c < w.cells(); ++c) {
    const CellTerms& t = work.terms[c];
    CellTotals& total = totals_[(w.row_begin + c / w.columns()) * sensor_->columns + w.column_begin + c % w.columns()];
    total.mean_x += sign * t.mean_x;
    total.mean_y += sign * t.mean_y;
    total.v_xx += sign * (t.r_xx - t.mean_x * t.mean_x);
    total.v_xy += sign * (t.r_xy - t.mean_x * t.mean_y);
    total.v_yy += sign * (t.r_yy - t.mean_y * t.mean_y);
  }
}

void CellMessages::gaussian_log_ratios(const ParticleObject& object, Work& work, bool interaction, bool own_factors) {
  const TbdSensor& s = *sensor_;
  const CellWindow& w = work.window;
  for (int c = 0; c < w.cells(); ++c) {
    const int cell = (w.row_begin + c / w.columns()) * s.columns + w.column_begin + c % w.columns();
    CellTerms& t = work.terms[c];
    // κ̃(0): e = z − Σ_{n'≠n} μ_{n',j}, V = C_ε + Σ_{n'≠n} (R − μμᵀ)  (eqs 5, 9 with r_n = 0)
    t.e_x = (*frame_)(0, cell);
    t.e_y = (*frame_)(1, cell);
    t.v_xx = t.v_yy = s.noise_variance;
    t.v_xy = 0.0;
    if (interaction) {
      const CellTotals& total = totals_[cell];
      t.e_x -= total.mean_x - t.mean_x;
      t.e_y -= total.mean_y - t.mean_y;
      t.v_xx += total.v_xx - (t.r_xx - t.mean_x * t.mean_x);
      t.v_xy += total.v_xy - (t.r_xy - t.mean_x * t.mean_y);
      t.v_yy += total.v_yy - (t.r_yy - t.mean_y * t.mean_y);
    }
  }
  sum_log_ratios(work.terms, work, object.size(), work.total, own_factors ? work.own_factor.data() : nullptr);
}

void CellMessages::sum_log_ratios(const std::vector<CellTerms>& terms, const Work& spread, int p,
                                  std::vector<double>& total, double* own_factor) {
  const CellWindow& w = spread.window;
  total.assign(p, 0.0);
  // Σ_j λ = −½ Σ_j log(det_j/det0_j) − ½ Σ_j (quad_j − quad0_j). The determinant ratios (each
  // in [1, (1 + c_max/σ²)²], so a window row cannot overflow) are multiplied over the whole
  // window, the product's binary exponent moved into work_exponent_ after every row (exact), and
  // one log taken per particle at the end.
  work_product_.assign(p, 1.0);
  work_exponent_.assign(p, 0);
  const SpreadCoefficients coefficients{mean_per_spread_, variance_per_spread_, variance_per_spread2_};
  double* sum = total.data();
  double* product = work_product_.data();
  std::int64_t* exponent = work_exponent_.data();
  for (int row = 0; row < w.rows(); ++row) {
    for (int column = 0; column < w.columns(); ++column) {
      const int c = row * w.columns() + column;
      const CellTerms& t = terms[c];
      const double* gx = &spread.spread_x[static_cast<std::size_t>(column) * p];
      const double* gy = &spread.spread_y[static_cast<std::size_t>(row) * p];
      double* own = own_factor != nullptr ? own_factor + static_cast<std::size_t>(c) * p : nullptr;
      if (coefficients.mean == 0.0 && t.v_xy == 0.0 && t.v_xx == t.v_yy) {
        (own ? isotropic_cell_log_ratios<true> : isotropic_cell_log_ratios<false>)(t, coefficients, gx, gy, p, sum,
                                                                                    product, own);
      } else {
        (own ? cell_log_ratios<true> : cell_log_ratios<false>)(t, coefficients, gx, gy, p, sum, product, own);
      }
    }
    constexpr std::uint64_t kMantissa = (std::uint64_t{1} << 52) - 1, kOne = std::uint64_t{1023} << 52;
#pragma omp simd
    for (int i = 0; i < p; ++i) {  // product = m · 2^e, m ∈ [1, 2) (product ≈≥ 1: positive, normal)
      const std::uint64_t bits = std::bit_cast<std::uint64_t>(product[i]);
      exponent[i] += static_cast<std::int64_t>(bits >> 52) - 1023;
      product[i] = std::bit_cast<double>((bits & kMantissa) | kOne);
    }
  }
  for (int i = 0; i < p; ++i) {
    sum[i] -= 0.5 * (std::log(product[i]) + std::numbers::ln2 * static_cast<double>(exponent[i]));
  }
}

void CellMessages::log_ratios_at(const Work& work, const ParticleObject& object, std::vector<double>& out) {
  drawn_.window = work.window;
  tabulate_spread(object, drawn_);
  sum_log_ratios(work.terms, drawn_, object.size(), out, nullptr);
}

void CellMessages::exact_log_ratios(const std::vector<ParticleObject*>& objects) {
  const TbdSensor& s = *sensor_;
  const int count = static_cast<int>(objects.size());
  const double noise = s.noise_variance;
  // Which PO reaches each cell besides n (at most one other: checked in run()).
  std::vector<int> first(s.cells(), -1), second(s.cells(), -1);
  std::vector<int> slot_first(s.cells(), -1), slot_second(s.cells(), -1);
  for (int n = 0; n < count; ++n) {
    const CellWindow& w = work_[n].window;
    for (int c = 0; c < w.cells(); ++c) {
      const int cell = (w.row_begin + c / w.columns()) * s.columns + w.column_begin + c % w.columns();
      if (first[cell] < 0) {
        first[cell] = n;
        slot_first[cell] = c;
      } else {
        second[cell] = n;
        slot_second[cell] = c;
      }
    }
  }
  // The other PO's β_{n',j} log weights (normalised, absent last), from its current λ.
  std::vector<double> log_other_weight, other_mean, other_variance, terms;
  const auto extrinsic = [&](int m, int c) {
    const ParticleObject& other = *objects[m];
    const Work& work = work_[m];
    const int p = other.size();
    log_other_weight.resize(p + 1);
    // log of w r exp(Σ_{j'≠j} λ) from λ itself: exp(−λ) (own_factor) underflows once λ > 745.
    const double* lambda = &exact_lambda_[m][static_cast<std::size_t>(c) * p];
    const double log_existence = std::log(other.existence);
    for (int i = 0; i < p; ++i) log_other_weight[i] = std::log(other.weight[i]) + log_existence + work.total[i] - lambda[i];
    log_other_weight[p] = std::log1p(-other.existence);
    const double log_norm = log_sum_exp(log_other_weight, p + 1, kMinusInfinity);
    for (double& v : log_other_weight) v -= log_norm;
  };
  std::vector<std::vector<double>> next(count);
  for (int n = 0; n < count; ++n) next[n].assign(work_[n].own_factor.size(), 0.0);
  for (int n = 0; n < count; ++n) {
    const ParticleObject& object = *objects[n];
    const Work& work = work_[n];
    const CellWindow& w = work.window;
    const int p = object.size();
    for (int c = 0; c < w.cells(); ++c) {
      const int column = w.column_begin + c % w.columns();
      const int row = w.row_begin + c / w.columns();
      const int cell = row * s.columns + column;
      const double zx = (*frame_)(0, cell), zy = (*frame_)(1, cell);
      const int other = first[cell] == n ? second[cell] : first[cell];
      const int other_slot = first[cell] == n ? slot_second[cell] : slot_first[cell];
      const ParticleObject* o = other >= 0 ? objects[other] : nullptr;
      const int q = o != nullptr ? o->size() : 0;
      if (o != nullptr) {
        extrinsic(other, other_slot);
        other_mean.resize(q);
        other_variance.resize(q);
        for (int i = 0; i < q; ++i) {
          const double g = s.spread(column, row, o->x[i], o->y[i]);
          other_mean[i] = mean_per_spread_ * g;
          other_variance[i] = (variance_per_spread_ + variance_per_spread2_ * g) * g;
        }
      }
      // log κ(0) and log κ(x, 1) as log-sums over the other PO's states (letter eq (5)); in the
      // log domain, since a bright cell's Gaussians underflow at small variances.
      terms.resize(q + 1);
      const auto log_kappa = [&](double m, double variance) {
        terms[q] = (o != nullptr ? log_other_weight[q] : 0.0) + log_isotropic_normal(zx - m, zy, noise + variance);
        for (int i = 0; i < q; ++i) {
          terms[i] = log_other_weight[i] +
                     log_isotropic_normal(zx - m - other_mean[i], zy, noise + variance + other_variance[i]);
        }
        return log_sum_exp(terms, q, terms[q]);
      };
      const double absent = log_kappa(0.0, 0.0);
      const double* gx = &work.spread_x[static_cast<std::size_t>(c % w.columns()) * p];
      const double* gy = &work.spread_y[static_cast<std::size_t>(c / w.columns()) * p];
      double* lambda = &next[n][static_cast<std::size_t>(c) * p];  // λ here, exp(−λ) below
      for (int i = 0; i < p; ++i) {
        const double g = gx[i] * gy[i];
        lambda[i] = log_kappa(mean_per_spread_ * g, (variance_per_spread_ + variance_per_spread2_ * g) * g) - absent;
      }
    }
  }
  for (int n = 0; n < count; ++n) {
    Work& work = work_[n];
    const int p = objects[n]->size();
    std::fill(work.total.begin(), work.total.end(), 0.0);
    for (int c = 0; c < work.window.cells(); ++c) {
      for (int i = 0; i < p; ++i) {
        const double lambda = next[n][static_cast<std::size_t>(c) * p + i];
        work.total[i] += lambda;
        work.own_factor[static_cast<std::size_t>(c) * p + i] = std::exp(-lambda);
      }
    }
  }
  exact_lambda_.swap(next);
}

void CellMessages::belief(const ParticleObject& object, Work& work) {
  const int p = object.size();
  // r̃/(1 − r̃) = r Σ_i w_i exp(Λ_i) / (1 − r)
  shifted_.resize(p);
  for (int i = 0; i < p; ++i) shifted_[i] = std::log(object.weight[i]) + work.total[i];
  work.log_odds = std::log(object.existence) - std::log1p(-object.existence) + log_sum_exp(shifted_, p, kMinusInfinity);
}

}  // namespace dabench
