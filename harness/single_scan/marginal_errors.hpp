#pragma once
// Marginal error of bp-marginal-association Sec. V: for each target the largest absolute
// difference between estimated and reference marginals over j = 0..m; `max_error` averages
// that over targets. `mean_error` is the mean absolute difference over all n·(m+1) entries.
#include "harness/core/marginal_table.hpp"

namespace dabench {

struct MarginalErrors {
  double max_error = 0.0;
  double mean_error = 0.0;
};

// Both tables must have the same shape and at least one target.
MarginalErrors marginal_errors(const MarginalTable& estimate, const MarginalTable& reference);

}  // namespace dabench
