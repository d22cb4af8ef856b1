#pragma once
// The weight matrices other tracking code hands to a data-association solver, brought to
// dabench's ψ form (eq 11 of bp-marginal-association: n × m, ψ_i(0) = 1 implied). Every layout
// scales a target's or a measurement's weights by a common factor relative to ψ; dividing it out,
// ψ_i(j) = w_ij / (w_i0 · w_0j), leaves the posterior over association events unchanged.
//   psi        n × m       ψ_i(j) as is.
//   stonesoup  n × (m+1)   Stone Soup's and pyehm's likelihood matrix: column 0 the missed
//                          detection w_i0, then w_ij (unnormalised).
//   tcl        n × (m+n)   the Tracker Component Library's: w_ij in the first m columns, then a
//                          diagonal block holding w_i0 at column m+i; its off-diagonal entries are 0.
//   matlab     (m+1) × (n+1)  MATLAB's jpdaEvents likelihood matrix: rows are measurements, columns
//                          tracks; row 0 holds the tracks' missed detections w_i0, column 0 the
//                          measurements' clutter w_0j, entry (0, 0) is ignored.
// With `log`, entries are natural logarithms of the weights (−inf for a weight of 0).
// A missed-detection weight of 0 (Pd = 1: the Tracker Component Library and Stone Soup accept
// it) makes the target one that must be detected (SingleScanProblem::must_detect): its row is
// kept at the user's scale with w_i0 = 0, and only the exact methods that enumerate events take
// such a problem (the others report skipped:zero_miss_weight). A clutter weight of 0 is refused.
//
// What a layout means for the approximations: dividing out w_i0 and w_0j leaves the posterior
// over events, so every exact method's marginals are the same in any layout. An approximation
// is defined on ψ = w_ij / (w_i0 · w_0j) with ψ_i(0) = 1 (eq 9), so it too sees one problem
// whatever the layout — but not always the problem another library's approximation of the same
// name sees: a method whose formula uses the raw w_i0 (the TCL's and Stone Soup's cheap JPDA,
// for instance, normalise by the missed-detection entries as given) gives other numbers when
// the w_i0 differ between targets, by construction, not by error.
#include <string>
#include <string_view>

#include "harness/core/matrix_types.hpp"
#include "harness/single_scan/problem.hpp"

namespace dabench {

enum class WeightsLayout { psi, stonesoup, tcl, matlab };

struct WeightsFormat {
  WeightsLayout layout = WeightsLayout::psi;
  bool log = false;  // entries are log weights
};

// "psi", "stonesoup", "tcl" or "matlab"; InputError naming the choices otherwise.
WeightsLayout parse_weights_layout(std::string_view name);
const char* weights_layout_name(WeightsLayout layout);
// The layout's shape in words, e.g. "n x (m+1)" for stonesoup.
const char* weights_layout_shape(WeightsLayout layout);

// The ψ problem of `matrix` read in `format`. InputError "WHERE:ROW: column C: reason" (1-based
// positions in `matrix`) for a NaN, infinite (+inf in log form) or negative entry, a clutter
// weight of 0, a non-zero off-diagonal entry of tcl's block, a shape the layout cannot have, or
// a ψ that overflows.
// `matrix` may map the caller's memory (e.g. a numpy array): it is read, not copied.
SingleScanProblem problem_from_weights(const Eigen::Ref<const RowMatrix>& matrix, const WeightsFormat& format,
                                       const std::string& where);

}  // namespace dabench
