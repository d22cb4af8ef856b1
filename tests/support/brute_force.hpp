#pragma once
// Test oracle for single-scan marginals, written to be obviously correct rather than fast:
// it visits EVERY tuple a = (a_1, ..., a_n) in {0, ..., m}^n (an odometer over (m+1)^n
// tuples), keeps those whose nonzero entries are distinct (the consistent events of eqs 9-10
// of Williams & Lau 2014), and weights each by the general form of single_scan_problem.hpp:
//
//   w(a) = Π_i w(i, a_i) · Π_{j unused by a} w_0j,   w(i, 0) = w_i0 (miss weight, default 1),
//                                                     w(i, j) = psi(i, j-1) for j > 0,
//                                                     w_0j = clutter weight (default 1).
//
// Marginals p(a_i = j) = Σ_{a: a_i = j} w(a) / Z, Z = Σ_a w(a) (eq 12). No gating graph, no
// clusters, no normalisation tricks: nothing shared with the algorithms under test.
//
// Also: a random problem generator on a fixed RandomStream, and small comparison helpers.
#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <vector>

#include "harness/core/marginal_table.hpp"
#include "harness/core/matrix_types.hpp"
#include "harness/core/random_stream.hpp"
#include "harness/single_scan/problem.hpp"
#include "harness/single_scan/solver.hpp"

namespace dabench::test {

struct BruteForceResult {
  RowMatrix marginals;          // n×(m+1), column 0 = missed detection
  double partition = 0.0;       // Z = Σ over consistent events of w(a)
  std::int64_t events = 0;      // consistent events visited (including zero-weight ones)
  std::int64_t positive_events = 0;  // consistent events with w(a) > 0
};

inline double miss_weight_of(const SingleScanProblem& problem, int i) {
  return problem.miss_weight.size() == 0 ? 1.0 : problem.miss_weight[i];
}
inline double clutter_weight_of(const SingleScanProblem& problem, int j) {
  return problem.clutter_weight.size() == 0 ? 1.0 : problem.clutter_weight[j];
}

// Exhaustive enumeration; intended for n, m <= 7 ((m+1)^n <= 8^7 ≈ 2.1e6 tuples).
inline BruteForceResult brute_force_marginals(const SingleScanProblem& problem) {
  const int n = problem.targets();
  const int m = problem.measurements();
  assert(std::pow(double(m + 1), double(n)) <= 5.0e7 && "brute force: problem too large");

  BruteForceResult result;
  result.marginals = RowMatrix::Zero(n, m + 1);
  std::vector<int> a(n, 0);  // the current tuple (odometer digits, each in 0..m)
  std::vector<int> uses(m + 1, 0);
  while (true) {
    // Consistency: no measurement j > 0 used by two targets.
    std::fill(uses.begin(), uses.end(), 0);
    bool consistent = true;
    for (int i = 0; i < n; ++i) {
      if (a[i] > 0 && ++uses[a[i]] > 1) consistent = false;
    }
    if (consistent) {
      double weight = 1.0;
      for (int i = 0; i < n; ++i) {
        weight *= a[i] == 0 ? miss_weight_of(problem, i) : problem.psi(i, a[i] - 1);
      }
      for (int j = 1; j <= m; ++j) {
        if (uses[j] == 0) weight *= clutter_weight_of(problem, j - 1);
      }
      ++result.events;
      if (weight > 0.0) ++result.positive_events;
      result.partition += weight;
      for (int i = 0; i < n; ++i) result.marginals(i, a[i]) += weight;
    }
    // Next tuple.
    int digit = 0;
    while (digit < n && a[digit] == m) a[digit++] = 0;
    if (digit == n) break;
    ++a[digit];
  }
  if (n > 0) result.marginals /= result.partition;
  return result;
}

// ---------------------------------------------------------------------------------------------
// Random problems (fixed RandomStream ⇒ the same problems on every platform).

enum class Density {
  dense,    // every ψ_i(j) = exp(U(-3, 3)) ∈ (0.05, 20)
  sparse,   // as dense, but each weight is zero with probability 1/2
  extreme,  // as sparse, and each nonzero weight is 1e6 w.p. 0.1 or 1e-8 w.p. 0.1
};

inline const char* density_name(Density density) {
  switch (density) {
    case Density::dense: return "dense";
    case Density::sparse: return "sparse";
    case Density::extreme: return "extreme";
  }
  return "?";
}

inline int uniform_int(RandomStream& rng, int lo, int hi) {  // inclusive
  return lo + static_cast<int>(rng.uniform() * (hi - lo + 1));
}

inline SingleScanProblem random_problem(RandomStream& rng, int n, int m, Density density,
                                        bool side_weights = false) {
  SingleScanProblem problem;
  problem.psi = RowMatrix::Zero(n, m);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) {
      double w = std::exp(rng.uniform(-3.0, 3.0));
      if (density != Density::dense && rng.bernoulli(0.5)) w = 0.0;
      if (density == Density::extreme && w > 0.0) {
        const double u = rng.uniform();
        if (u < 0.1) w = 1e6;
        else if (u < 0.2) w = 1e-8;
      }
      problem.psi(i, j) = w;
    }
  }
  if (side_weights) {
    problem.miss_weight = Vector(n);
    for (int i = 0; i < n; ++i) problem.miss_weight[i] = std::exp(rng.uniform(-2.0, 2.0));
    problem.clutter_weight = Vector(m);
    for (int j = 0; j < m; ++j) problem.clutter_weight[j] = std::exp(rng.uniform(-2.0, 2.0));
  }
  return problem;
}

