// Tests of harness/tbd/gospa.hpp (GOSPA, Rahman, García-Fernández & Svensson, FUSION 2017):
// closed-form values, against brute force over every partial assignment on random small sets
// for several (c, p, α), the α = 2 decomposition of Proposition 1 (its parts sum to d^p and
// agree with a brute-force minimum over γ restricted to pairs closer than c), symmetry, the
// triangle inequality, option validation and reuse of one object.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "harness/core/random_stream.hpp"
#include "harness/tbd/gospa.hpp"
#include "tests/support/input_error.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench;

namespace {

using Points = std::vector<Eigen::Vector2d>;

// Minimum over every partial assignment γ (each point in at most one pair) of
//   Σ_{(x,y)∈γ} pair(‖x − y‖) + (c^p/α)(|X| − |γ|) + (c^p/α)(|Y| − |γ|).
// With pair(d) = min(d, c)^p this is Definition 1 for α ≤ 2 (unpairing a pair costs 2c^p/α ≥ c^p,
// so some optimum pairs all of the smaller set); with pair(d) = d^p for d < c and +∞ otherwise,
// it is Proposition 1's minimum for α = 2.
template <class PairCost>
void enumerate(const Points& x, const Points& y, std::size_t i, std::vector<char>& used, double sum,
               double unmatched_cost, const PairCost& pair, double& best) {
  if (i == x.size()) {
    std::size_t free_y = 0;
    for (char u : used) free_y += !u;
    best = std::min(best, sum + unmatched_cost * static_cast<double>(free_y));
    return;
  }
  enumerate(x, y, i + 1, used, sum + unmatched_cost, unmatched_cost, pair, best);  // x_i unpaired
  for (std::size_t j = 0; j < y.size(); ++j) {
    if (used[j]) continue;
    used[j] = 1;
    enumerate(x, y, i + 1, used, sum + pair((x[i] - y[j]).norm()), unmatched_cost, pair, best);
    used[j] = 0;
  }
}

template <class PairCost>
double brute_force_power(const Points& x, const Points& y, double unmatched_cost, const PairCost& pair) {
  std::vector<char> used(y.size(), 0);
  double best = std::numeric_limits<double>::infinity();
  enumerate(x, y, 0, used, 0.0, unmatched_cost, pair, best);
  return best;
}

// d_p^(c,α)(X, Y) by brute force (Definition 1 through the partial-assignment form).
double brute_force_gospa(const Points& x, const Points& y, const GospaOptions& o) {
  const auto pair = [&](double d) { return std::pow(std::min(d, o.cutoff), o.order); };
  return std::pow(brute_force_power(x, y, std::pow(o.cutoff, o.order) / o.alpha, pair), 1.0 / o.order);
}

// Proposition 1's minimum over γ (pairs closer than c only), α = 2: the p-th power.
double brute_force_proposition1_power(const Points& x, const Points& y, const GospaOptions& o) {
  const auto pair = [&](double d) {
    return d < o.cutoff ? std::pow(d, o.order) : std::numeric_limits<double>::infinity();
  };
  return brute_force_power(x, y, std::pow(o.cutoff, o.order) / 2.0, pair);
}

// `count` points: real in [0, 6)² or, with `grid`, on the integer grid {0..4}² (coincident
// points and pairs exactly at distance c = 1, 2, 3 occur).
Points random_points(RandomStream& rng, int count, bool grid) {
  Points points(count);
  for (auto& point : points) {
    point = grid ? Eigen::Vector2d(std::floor(rng.uniform(0.0, 5.0)), std::floor(rng.uniform(0.0, 5.0)))
                 : Eigen::Vector2d(rng.uniform(0.0, 6.0), rng.uniform(0.0, 6.0));
  }
  return points;
}

const std::vector<GospaOptions> kParameterSets = {
    {2.0, 1.0, 2.0}, {2.0, 2.0, 2.0}, {1.0, 1.0, 1.0}, {3.0, 1.5, 0.5}, {0.5, 3.0, 2.0}, {2.0, 1.0, 1.3}};

// The α = 2 decomposition is self-consistent and matches the distance.
void check_decomposition(const GospaResult& r, const Points& x, const Points& y, const GospaOptions& o) {
  const double cp = std::pow(o.cutoff, o.order);
  const int pairs = static_cast<int>(x.size()) - r.missed_count;
  CHECK(pairs >= 0);
  CHECK(static_cast<int>(y.size()) - r.false_count == pairs);
  CHECK(r.missed == cp / 2.0 * r.missed_count);
  CHECK(r.false_targets == cp / 2.0 * r.false_count);
  CHECK(r.localisation >= 0.0);
  CHECK(r.localisation <= cp * pairs);  // every pair of γ is closer than c
  CHECK(r.localisation + r.missed + r.false_targets == Approx(std::pow(r.distance, o.order)).margin(1e-12));
}

}  // namespace

