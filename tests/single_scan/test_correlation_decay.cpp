// Tests of `cd`, correlation decay (Oh 2011) as eqs (40)-(41) of Williams & Lau 2014:
//  - full depth (≥ the longest self-avoiding walk, e.g. n + m) equals `exact` and brute force;
//  - every depth equals a literal, unmemoised transcription of (40)-(41) on index sets, whose
//    unnormalised rows already sum to one;
//  - depth 1 is PDA; odd/even depths bracket p(a_i = 0) monotonically; tree-shaped gating
//    graphs are exact once the depth reaches the longest walk from each target;
//  - memo on/off (and a tiny memo cap, and clusters wider than 64 nodes) give identical bits,
//    with far fewer evaluations on the 2×3 grid at spacing 0, depth 7;
//  - the budget refuses with skipped:budget and the solver then solves the next problem.
#include <catch2/catch.hpp>

#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "algorithms/single_scan/correlation_decay.hpp"
#include "bench/single_scan/problem_pool.hpp"
#include "harness/core/errors.hpp"
#include "harness/single_scan/registry.hpp"
#include "tests/support/brute_force.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench;
using namespace dabench::test;

namespace {

RowMatrix normalized_psi(const SingleScanProblem& problem) {
  RowMatrix psi(problem.targets(), problem.measurements());
  for (int i = 0; i < problem.targets(); ++i) {
    for (int j = 0; j < problem.measurements(); ++j) psi(i, j) = problem.normalized_weight(i, j);
  }
  return psi;
}

CorrelationDecayOptions cd_options(int depth, bool memo = true) {
  CorrelationDecayOptions options;
  options.depth = depth;
  options.memo = memo;
  REQUIRE(options.validate().empty());
  return options;
}

RowMatrix solve_cd(CorrelationDecay& solver, const SingleScanProblem& problem) {
  const SolveResult result = run_solver(solver, problem);
  REQUIRE(result.report.skipped.empty());
  return result.marginals;
}

RowMatrix solve_cd(const SingleScanProblem& problem, int depth, bool memo = true) {
  CorrelationDecay solver(cd_options(depth, memo));
  return solve_cd(solver, problem);
}

bool same_bits(const RowMatrix& a, const RowMatrix& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() &&
         (a.size() == 0 || std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0);
}

// Eqs (40)-(41) word for word on index sets T, M (no clusters, no memo, no depth clamp), and
// the marginals p_i0 = Φ_i, p_ij = ψ_i(j) Φ(T−{i}, M, j, t−1) Φ_i WITHOUT normalisation.
class LiteralRecursion {
 public:
  explicit LiteralRecursion(const SingleScanProblem& problem)
      : psi_(normalized_psi(problem)), in_t_(problem.targets(), 1), in_m_(problem.measurements(), 1) {}

  double target(int i, int t) {  // eq (40)
    if (t == 0) return 1.0;
    in_t_[i] = 0;  // the children see T − {i}
    double s = 1.0;
    for (int j = 0; j < psi_.cols(); ++j) {
      if (in_m_[j] && psi_(i, j) > 0.0) s += psi_(i, j) * measurement(j, t - 1);
    }
    in_t_[i] = 1;
    return 1.0 / s;
  }
  double measurement(int j, int t) {  // eq (41)
    if (t == 0) return 1.0;
    in_m_[j] = 0;
    double s = 1.0;
    for (int i = 0; i < psi_.rows(); ++i) {
      if (in_t_[i] && psi_(i, j) > 0.0) s += psi_(i, j) * target(i, t - 1);
    }
    in_m_[j] = 1;
    return 1.0 / s;
  }
  RowMatrix unnormalized_marginals(int t) {
    RowMatrix p = RowMatrix::Zero(psi_.rows(), psi_.cols() + 1);
    for (int i = 0; i < psi_.rows(); ++i) {
      const double phi_i = target(i, t);
      p(i, 0) = phi_i;
      in_t_[i] = 0;
      for (int j = 0; j < psi_.cols(); ++j) {
        if (psi_(i, j) > 0.0) p(i, j + 1) = psi_(i, j) * measurement(j, t - 1) * phi_i;
      }
      in_t_[i] = 1;
    }
    return p;
  }

 private:
  RowMatrix psi_;
  std::vector<char> in_t_;
  std::vector<char> in_m_;
};

}  // namespace

