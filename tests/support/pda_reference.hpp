#pragma once
// Closed forms shared by the tests of the PDA-like approximations (lmipda, baa): single-target
// PDA marginals and random problems whose gates are disjoint (each measurement gated by at most
// one target), where the exact marginals are PDA per target.
#include <cmath>

#include "harness/core/matrix_types.hpp"
#include "harness/core/random_stream.hpp"
#include "harness/single_scan/problem.hpp"

namespace dabench::test {

// PDA for every row on its own, in the ψ_i(0) = 1 normalisation (side weights applied):
// p_i0 = 1/(1 + Σ_j ψ_ij), p_ij = ψ_ij/(1 + Σ_j ψ_ij).
inline RowMatrix pda_marginals(const SingleScanProblem& problem) {
  const int n = problem.targets();
  const int m = problem.measurements();
  RowMatrix p = RowMatrix::Zero(n, m + 1);
  for (int i = 0; i < n; ++i) {
    double total = 1.0;
    for (int j = 0; j < m; ++j) total += problem.normalized_weight(i, j);
    p(i, 0) = 1.0 / total;
    for (int j = 0; j < m; ++j) p(i, j + 1) = problem.normalized_weight(i, j) / total;
  }
  return p;
}

// n targets, m measurements; each measurement belongs to one target chosen uniformly, or to none
// with probability 1/(n+1); ψ = exp(U(-3, 3)) on owned pairs, 0 elsewhere.
inline SingleScanProblem disjoint_problem(RandomStream& rng, int n, int m) {
  SingleScanProblem problem;
  problem.psi = RowMatrix::Zero(n, m);
  for (int j = 0; j < m; ++j) {
    const int owner = static_cast<int>(rng.uniform() * (n + 1)) - 1;  // -1 = nobody
    if (owner >= 0) problem.psi(owner, j) = std::exp(rng.uniform(-3.0, 3.0));
  }
  return problem;
}

}  // namespace dabench::test