TEST_CASE("gospa: closed cases (c = 2, p = 1, alpha = 2 unless stated)", "[gospa]") {
  Gospa gospa;
  const GospaOptions o;  // c = 2, p = 1, α = 2
  const Eigen::Vector2d origin(0.0, 0.0);

  GospaResult r = gospa.compute({}, {}, o);
  CHECK(r.distance == 0.0);
  CHECK(r.localisation == 0.0);
  CHECK(r.missed_count == 0);
  CHECK(r.false_count == 0);

  // No truth, three estimates: three false targets at c^p/2 = 1 each.
  r = gospa.compute({}, {{1, 1}, {2, 2}, {3, 3}}, o);
  CHECK(r.distance == Approx(3.0));
  CHECK(r.false_count == 3);
  CHECK(r.false_targets == Approx(3.0));
  CHECK(r.missed_count == 0);
  CHECK(r.missed == 0.0);
  CHECK(r.localisation == 0.0);

  // Two truths, no estimate: two misses.
  r = gospa.compute({{1, 1}, {5, 5}}, {}, o);
  CHECK(r.distance == Approx(2.0));
  CHECK(r.missed_count == 2);
  CHECK(r.false_count == 0);

  // One pair at distance 0.5: localisation only.
  r = gospa.compute({origin}, {{0.3, 0.4}}, o);
  CHECK(r.distance == Approx(0.5));
  CHECK(r.localisation == Approx(0.5));
  CHECK(r.missed_count == 0);
  CHECK(r.false_count == 0);

  // One pair at distance 3 > c: a miss and a false target, (c^p/2 · 2)^(1/p) = 2.
  r = gospa.compute({origin}, {{3.0, 0.0}}, o);
  CHECK(r.distance == Approx(2.0));
  CHECK(r.localisation == 0.0);
  CHECK(r.missed_count == 1);
  CHECK(r.false_count == 1);
  CHECK(r.missed == Approx(1.0));
  CHECK(r.false_targets == Approx(1.0));

  // Exactly at the cut-off the pair is not in γ (Proposition 1 needs d < c): same distance 2,
  // counted as a miss and a false target.
  r = gospa.compute({origin}, {{0.0, 2.0}}, o);
  CHECK(r.distance == Approx(2.0));
  CHECK(r.missed_count == 1);
  CHECK(r.false_count == 1);
  CHECK(r.localisation == 0.0);

  // Just inside the cut-off the pair is assigned (1.9 < 2 = miss + false).
  r = gospa.compute({origin}, {{1.9, 0.0}}, o);
  CHECK(r.distance == Approx(1.9));
  CHECK(r.missed_count == 0);

  // The optimal assignment, not the greedy nearest pair (x1–y0 at 0.9 first would give 4.1):
  // x0–y0 1.1 + x1–y1 1.2 = 2.3, with c = 10.
  GospaOptions wide = o;
  wide.cutoff = 10.0;
  r = gospa.compute({origin, {2.0, 0.0}}, {{1.1, 0.0}, {3.2, 0.0}}, wide);
  CHECK(r.distance == Approx(2.3));
  CHECK(r.localisation == Approx(2.3));
}

TEST_CASE("gospa: closed cases with p = 2 and alpha != 2", "[gospa]") {
  Gospa gospa;
  GospaOptions o;
  o.order = 2.0;
  // A pair at 0.5 and a truth with no estimate: d² = 0.25 + 2²/2 = 2.25, d = 1.5.
  GospaResult r = gospa.compute({{0.0, 0.0}, {10.0, 0.0}}, {{0.3, 0.4}}, o);
  CHECK(r.distance == Approx(1.5));
  CHECK(r.localisation == Approx(0.25));
  CHECK(r.missed == Approx(2.0));
  CHECK(r.missed_count == 1);
  CHECK(r.false_count == 0);
  // A pair at distance 3 > c: (2² / 2 · 2)^(1/2) = 2.
  r = gospa.compute({{0.0, 0.0}}, {{0.0, 3.0}}, o);
  CHECK(r.distance == Approx(2.0));

  // α = 1, p = 2, no truth, two estimates: d² = 2²/1 · 2 = 8. The decomposition is NaN.
  o.alpha = 1.0;
  r = gospa.compute({}, {{1.0, 1.0}, {2.0, 2.0}}, o);
  CHECK(r.distance == Approx(std::sqrt(8.0)));
  CHECK(std::isnan(r.localisation));
  CHECK(std::isnan(r.missed));
  CHECK(std::isnan(r.false_targets));
  CHECK(r.missed_count == -1);
  CHECK(r.false_count == -1);
  // α = 1: a pair beyond the cut-off still counts c^p (Definition 1 pairs all of the smaller
  // set), not 2c^p/α: ‖(0,0) − (0,3)‖ → min(3, 2)² = 4, d = 2.
  r = gospa.compute({{0.0, 0.0}}, {{0.0, 3.0}}, o);
  CHECK(r.distance == Approx(2.0));
}

