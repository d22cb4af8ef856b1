#pragma once
// The multiple-scan association problem of Williams & Lau, "Multiple scan data association by
// convex variational inference" (multiscan-convex-variational), Sec. II–III: n tracks, each a
// set of single-target hypotheses (or particles) A^i with vertex factor ψ^i(A^i), and scans
// t' ∈ S, each with m_t' measurements and edge factors ψ^i_t'(A^i, a^i_t') — for particles,
// eq (33): 1 − Pd(x) for a = 0 and f(z_j | x) Pd(x) / λ_fa(z_j) for a = j > 0.
// The feasible global hypotheses are those in which no two tracks use the same measurement
// of the same scan (eq 1); their probability is ∝ Π_i ψ^i(A^i) Π_t' ψ^i_t'(A^i, a^i_t').
#include <string>
#include <vector>

#include "harness/core/marginal_table.hpp"
#include "harness/core/matrix_types.hpp"

namespace dabench {

// One scan t': the factors ψ^i_t'(A^i, a) of every track, in arrival order within the problem.
struct ScanFactors {
  int measurements = 0;           // m_t'
  std::vector<RowMatrix> factor;  // per track i: H_i × (m_t' + 1), column 0 = missed detection
};

struct MultiScanProblem {
  std::vector<Vector> prior;      // per track i: ψ^i(A^i) ≥ 0 over its H_i hypotheses/particles
  std::vector<ScanFactors> scans; // S, in the order the scans arrive (sequential methods use it)

  int tracks() const { return static_cast<int>(prior.size()); }
  int hypotheses(int track) const { return static_cast<int>(prior[track].size()); }
  int scan_count() const { return static_cast<int>(scans.size()); }

  // Empty if well formed, else what is wrong: factor shapes that do not match the tracks'
  // hypothesis counts or the scan's measurement count, negative or non-finite factors, a
  // track whose prior is all zero.
  std::string validate() const;
};

// Beliefs over the problem's variables after all scans have been processed.
struct MultiScanBeliefs {
  std::vector<Vector> track;                // q^i(A^i), each summing to 1
  std::vector<MarginalTable> association;   // per scan t': q^{i,j}_t', n × (m_t' + 1)
};

}  // namespace dabench
