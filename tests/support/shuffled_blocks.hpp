#pragma once
// Block-diagonal single-scan problems for the solvers' cluster tests (test_ehm, test_jt):
// independent random blocks whose targets and measurements are shuffled together, and the check
// that a solver gives each block its own brute-force marginals.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "harness/core/matrix_types.hpp"
#include "harness/core/random_stream.hpp"
#include "harness/single_scan/problem.hpp"
#include "tests/support/brute_force.hpp"

namespace dabench::test {

// `parts` on the diagonal of one problem, shuffled by permute_problem(·, rows, cols).
struct ShuffledBlocks {
  std::vector<SingleScanProblem> parts;
  std::vector<int> rows, cols;
  SingleScanProblem shuffled;
};

// `blocks` random size × size problems (block b of density density_of(b)), then the row and
// the column permutation, all drawn from `rng` in that order.
template <class DensityOf>
ShuffledBlocks shuffled_blocks(RandomStream& rng, int blocks, int size, DensityOf&& density_of) {
  const int n = blocks * size;
  ShuffledBlocks out;
  SingleScanProblem problem = make_problem(RowMatrix::Zero(n, n));
  for (int b = 0; b < blocks; ++b) {
    out.parts.push_back(random_problem(rng, size, size, density_of(b)));
    problem.psi.block(b * size, b * size, size, size) = out.parts.back().psi;
  }
  out.rows = random_permutation(rng, n);
  out.cols = random_permutation(rng, n);
  out.shuffled = permute_problem(problem, out.rows, out.cols);
  return out;
}

// Requires the marginals `m` of problem.shuffled to be, for each block, its brute-force
// marginals (within near(expected), an Approx) and 0 for every measurement of another block.
// Returns log Z, the sum of the blocks' log partition functions.
template <class Near>
double check_block_marginals(const RowMatrix& m, const ShuffledBlocks& problem, Near&& near) {
  const int blocks = static_cast<int>(problem.parts.size());
  const int size = problem.parts[0].targets(), n = blocks * size;
  double log_z = 0.0;
  for (int b = 0; b < blocks; ++b) {
    const BruteForceResult reference = brute_force_marginals(problem.parts[b]);
    log_z += std::log(reference.partition);
    for (int r = 0; r < size; ++r) {
      const int i = problem.rows[b * size + r];
      INFO("block " << b << " row " << r);
      CHECK(m(i, 0) == near(reference.marginals(r, 0)));
      for (int c = 0; c < n; ++c) {
        const bool in_block = c >= b * size && c < (b + 1) * size;
        if (in_block) {
          CHECK(m(i, problem.cols[c] + 1) == near(reference.marginals(r, c - b * size + 1)));
        } else {
          CHECK(m(i, problem.cols[c] + 1) == 0.0);
        }
      }
    }
  }
  return log_z;
}

}  // namespace dabench::test