TEST_CASE("cd: hand-computed 2x2 at depths 1 2 3", "[cd]") {
  // ψ = [[1, 2], [3, 4]] (the 2x2 of test_exact: exact p_1 = [8, 5, 8]/21, p_2 = [4, 9, 8]/21).
  const SingleScanProblem problem = make_problem(psi_2x2());
  // Depth 1 (PDA): target 1: s = 1 + 1 + 2 = 4; target 2: s = 1 + 3 + 4 = 8.
  RowMatrix d1(2, 3);
  d1 << 1.0 / 4, 1.0 / 4, 2.0 / 4, 1.0 / 8, 3.0 / 8, 4.0 / 8;
  CHECK(scaled_error(solve_cd(problem, 1), d1, 1e-15, 0.0) <= 1.0);
  // Depth 2, target 1: Φ(M1 | T2 only) = 1/(1+3), Φ(M2 | T2) = 1/(1+4);
  //   s = 1 + 1/4 + 2/5 = 33/20 → p_1 = [20, 5, 8]/33.
  // Target 2: Φ(M1 | T1) = 1/2, Φ(M2 | T1) = 1/3; s = 1 + 3/2 + 4/3 = 23/6 → p_2 = [6, 9, 8]/23.
  RowMatrix d2(2, 3);
  d2 << 20.0 / 33, 5.0 / 33, 8.0 / 33, 6.0 / 23, 9.0 / 23, 8.0 / 23;
  CHECK(scaled_error(solve_cd(problem, 2), d2, 1e-15, 0.0) <= 1.0);
  // Depth 3 = longest self-avoiding walk (4 nodes, 3 edges): exact.
  const RowMatrix exact = marginals_2x2();
  CHECK(scaled_error(solve_cd(problem, 3), exact, 1e-14, 0.0) <= 1.0);
  CHECK(scaled_error(solve_cd(problem, 2), exact, 1e-3, 0.0) > 1.0);  // depth 2 is not
}

TEST_CASE("cd: full depth equals exact and brute force on random problems up to 6x6", "[cd]") {
  RandomStream rng(20240611, 3, 0);
  auto exact_solver = make_single_scan_solver("exact");
  std::map<int, std::unique_ptr<CorrelationDecay>> by_depth;  // reused: workspace reuse too
  CorrelationDecay deep(cd_options(1000));
  CorrelationDecay deep_plain(cd_options(1000, false));
  int checked = 0;
  for (int trial = 0; trial < 300; ++trial) {
    auto [n, m, density, side, problem] = sweep_trial(rng, trial, 6);
    if (trial % 50 == 7 && n > 0 && m > 0) problem.psi.setZero();  // degenerate: nothing gated
    REQUIRE(problem.validate().empty());
    INFO("trial " << trial << " n=" << n << " m=" << m << " density " << density_name(density) << " side " << side
                  << "\npsi=\n" << problem.psi);
    const SolveResult exact = run_solver(*exact_solver, problem);
    REQUIRE(exact.report.skipped.empty());
    const BruteForceResult brute = brute_force_marginals(problem);

    // Depth n + m − 1 ≥ longest self-avoiding walk (in edges) of any cluster: already exact.
    const int depth = std::max(1, n + m - 1);
    auto& solver = by_depth[depth];
    if (!solver) solver = std::make_unique<CorrelationDecay>(cd_options(depth));
    const RowMatrix cd = solve_cd(*solver, problem);
    CHECK(max_abs_difference(cd, exact.marginals) <= 1e-10);
    CHECK(max_abs_difference(cd, brute.marginals) <= 1e-10);
    CHECK(scaled_error(cd, brute.marginals, 1e-11, 1e-14) <= 1.0);  // in fact relative accuracy

    const RowMatrix cd_deep = solve_cd(deep, problem);  // any depth ≥ n + m: the same bits
    CHECK(same_bits(cd_deep, cd));
    CHECK(same_bits(solve_cd(deep_plain, problem), cd));
    ++checked;
  }
  CHECK(checked == 300);
}

