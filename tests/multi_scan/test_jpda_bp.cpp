// Tests of jpda-bp (multiscan-convex-variational, Sec. IV baseline) against the exact
// multi-scan posterior by brute-force enumeration over every particle tuple and every
// consistent association of every scan (eq 1): equal to it with one track and with tracks whose
// measurements are disjoint; rows of every output sum to one; on a shared-measurement problem
// it differs from the exact posterior (it is an approximation), while its first scan's
// association probabilities equal the exact single-scan marginals when that scan's graph has no
// loop (one measurement), where BP is exact.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <vector>

#include "harness/core/random_stream.hpp"
#include "harness/multi_scan/registry.hpp"

namespace DABENCH_TEST_FILE {

namespace {

using dabench::MultiScanBeliefs;
using dabench::MultiScanProblem;
using dabench::RandomStream;
using dabench::RowMatrix;
using dabench::ScanFactors;
using dabench::SolveReport;
using dabench::Vector;

// Exact q^i(p) ∝ Σ over particle tuples and consistent per-scan associations of
// Π_i ψ^i(p_i) Π_t ψ^i_t(p_i, a^i_t). Written for clarity, not speed.
std::vector<Vector> exact_track_beliefs(const MultiScanProblem& problem) {
  const int n = problem.tracks();
  std::vector<Vector> belief(n);
  for (int i = 0; i < n; ++i) belief[i] = Vector::Zero(problem.hypotheses(i));
  std::vector<int> particle(n, 0);
  // Σ over consistent associations of scan t of Π_i ψ^i_t(p_i, a_i), by recursion over tracks.
  const std::function<double(const ScanFactors&, int, std::vector<bool>&)> scan_sum =
      [&](const ScanFactors& scan, int i, std::vector<bool>& used) -> double {
    if (i == n) return 1.0;
    double total = scan.factor[i](particle[i], 0) * scan_sum(scan, i + 1, used);
    for (int j = 1; j <= scan.measurements; ++j) {
      if (used[j]) continue;
      used[j] = true;
      total += scan.factor[i](particle[i], j) * scan_sum(scan, i + 1, used);
      used[j] = false;
    }
    return total;
  };
  const std::function<void(int)> over_particles = [&](int i) {
    if (i == n) {
      double weight = 1.0;
      for (int k = 0; k < n; ++k) weight *= problem.prior[k][particle[k]];
      for (const ScanFactors& scan : problem.scans) {
        std::vector<bool> used(scan.measurements + 1, false);
        weight *= scan_sum(scan, 0, used);
      }
      for (int k = 0; k < n; ++k) belief[k][particle[k]] += weight;
      return;
    }
    for (particle[i] = 0; particle[i] < problem.hypotheses(i); ++particle[i]) over_particles(i + 1);
  };
  over_particles(0);
  for (Vector& b : belief) b /= b.sum();
  return belief;
}

// Random problem: `tracks` tracks of `particles` particles, scans with `measurements` each.
// With `disjoint`, track i's factors are nonzero only on measurements j ≡ i (mod tracks).
MultiScanProblem random_problem(RandomStream& rng, int tracks, int particles, int scans, int measurements, bool disjoint) {
  MultiScanProblem problem;
  for (int i = 0; i < tracks; ++i) {
    problem.prior.push_back(Vector(particles));
    for (int p = 0; p < particles; ++p) problem.prior.back()[p] = rng.uniform(0.1, 1.0);
  }
  for (int t = 0; t < scans; ++t) {
    ScanFactors scan;
    scan.measurements = measurements;
    for (int i = 0; i < tracks; ++i) {
      RowMatrix factor(particles, measurements + 1);
      for (int p = 0; p < particles; ++p) {
        factor(p, 0) = 0.1;
        for (int j = 1; j <= measurements; ++j) {
          const bool allowed = !disjoint || (j - 1) % tracks == i;
          factor(p, j) = allowed ? rng.uniform(0.0, 5.0) : 0.0;
        }
      }
      scan.factor.push_back(factor);
    }
    problem.scans.push_back(scan);
  }
  return problem;
}

MultiScanBeliefs solve(const MultiScanProblem& problem) {
  auto solver = dabench::make_multi_scan_solver("jpda-bp");
  MultiScanBeliefs beliefs;
  SolveReport report;
  solver->solve(problem, beliefs, report);
  REQUIRE(report.skipped.empty());
  CHECK(report.converged);
  return beliefs;
}

void check_rows_sum_to_one(const MultiScanProblem& problem, const MultiScanBeliefs& beliefs) {
  REQUIRE(beliefs.track.size() == static_cast<std::size_t>(problem.tracks()));
  for (const Vector& q : beliefs.track) CHECK(q.sum() == Approx(1.0).epsilon(1e-12));
  REQUIRE(beliefs.association.size() == static_cast<std::size_t>(problem.scan_count()));
  for (int t = 0; t < problem.scan_count(); ++t) {
    const auto& table = beliefs.association[t];
    REQUIRE(table.targets() == problem.tracks());
    REQUIRE(table.measurements() == problem.scans[t].measurements);
    for (int i = 0; i < table.targets(); ++i) CHECK(table.view().row(i).sum() == Approx(1.0).epsilon(1e-12));
  }
}

double max_difference(const std::vector<Vector>& a, const std::vector<Vector>& b) {
  double d = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, (a[i] - b[i]).cwiseAbs().maxCoeff());
  return d;
}

}  // namespace

