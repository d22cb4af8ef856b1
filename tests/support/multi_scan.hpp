#pragma once
// Test helpers for multiple-scan problems (multiscan-convex-variational, Sec. II-III):
// a random problem generator on a fixed RandomStream, an obviously-correct brute-force
// posterior, and the solver call. The brute force shares nothing with ms-exact: it visits
// every joint value of (A^1..A^n, a^i_t' for all i, t') with an odometer, keeps those in which
// no two tracks use the same measurement of a scan (eq 1), and weights each by
// Π_i ψ^i(A^i) Π_t' ψ^i_t'(A^i, a^i_t') (eq 2).
#include <cassert>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "harness/core/random_stream.hpp"
#include "harness/multi_scan/problem.hpp"
#include "harness/multi_scan/registry.hpp"
#include "harness/multi_scan/solver.hpp"

namespace dabench::test {

struct RandomMultiScanShape {
  int tracks = 2;
  int hypotheses = 2;
  std::vector<int> measurements = {2, 2};  // m_t' per scan
  double zero_fraction = 0.0;              // share of factors ψ_t'(A, j > 0) set to exactly 0
};

inline MultiScanProblem random_multi_scan_problem(const RandomMultiScanShape& shape, std::uint64_t seed) {
  RandomStream random(seed, 7, 11);
  MultiScanProblem problem;
  for (int i = 0; i < shape.tracks; ++i) {
    Vector prior(shape.hypotheses);
    for (int h = 0; h < shape.hypotheses; ++h) prior[h] = random.uniform(0.2, 1.0);
    problem.prior.push_back(prior);
  }
  for (int m : shape.measurements) {
    ScanFactors scan;
    scan.measurements = m;
    for (int i = 0; i < shape.tracks; ++i) {
      RowMatrix factor(shape.hypotheses, m + 1);
      for (int h = 0; h < shape.hypotheses; ++h) {
        factor(h, 0) = random.uniform(0.1, 0.5);
        for (int j = 1; j <= m; ++j) {
          factor(h, j) = random.uniform() < shape.zero_fraction ? 0.0 : random.uniform(0.0, 2.0);
        }
      }
      scan.factor.push_back(factor);
    }
    problem.scans.push_back(scan);
  }
  return problem;
}

inline MultiScanBeliefs brute_force_posterior(const MultiScanProblem& problem) {
  const int n = problem.tracks();
  const int scans = problem.scan_count();
  // Digits: per track, its hypothesis then one association per scan.
  std::vector<int> radix;
  for (int i = 0; i < n; ++i) {
    radix.push_back(problem.hypotheses(i));
    for (int t = 0; t < scans; ++t) radix.push_back(problem.scans[t].measurements + 1);
  }
  double total = 1.0;
  for (int r : radix) total *= r;
  assert(total <= 2e7 && "brute force: problem too large");
  MultiScanBeliefs beliefs;
  for (int i = 0; i < n; ++i) beliefs.track.push_back(Vector::Zero(problem.hypotheses(i)));
  beliefs.association.resize(scans);
  std::vector<RowMatrix> association(scans);
  for (int t = 0; t < scans; ++t) association[t] = RowMatrix::Zero(n, problem.scans[t].measurements + 1);
  std::vector<int> digit(radix.size(), 0);
  double partition = 0.0;
  const int per_track = 1 + scans;
  while (true) {
    bool feasible = true;
    for (int t = 0; t < scans && feasible; ++t) {
      for (int i = 0; i < n && feasible; ++i) {
        for (int k = i + 1; k < n && feasible; ++k) {
          const int a = digit[i * per_track + 1 + t];
          feasible = a == 0 || a != digit[k * per_track + 1 + t];
        }
      }
    }
    if (feasible) {
      double weight = 1.0;
      for (int i = 0; i < n; ++i) {
        const int h = digit[i * per_track];
        weight *= problem.prior[i][h];
        for (int t = 0; t < scans; ++t) weight *= problem.scans[t].factor[i](h, digit[i * per_track + 1 + t]);
      }
      partition += weight;
      for (int i = 0; i < n; ++i) {
        beliefs.track[i][digit[i * per_track]] += weight;
        for (int t = 0; t < scans; ++t) association[t](i, digit[i * per_track + 1 + t]) += weight;
      }
    }
    std::size_t position = 0;
    while (position < digit.size() && ++digit[position] == radix[position]) digit[position++] = 0;
    if (position == digit.size()) break;
  }
  for (int i = 0; i < n; ++i) beliefs.track[i] /= partition;
  for (int t = 0; t < scans; ++t) {
    beliefs.association[t].reshape(n, problem.scans[t].measurements);
    beliefs.association[t].view() = association[t] / partition;
  }
  return beliefs;
}

struct MultiScanRun {
  MultiScanBeliefs beliefs;
  SolveReport report;
};

inline MultiScanRun run_multi_scan(const std::string& spec, const MultiScanProblem& problem) {
  const std::unique_ptr<MultiScanSolver> solver = make_multi_scan_solver(spec);
  MultiScanRun run;
  solver->solve(problem, run.beliefs, run.report);
  return run;
}

// Largest absolute difference over every track belief and every association belief.
inline double belief_difference(const MultiScanBeliefs& a, const MultiScanBeliefs& b) {
  double largest = 0.0;
  for (std::size_t i = 0; i < a.track.size(); ++i) largest = std::max(largest, (a.track[i] - b.track[i]).cwiseAbs().maxCoeff());
  for (std::size_t t = 0; t < a.association.size(); ++t) {
    largest = std::max(largest, (a.association[t].view() - b.association[t].view()).cwiseAbs().maxCoeff());
  }
  return largest;
}

}  // namespace dabench::test