TEST_CASE("cd: every depth equals the literal recursion whose rows need no normalisation", "[cd]") {
  RandomStream rng(99, 4, 0);
  for (int trial = 0; trial < 60; ++trial) {
    const int n = uniform_int(rng, 1, 5);
    const int m = uniform_int(rng, 1, 5);
    const SingleScanProblem problem = random_problem(rng, n, m, cycled_density(trial), trial % 4 == 0);
    LiteralRecursion literal(problem);
    for (int depth = 1; depth <= 7; ++depth) {
      INFO("trial " << trial << " depth " << depth << "\npsi=\n" << problem.psi);
      const RowMatrix reference = literal.unnormalized_marginals(depth);
      // Φ_i = 1/(1 + Σ_j ψ_i(j) Φ_j) makes every row sum to one at every depth.
      for (int i = 0; i < n; ++i) CHECK(reference.row(i).sum() == Approx(1.0).epsilon(0).margin(1e-14));
      const RowMatrix cd = solve_cd(problem, depth);
      CHECK(scaled_error(cd, reference, 1e-13, 1e-300) <= 1.0);
      for (int i = 0; i < n; ++i) CHECK(cd.row(i).sum() == Approx(1.0).epsilon(0).margin(1e-14));
    }
  }
}

TEST_CASE("cd: depth 1 is PDA", "[cd]") {
  RandomStream rng(5, 5, 0);
  CorrelationDecay solver(cd_options(1));
  for (int trial = 0; trial < 40; ++trial) {
    const SingleScanProblem problem =
        random_problem(rng, uniform_int(rng, 1, 6), uniform_int(rng, 0, 6), Density::sparse, trial % 2 == 0);
    const RowMatrix psi = normalized_psi(problem);
    RowMatrix pda(psi.rows(), psi.cols() + 1);
    for (int i = 0; i < psi.rows(); ++i) {
      const double s = 1.0 + psi.row(i).sum();
      pda(i, 0) = 1.0 / s;
      for (int j = 0; j < psi.cols(); ++j) pda(i, j + 1) = psi(i, j) / s;
    }
    INFO("trial " << trial);
    CHECK(scaled_error(solve_cd(solver, problem), pda, 1e-14, 0.0) <= 1.0);
  }
}

TEST_CASE("cd: odd depths bound the missed-detection probability below and even depths above", "[cd]") {
  // 1/(1 + Σ ψ x) is decreasing in x and Φ(·,0) = 1 ≥ truth, so by induction Φ(t) ≤ truth for
  // odd t and ≥ truth for even t, odd iterates increasing and even ones decreasing.
  RandomStream rng(31, 6, 0);
  constexpr double kSlack = 1e-14;
  for (int trial = 0; trial < 25; ++trial) {
    const SingleScanProblem problem = random_problem(rng, uniform_int(rng, 2, 5), uniform_int(rng, 2, 5),
                                                     trial % 2 ? Density::dense : Density::sparse);
    const BruteForceResult truth = brute_force_marginals(problem);
    std::vector<RowMatrix> by_depth;
    for (int depth = 1; depth <= 9; ++depth) by_depth.push_back(solve_cd(problem, depth));
    for (int i = 0; i < problem.targets(); ++i) {
      INFO("trial " << trial << " target " << i);
      const double p = truth.marginals(i, 0);
      for (int depth = 1; depth <= 9; ++depth) {
        const double q = by_depth[depth - 1](i, 0);
        if (depth % 2) CHECK(q <= p + kSlack); else CHECK(q >= p - kSlack);
        if (depth >= 3) {
          const double earlier = by_depth[depth - 3](i, 0);
          if (depth % 2) CHECK(q >= earlier - kSlack); else CHECK(q <= earlier + kSlack);
        }
      }
    }
  }
}