// An n × m problem whose pairs are gated with probability `gated`, each with ψ exponentially
// distributed of mean 3.
inline SingleScanProblem gated_exponential_problem(RandomStream& rng, int n, int m, double gated) {
  SingleScanProblem problem;
  problem.psi = RowMatrix::Zero(n, m);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) {
      if (rng.uniform() < gated) problem.psi(i, j) = -3.0 * std::log(1.0 - rng.uniform());
    }
  }
  return problem;
}

// The density of trial `trial` of the solvers' random sweeps: dense, sparse, extreme in turn.
inline Density cycled_density(int trial) {
  constexpr Density densities[] = {Density::dense, Density::sparse, Density::extreme};
  return densities[trial % 3];
}

// Trial `trial` of the solvers' sweeps against the oracles: n, then m, uniform in 0..largest
// (drawn from `rng` before the problem), cycled_density(trial), and side weights in the first
// of every three triples of trials.
struct SweepTrial {
  int n = 0;
  int m = 0;
  Density density = Density::dense;
  bool side = false;
  SingleScanProblem problem;
};

inline SweepTrial sweep_trial(RandomStream& rng, int trial, int largest) {
  SweepTrial t;
  t.n = uniform_int(rng, 0, largest);
  t.m = uniform_int(rng, 0, largest);
  t.density = cycled_density(trial);
  t.side = (trial / 3) % 3 == 0;
  t.problem = random_problem(rng, t.n, t.m, t.density, t.side);
  return t;
}

// A problem given by ψ alone (every miss and clutter weight 1).
inline SingleScanProblem make_problem(const RowMatrix& psi) {
  SingleScanProblem problem;
  problem.psi = psi;
  return problem;
}

// The 2 × 2 case computed by hand in test_exact.cpp: ψ = [[1, 2], [3, 4]], Z = 21.
inline RowMatrix psi_2x2() {
  RowMatrix psi(2, 2);
  psi << 1, 2, 3, 4;
  return psi;
}

// psi_2x2()'s exact marginals (column 0: missed): p_1 = [8, 5, 8]/21, p_2 = [4, 9, 8]/21.
inline RowMatrix marginals_2x2() {
  RowMatrix marginals(2, 3);
  marginals << 8, 5, 8, 4, 9, 8;
  marginals /= 21.0;
  return marginals;
}

// A random permutation of 0..size-1 (Fisher-Yates on the given stream).
inline std::vector<int> random_permutation(RandomStream& rng, int size) {
  std::vector<int> perm(size);
  std::iota(perm.begin(), perm.end(), 0);
  for (int k = size - 1; k > 0; --k) std::swap(perm[k], perm[uniform_int(rng, 0, k)]);
  return perm;
}

// Same problem with target i' = row_perm[i] and measurement j' = col_perm[j]:
// permuted.psi(row_perm[i], col_perm[j]) = problem.psi(i, j).
inline SingleScanProblem permute_problem(const SingleScanProblem& problem, const std::vector<int>& row_perm,
                                         const std::vector<int>& col_perm) {
  SingleScanProblem out = problem;
  for (int i = 0; i < problem.targets(); ++i) {
    for (int j = 0; j < problem.measurements(); ++j) out.psi(row_perm[i], col_perm[j]) = problem.psi(i, j);
  }
  for (int i = 0; i < problem.miss_weight.size(); ++i) out.miss_weight[row_perm[i]] = problem.miss_weight[i];
  for (int j = 0; j < problem.clutter_weight.size(); ++j) out.clutter_weight[col_perm[j]] = problem.clutter_weight[j];
  return out;
}

// Marginals of permute_problem(problem, row_perm, col_perm) put back in `problem`'s order: row i,
// column j + 1 of the result is row row_perm[i], column col_perm[j] + 1 of `permuted`.
inline RowMatrix unpermute_marginals(const RowMatrix& permuted, const std::vector<int>& row_perm,
                                     const std::vector<int>& col_perm) {
  const int n = static_cast<int>(row_perm.size()), m = static_cast<int>(col_perm.size());
  RowMatrix out(n, m + 1);
  for (int i = 0; i < n; ++i) {
    out(i, 0) = permuted(row_perm[i], 0);
    for (int j = 0; j < m; ++j) out(i, j + 1) = permuted(row_perm[i], col_perm[j] + 1);
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Running solvers and comparing tables.

struct SolveResult {
  RowMatrix marginals;
  SolveReport report;
};

inline RowMatrix to_matrix(const MarginalTable& table) { return RowMatrix(table.view()); }

inline SolveResult run_solver(SingleScanSolver& solver, const SingleScanProblem& problem) {
  MarginalTable table;
  SolveResult result;
  solver.solve(problem, table, result.report);
  if (result.report.skipped.empty()) result.marginals = to_matrix(table);
  return result;
}

// Largest |a - b| / (rel_scale·|b| + abs_floor) over entries; <= 1 means "close". Returns
// +inf on a shape mismatch or a non-finite entry.
inline double scaled_error(const RowMatrix& a, const RowMatrix& b, double relative, double absolute) {
  if (a.rows() != b.rows() || a.cols() != b.cols()) return std::numeric_limits<double>::infinity();
  double worst = 0.0;
  for (Eigen::Index i = 0; i < a.rows(); ++i) {
    for (Eigen::Index j = 0; j < a.cols(); ++j) {
      if (!std::isfinite(a(i, j))) return std::numeric_limits<double>::infinity();
      worst = std::max(worst, std::fabs(a(i, j) - b(i, j)) / (relative * std::fabs(b(i, j)) + absolute));
    }
  }
  return worst;
}

inline double max_abs_difference(const RowMatrix& a, const RowMatrix& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols()) return std::numeric_limits<double>::infinity();
  if (a.size() == 0) return 0.0;
  if (!a.allFinite() || !b.allFinite()) return std::numeric_limits<double>::infinity();
  return (a - b).cwiseAbs().maxCoeff();
}

}  // namespace dabench::test
