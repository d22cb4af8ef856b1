#pragma once
// The single-scan data-association problem of Williams & Lau 2014 (bp-marginal-association),
// eqs (9)-(11): n targets, m measurements, p(a,b) ∝ Π_i ψ_i(a_i) over consistent events, with
// ψ_i(0) = 1 and ψ_i(j) ≥ 0 the likelihood ratio of eq (11); ψ_i(j) = 0 means "not gated".
//
// The general form used by the fractional free energy (multiscan-convex-variational, eq 79)
// weights a missed detection by w_i0 and an unused measurement by w_0j. Both default to 1;
// any problem can be brought to the ψ_i(0) = 1 form by ψ_i(j) = w_ij / (w_i0 · w_0j), which
// leaves the posterior over association events unchanged (see normalized_weight()).
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "harness/core/matrix_types.hpp"
#include "harness/core/random_stream.hpp"

namespace dabench {

// Model constants some algorithms need besides ψ (e.g. LMIPDA needs Pd). NaN = unknown.
struct ScanContext {
  double pd = std::numeric_limits<double>::quiet_NaN();         // detection probability
  double lambda_fa = std::numeric_limits<double>::quiet_NaN();  // false-alarm density
};

struct SingleScanProblem {
  RowMatrix psi;           // n×m, ψ_i(j) (or w_ij when miss/clutter weights are not 1)
  Vector miss_weight;      // size n (w_i0) or empty = all ones
  Vector clutter_weight;   // size m (w_0j) or empty = all ones
  ScanContext context;
  TrialKey trial_key;

  int targets() const { return static_cast<int>(psi.rows()); }
  int measurements() const { return static_cast<int>(psi.cols()); }
  bool has_unit_side_weights() const { return miss_weight.size() == 0 && clutter_weight.size() == 0; }

  // A target that cannot be missed (w_i0 = 0: Pd = 1, as the Tracker Component Library and
  // Stone Soup allow): every event with positive weight assigns it a measurement.
  bool must_detect(int i) const { return miss_weight.size() != 0 && miss_weight[i] == 0.0; }
  bool has_must_detect_targets() const { return miss_weight.size() != 0 && (miss_weight.array() == 0.0).any(); }

  // ψ_i(j) in the ψ_i(0) = 1 normalisation of eq (9); for a target that must be detected the
  // row is left unscaled by its (zero) miss weight, its ψ_i(0) being 0 instead (scaling such a
  // row by any positive factor leaves the posterior unchanged, as every event takes one entry).
  double normalized_weight(int i, int j) const {
    double w = psi(i, j);
    if (miss_weight.size() != 0 && miss_weight[i] != 0.0) w /= miss_weight[i];
    if (clutter_weight.size() != 0) w /= clutter_weight[j];
    return w;
  }

  // max over targets and measurements of 1 + Σ ψ along the row or column (normalised weights):
  // an approximation whose message sums can overflow refuses (skipped:numerical) from
  // kOutOfRangeSum on (ψ near 1e308), since an overflowed sum gives wrong beliefs, not NaN.
  double largest_weight_sum() const;
  static constexpr double kOutOfRangeSum = 0x1p1020;

  // Empty if the problem is well formed, else what is wrong (negative, NaN or infinite
  // weights, side-weight vectors of the wrong size, a negative missed-detection weight, a
  // clutter weight that is not strictly positive).
  std::string validate() const;
};

}  // namespace dabench