TEST_CASE("cd: tree-shaped gating graphs are exact once depth reaches the longest walk", "[cd]") {
  RandomStream rng(8, 7, 0);
  SECTION("a single target: exact from depth 1") {
    const SingleScanProblem problem = random_problem(rng, 1, 6, Density::dense, true);
    const RowMatrix truth = brute_force_marginals(problem).marginals;
    for (int depth = 1; depth <= 4; ++depth) CHECK(scaled_error(solve_cd(problem, depth), truth, 1e-14, 0.0) <= 1.0);
  }
  SECTION("disjoint targets (each measurement gated by one target): exact from depth 1") {
    RowMatrix psi = RowMatrix::Zero(3, 7);
    for (int j = 0; j < 7; ++j) psi(j % 3, j) = std::exp(rng.uniform(-3.0, 3.0));
    const SingleScanProblem problem = make_problem(psi);
    const RowMatrix truth = brute_force_marginals(problem).marginals;
    for (int depth = 1; depth <= 4; ++depth) CHECK(scaled_error(solve_cd(problem, depth), truth, 1e-14, 0.0) <= 1.0);
  }
  SECTION("a path T1-M1-T2-M2-T3: target 1 needs depth 4, target 2 depth 2") {
    RowMatrix psi = RowMatrix::Zero(3, 2);
    psi(0, 0) = 2.0;
    psi(1, 0) = 3.0;
    psi(1, 1) = 0.5;
    psi(2, 1) = 4.0;
    const SingleScanProblem problem = make_problem(psi);
    const RowMatrix truth = brute_force_marginals(problem).marginals;
    const auto row_error = [&](const RowMatrix& cd, int i) { return (cd.row(i) - truth.row(i)).cwiseAbs().maxCoeff(); };
    for (int depth = 1; depth <= 6; ++depth) {
      INFO("depth " << depth);
      const RowMatrix cd = solve_cd(problem, depth);
      // The walk from target 1 (or 3) has 4 edges, from target 2 two edges each way.
      CHECK((row_error(cd, 0) <= 1e-15) == (depth >= 4));
      CHECK((row_error(cd, 2) <= 1e-15) == (depth >= 4));
      CHECK((row_error(cd, 1) <= 1e-15) == (depth >= 2));
    }
  }
}

TEST_CASE("cd: memo on and off give identical bits and the memo saves work", "[cd]") {
  SECTION("random problems, several depths, and a 16-entry memo cap") {
    RandomStream rng(77, 8, 0);
    CorrelationDecayOptions tiny = cd_options(6);
    tiny.memo_entries = 16;
    CorrelationDecay capped(tiny);
    for (int trial = 0; trial < 40; ++trial) {
      const SingleScanProblem problem = random_problem(rng, uniform_int(rng, 1, 6), uniform_int(rng, 1, 6),
                                                       trial % 2 ? Density::dense : Density::extreme, trial % 3 == 0);
      for (int depth : {4, 6, 9}) {
        INFO("trial " << trial << " depth " << depth);
        const RowMatrix on = solve_cd(problem, depth, true);
        CHECK(same_bits(on, solve_cd(problem, depth, false)));
        if (depth == 6) CHECK(same_bits(on, solve_cd(capped, problem)));
      }
    }
  }
  SECTION("2x3 grid at spacing 0, depth 7") {
    const auto pool = bench::grid_pool({{"rows", "2"}, {"cols", "3"}, {"spacing", "0"}}, 6);
    CorrelationDecay on(cd_options(7, true));
    CorrelationDecay off(cd_options(7, false));
    std::int64_t with_memo = 0;
    std::int64_t without = 0;
    for (const SingleScanProblem& problem : pool) {
      const RowMatrix a = solve_cd(on, problem);
      with_memo += on.evaluations();
      CHECK(on.memo_hits() > 0);
      const RowMatrix b = solve_cd(off, problem);
      without += off.evaluations();
      CHECK(off.memo_hits() == 0);
      CHECK(same_bits(a, b));
    }
    INFO("evaluations with memo " << with_memo << ", without " << without);
    CHECK(with_memo * 4 < without);  // 4.8x fewer on these six; about 3x less CPU time (bench_cd)
  }
}

