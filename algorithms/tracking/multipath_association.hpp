#pragma once
// Module 3 of JDT-VB (jdt-vb-multipath-othr, Sec. III-D and Appendix E): the marginals E[a] of
// the multipath association variables a^{i,j,τ} (target i, measurement j, propagation path τ) of
// one scan by loopy BP on the factor graph of eq (44), given the evidence χ of eq (43).
//
// Reading of equation group (3). As printed it uses equalities; the text means "at most one":
//  (3a) a measurement has at most one source: Σ_{i,τ} a^{i,j,τ} + a^{0,j} = 1 for every j. This
//       is one column factor per measurement over every (target, path). (With a per-(j, τ)
//       equality that shares one clutter variable a^{0,j}, a measurement that is not clutter
//       would need a source on every path.)
//  (3b) a (target, path) yields at most one measurement: Σ_{j≥1} a^{i,j,τ} + a^{i,0,τ} = 1, with
//       the missed-detection variable a^{i,0,τ} as the slack;
//  (3c) a (target, measurement) pair uses at most one path: Σ_τ a^{i,j,τ} ≤ 1.
// Under (3a), (3c) is implied. The feasible events are then exactly those of the pseudo-target
// reduction: each (target, path) is a pseudo-target of a single-scan problem (eqs 9-10 of the
// BP paper) with weights e^{χ^{i,j,τ}}, miss weight e^{χ^{i,0,τ}} and clutter weight e^{χ^{0,j}}.
// So the page factor of (44) is redundant. It is kept as an option (`page_factor`) and is off by
// default: each page factor shares two variables with a column factor (a 2-cycle), so in LBP it
// only counts again an exclusion the column factor already enforces.
//
// Messages are kept as log ratios (a binary message µ as r = log µ(1)/µ(0)), with ν the
// variable-to-factor log ratios of eqs (51)-(53), e.g. ν^R = χ + r^C + r^P:
//   row, eq (48):    r^R_{ijτ} = −log(e^{χ^{i,0,τ}} + Σ_{j'≠j} e^{ν^R_{ij'τ}})
//   column, eq (49): r^C_{ijτ} = −log(e^{χ^{0,j}} + Σ_{(i',τ')≠(i,τ)} e^{ν^C_{i'jτ'}})
//   page, eq (50) read as "at most one": r^P_{ijτ} = −log(1 + Σ_{τ'≠τ} e^{ν^P_{ijτ'}})
//   beliefs, eqs (54)-(55): E[a^{i,j,τ}] = 1 / (1 + e^{−(χ + r^R + r^C + r^P)}); E[a^{i,0,τ}] and
//   E[a^{0,j}] the same way from their one constraint factor.
// The log domain keeps evidence spread over thousands of nats exact (ratios would overflow).
// Each log-sum-exp is taken about its largest term; leaving out a term other than the largest
// leaves that term's 1 in the sum, so nothing cancels, and the sum without the largest term is
// taken about the second largest. With finite χ^{i,0,τ} and χ^{0,j} every message is finite.
// Schedule: all row messages, then all column messages (then all page messages), per iteration.
// Without page factors this is the row/column iteration of the BP paper's Fig. 3 on the
// pseudo-target problem, whose convergence that paper proves. The paper's Module 3 instead
// updates every ν and then every µ.
// Stopping: the largest change of any r in an iteration is below `tolerance`.
#include <string>
#include <vector>

#include "harness/core/matrix_types.hpp"

namespace dabench {

// The evidence χ of eq (43) for one scan. Pseudo-target p = i·paths + τ.
struct MultipathEvidence {
  int targets = 0;
  int paths = 0;
  RowMatrix detection;  // (targets·paths) × measurements: χ^{i,j,τ}; −∞ = gated out (weight 0)
  Vector miss;          // targets·paths: χ^{i,0,τ} (finite)
  Vector clutter;       // measurements: χ^{0,j} (finite)

  int pseudo_targets() const { return targets * paths; }
  int measurements() const { return static_cast<int>(detection.cols()); }
  std::string validate() const;  // "" if the sizes agree and every χ is allowed
};

struct MultipathAssociationOptions {
  double tolerance = 1e-9;   // stop when no message ratio changes by more than this (log units)
  int max_iterations = 1000; // iteration cap (converged = false when reached)
  bool page_factor = false;  // include the page factors (3c) of eq (44); redundant under (3a)

  std::string validate() const;
};

// E[a] of one scan (eq 55).
struct MultipathAssociation {
  RowMatrix detection;  // (targets·paths) × measurements: E[a^{i,j,τ}]
  Vector miss;          // targets·paths: E[a^{i,0,τ}]
  Vector clutter;       // measurements: E[a^{0,j}]
  int iterations = 0;
  bool converged = false;
};

// Loopy BP for Module 3 over the gated pairs only (χ > −∞): a pair outside the gate has belief
// 0 and its messages influence nothing. One object per thread; buffers are reused between scans,
// so a run's scans allocate only when a scan is larger than any before.
class MultipathAssociationBp {
 public:
  // Throws InputError if the evidence or the options are invalid.
  void solve(const MultipathEvidence& evidence, const MultipathAssociationOptions& options,
             MultipathAssociation& result);

 private:
  // The variables of one factor: pairs[first, last) of a factor index.
  struct FactorIndex {
    std::vector<int> start;  // factors + 1 offsets into pairs
    std::vector<int> pairs;  // pair (edge) numbers
  };
  enum class Kind { row, column, page };

  void build_graph(const MultipathEvidence& evidence, bool page_factor);
  double update(Kind kind, const FactorIndex& index, const double* slack);

  std::vector<int> pair_row_, pair_column_;  // gated pairs in row-major order
  std::vector<double> pair_chi_;             // χ of each pair
  FactorIndex rows_, columns_, pages_;       // pages_: one target's paths to one measurement (≥ 2)
  std::vector<double> row_message_, column_message_, page_message_;  // r^R, r^C, r^P per pair
  std::vector<double> values_, terms_;       // scratch of one factor: ν, and e^{ν − largest}
  std::vector<int> next_slot_;               // scratch of the column counting sort
};

}  // namespace dabench