TEST_CASE("jpda-bp: one track gives the exact Bayes posterior", "[jpda_bp]") {
  RandomStream rng(7, 0, 0);
  for (int repeat = 0; repeat < 5; ++repeat) {
    const MultiScanProblem problem = random_problem(rng, 1, 6, 4, 3, false);
    const MultiScanBeliefs beliefs = solve(problem);
    check_rows_sum_to_one(problem, beliefs);
    CHECK(max_difference(beliefs.track, exact_track_beliefs(problem)) < 1e-12);
  }
}

TEST_CASE("jpda-bp: tracks with disjoint measurements give the exact posterior", "[jpda_bp]") {
  RandomStream rng(7, 1, 0);
  for (int repeat = 0; repeat < 5; ++repeat) {
    const MultiScanProblem problem = random_problem(rng, 3, 3, 3, 4, true);
    const MultiScanBeliefs beliefs = solve(problem);
    check_rows_sum_to_one(problem, beliefs);
    CHECK(max_difference(beliefs.track, exact_track_beliefs(problem)) < 1e-9);
  }
}

TEST_CASE("jpda-bp: shared measurements are approximated scan by scan", "[jpda_bp]") {
  RandomStream rng(7, 2, 0);
  const MultiScanProblem problem = random_problem(rng, 2, 3, 3, 1, false);
  const MultiScanBeliefs beliefs = solve(problem);
  check_rows_sum_to_one(problem, beliefs);
  // The first scan's association probabilities are the exact single-scan marginals of the
  // prior tracks: brute force over a in {0,1}² with distinct nonzero entries.
  const auto& scan = problem.scans[0];
  Vector w[2];
  for (int i = 0; i < 2; ++i) w[i] = (problem.prior[i] / problem.prior[i].sum()).transpose() * scan.factor[i];
  RowMatrix exact = RowMatrix::Zero(2, 2);
  for (int a = 0; a < 2; ++a) {
    for (int b = 0; b < 2; ++b) {
      if (a > 0 && a == b) continue;
      exact(0, a) += w[0][a] * w[1][b];
      exact(1, b) += w[0][a] * w[1][b];
    }
  }
  exact /= exact.row(0).sum();
  CHECK((beliefs.association[0].view() - exact).cwiseAbs().maxCoeff() < 1e-8);
  // After three scans with shared measurements the product of marginals is not exact.
  CHECK(max_difference(beliefs.track, exact_track_beliefs(problem)) > 1e-4);
}

}  // namespace DABENCH_TEST_FILE