TEST_CASE("cd: clusters wider than 64 nodes (multi-word keys)", "[cd]") {
  // A chain of 4 targets linked by shared measurements S_k (T_k, T_k+1), each target with 15
  // private measurements: 4 + 3 + 60 = 67 nodes in one cluster; exact enumeration is cheap.
  RandomStream rng(3, 9, 0);
  RowMatrix psi = RowMatrix::Zero(4, 63);
  for (int k = 0; k < 3; ++k) {
    psi(k, k) = std::exp(rng.uniform(-1.0, 1.0));
    psi(k + 1, k) = std::exp(rng.uniform(-1.0, 1.0));
  }
  for (int i = 0; i < 4; ++i) {
    for (int p = 0; p < 15; ++p) psi(i, 3 + 15 * i + p) = std::exp(rng.uniform(-4.0, 0.0));
  }
  const SingleScanProblem chain = make_problem(psi);
  const RowMatrix exact = run_solver(*make_single_scan_solver("exact"), chain).marginals;
  const RowMatrix deep = solve_cd(chain, 100);
  CHECK(max_abs_difference(deep, exact) <= 1e-12);
  CHECK(same_bits(deep, solve_cd(chain, 100, false)));
  CHECK(scaled_error(solve_cd(chain, 3), exact, 1e-6, 0.0) > 1.0);  // truncation shows

  // 10 targets sharing 16 measurements (density 1/2), target 0 also with 54 private ones
  // listed first, so the shared measurements get local numbers 64..79: the memo keys' second
  // word carries the states. Memo on/off: same bits; measurement order reversed (other
  // local numbering and summation order): same values to rounding.
  SingleScanProblem wide = make_problem(RowMatrix::Zero(10, 70));
  for (int j = 0; j < 54; ++j) wide.psi(0, j) = std::exp(rng.uniform(-5.0, -1.0));
  for (int i = 0; i < 10; ++i) {
    for (int j = 54; j < 70; ++j) {
      if (rng.bernoulli(0.5)) wide.psi(i, j) = std::exp(rng.uniform(-2.0, 2.0));
    }
  }
  CorrelationDecay on(cd_options(6, true));
  const RowMatrix a = solve_cd(on, wide);
  CHECK(on.memo_hits() > 1000);
  CHECK(same_bits(a, solve_cd(wide, 6, false)));
  std::vector<int> rows(10);
  std::vector<int> reversed(70);
  for (int i = 0; i < 10; ++i) rows[i] = i;
  for (int j = 0; j < 70; ++j) reversed[j] = 69 - j;
  const RowMatrix b = solve_cd(permute_problem(wide, rows, reversed), 6);
  RowMatrix b_back(10, 71);
  for (int i = 0; i < 10; ++i) {
    b_back(i, 0) = b(i, 0);
    for (int j = 0; j < 70; ++j) b_back(i, j + 1) = b(i, reversed[j] + 1);
  }
  CHECK(scaled_error(a, b_back, 1e-12, 1e-300) <= 1.0);
}

TEST_CASE("cd: budget exceeded reports skipped and the solver goes on", "[cd]") {
  RandomStream rng(12, 10, 0);
  const SingleScanProblem big = random_problem(rng, 6, 6, Density::dense);
  const SingleScanProblem small = make_problem(psi_2x2());

  auto solver = make_single_scan_solver("cd:depth=7,budget=1000");
  const SolveResult refused = run_solver(*solver, big);
  CHECK(refused.report.skipped == "budget");
  const SolveResult next = run_solver(*solver, small);
  REQUIRE(next.report.skipped.empty());
  CHECK(max_abs_difference(next.marginals, brute_force_marginals(small).marginals) <= 1e-15);

  // The refused problem fits a larger budget; a solver that refused first gives the same bits.
  CorrelationDecay plenty(cd_options(7));
  const RowMatrix reference = solve_cd(plenty, big);
  CHECK(plenty.evaluations() > 1000);
  CorrelationDecayOptions exact_budget = cd_options(7);
  exact_budget.budget = plenty.evaluations();  // exactly enough
  CorrelationDecay just(exact_budget);
  CHECK(same_bits(solve_cd(just, big), reference));
  exact_budget.budget = plenty.evaluations() - 1;  // one short
  CorrelationDecay short_by_one(exact_budget);
  CHECK(run_solver(short_by_one, big).report.skipped == "budget");
  CHECK(same_bits(solve_cd(short_by_one, small), next.marginals));
  CHECK(same_bits(solve_cd(short_by_one, small), solve_cd(small, 7)));
}

TEST_CASE("cd: options", "[cd]") {
  CHECK_NOTHROW(make_single_scan_solver("cd"));
  CHECK_NOTHROW(make_single_scan_solver("cd:depth=3,memo=false,budget=1e6,memo_entries=0"));
  CHECK_THROWS_AS(make_single_scan_solver("cd:depth=0"), InputError);
  CHECK_THROWS_AS(make_single_scan_solver("cd:budget=0"), InputError);
  CHECK_THROWS_AS(make_single_scan_solver("cd:memo_entries=-1"), InputError);
  CHECK_THROWS_AS(make_single_scan_solver("cd:t=3"), InputError);
  // memo_entries = 0 disables the memo: same bits.
  RandomStream rng(1, 11, 0);
  const SingleScanProblem problem = random_problem(rng, 5, 5, Density::dense);
  const RowMatrix off = run_solver(*make_single_scan_solver("cd:depth=7,memo_entries=0"), problem).marginals;
  CHECK(same_bits(off, solve_cd(problem, 7)));
}

}  // namespace DABENCH_TEST_FILE