TEST_CASE("gospa: equals brute force on random small sets", "[gospa]") {
  Gospa gospa;
  std::uint32_t trial = 0;
  int cut_pairs = 0;  // α = 2 cases where γ is smaller than min(|X|, |Y|): a pair at ≥ c left out
  for (const GospaOptions& o : kParameterSets) {
    for (int nx = 0; nx <= 5; ++nx) {
      for (int ny = 0; ny <= 5; ++ny) {
        for (int repeat = 0; repeat < 6; ++repeat) {
          RandomStream rng(2017, 1, trial++);
          const bool grid = repeat % 2 == 1;
          const Points x = random_points(rng, nx, grid);
          const Points y = random_points(rng, ny, grid);
          const GospaResult r = gospa.compute(x, y, o);
          INFO("c " << o.cutoff << ", p " << o.order << ", alpha " << o.alpha << ", |X| " << nx << ", |Y| " << ny
                    << ", trial " << trial - 1);
          CHECK(r.distance == Approx(brute_force_gospa(x, y, o)).margin(1e-12));
          if (o.alpha == 2.0) {
            check_decomposition(r, x, y, o);
            CHECK(std::pow(r.distance, o.order) == Approx(brute_force_proposition1_power(x, y, o)).margin(1e-12));
            if (r.missed_count > std::max(0, nx - ny)) ++cut_pairs;
          } else {
            CHECK(std::isnan(r.localisation));
          }
        }
      }
    }
  }
  CHECK(cut_pairs > 50);  // the cut-off rule of Proposition 1 was exercised
}

TEST_CASE("gospa: symmetric, zero on equal sets, triangle inequality", "[gospa]") {
  Gospa gospa;
  std::uint32_t trial = 0;
  for (const GospaOptions& o : kParameterSets) {
    for (int repeat = 0; repeat < 60; ++repeat) {
      RandomStream rng(2017, 2, trial++);
      const bool grid = repeat % 3 == 0;
      const Points x = random_points(rng, static_cast<int>(rng.uniform() * 6), grid);
      const Points y = random_points(rng, static_cast<int>(rng.uniform() * 6), grid);
      const Points z = random_points(rng, static_cast<int>(rng.uniform() * 6), grid);
      INFO("c " << o.cutoff << ", p " << o.order << ", alpha " << o.alpha << ", trial " << trial - 1);
      const GospaResult xy = gospa.compute(x, y, o);
      const GospaResult yx = gospa.compute(y, x, o);
      CHECK(xy.distance == Approx(yx.distance).margin(1e-12));
      if (o.alpha == 2.0) {
        CHECK(xy.missed_count == yx.false_count);
        CHECK(xy.false_count == yx.missed_count);
        CHECK(xy.localisation == Approx(yx.localisation).margin(1e-12));
      }
      CHECK(gospa.compute(x, x, o).distance == 0.0);
      const double xz = gospa.compute(x, z, o).distance;
      const double yz = gospa.compute(y, z, o).distance;
      CHECK(xz <= xy.distance + yz + 1e-12);
      CHECK(xy.distance <= xz + yz + 1e-12);
    }
  }
}

TEST_CASE("gospa: one object reused gives the results of a fresh one", "[gospa]") {
  Gospa reused;
  for (std::uint32_t trial = 0; trial < 30; ++trial) {
    RandomStream rng(2017, 3, trial);
    const Points x = random_points(rng, static_cast<int>(trial % 9), false);
    const Points y = random_points(rng, static_cast<int>((trial * 7) % 9), false);
    const GospaOptions& o = kParameterSets[trial % kParameterSets.size()];
    Gospa fresh;
    const GospaResult a = reused.compute(x, y, o);
    const GospaResult b = fresh.compute(x, y, o);
    CHECK(a.distance == b.distance);
    CHECK(a.missed_count == b.missed_count);
    CHECK(a.false_count == b.false_count);
  }
}

TEST_CASE("gospa: options are validated, non-finite points rejected", "[gospa]") {
  Gospa gospa;
  const Points x = {{0.0, 0.0}};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  struct Bad {
    GospaOptions options;
    std::string field;
  };
  const std::vector<Bad> bad = {{{0.0, 1.0, 2.0}, "cutoff"},  {{-1.0, 1.0, 2.0}, "cutoff"}, {{inf, 1.0, 2.0}, "cutoff"},
                                {{nan, 1.0, 2.0}, "cutoff"},  {{2.0, 0.5, 2.0}, "order"},   {{2.0, inf, 2.0}, "order"},
                                {{2.0, nan, 2.0}, "order"},   {{2.0, 1.0, 0.0}, "alpha"},   {{2.0, 1.0, 2.5}, "alpha"},
                                {{2.0, 1.0, nan}, "alpha"}};
  for (const Bad& b : bad) {
    const std::string message = test::input_error_message([&] { gospa.compute(x, x, b.options); });
    CHECK_THAT(message, Catch::Contains("gospa: " + b.field + " must"));
  }
  CHECK_NOTHROW(GospaOptions{1e-3, 1.0, 1e-3}.validate());  // boundary: p = 1, small α, small c
  CHECK_NOTHROW(GospaOptions{2.0, 1.0, 2.0}.validate());

  CHECK_THROWS_AS(gospa.compute({{nan, 0.0}}, x), std::invalid_argument);
  CHECK_THROWS_AS(gospa.compute(x, {{0.0, 0.0}, {0.0, inf}}), std::invalid_argument);
}

}  // namespace DABENCH_TEST_FILE
