// Tests of algorithms/assignment/murty.hpp: Murty's k best events against a sorted exhaustive
// enumeration of every event (each row a column or a miss, columns distinct) on small random
// problems with negative costs, forbidden pairs, forbidden misses and many ties; a hand-ranked
// 2×2 problem; k above the number of feasible events; independent clusters ranked apart and
// merged by RankedListMerge against one Murty on the whole problem; determinism; bad input.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <set>
#include <span>
#include <vector>

#include "algorithms/assignment/murty.hpp"
#include "harness/core/random_stream.hpp"
#include "tests/support/cost_matrix.hpp"
#include "tests/support/input_error.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench;

namespace {

using dabench::test::CostMatrix;
using dabench::test::kInf;

// A cost matrix and each row's cost of a miss (j = −1; +∞: the row must take a column).
struct Problem : CostMatrix {
  std::vector<double> miss;  // rows
  double at(int r, int j) const { return j < 0 ? miss[r] : CostMatrix::at(r, j); }
};

struct Event {
  double cost;
  std::vector<int> columns;
};

// Every event with a finite cost, summed in row order (as Murty sums), sorted by cost.
std::vector<Event> enumerate_events(const Problem& p) {
  std::vector<Event> events;
  std::vector<int> a(p.rows, -1);
  while (true) {
    std::vector<char> used(p.cols, 0);
    bool valid = true;
    double total = 0.0;
    for (int r = 0; r < p.rows && valid; ++r) {
      if (a[r] >= 0 && used[a[r]]++) valid = false;
      total += p.at(r, a[r]);
    }
    if (valid && total < kInf) events.push_back({total, a});
    int r = 0;  // odometer over {-1, ..., cols-1}^rows
    while (r < p.rows && ++a[r] == p.cols) a[r++] = -1;
    if (r == p.rows) break;
  }
  std::stable_sort(events.begin(), events.end(), [](const Event& x, const Event& y) { return x.cost < y.cost; });
  return events;
}

Problem random_problem(RandomStream& rng, int rows, int cols, bool integers, double forbid_pair, double forbid_miss) {
  Problem p{rows, cols, std::vector<double>(static_cast<std::size_t>(rows) * cols), std::vector<double>(rows)};
  const auto draw = [&] { return integers ? std::floor(rng.uniform(0.0, 3.0)) : rng.uniform(-3.0, 3.0); };
  for (double& c : p.cost) c = rng.bernoulli(forbid_pair) ? kInf : draw();
  for (double& m : p.miss) m = rng.bernoulli(forbid_miss) ? kInf : draw();
  return p;
}

void solve(MurtyRanking& murty, const Problem& p, int k, RankedAssignments& out) {
  murty.solve(p.cost.data(), p.miss.data(), p.rows, p.cols, k, out);
}

// Murty's list is a correct top-k: k' = min(k, #events) distinct valid events whose costs are
// their recomputed costs and equal the k' smallest costs of the enumeration (this allows any
// order among tied events).
void check_against_enumeration(MurtyRanking& murty, const Problem& p, int k) {
  const std::vector<Event> all = enumerate_events(p);
  RankedAssignments out;
  solve(murty, p, k, out);
  REQUIRE(out.size() == std::min<int>(k, static_cast<int>(all.size())));
  REQUIRE(out.rows() == p.rows);
  std::set<std::vector<int>> seen;
  for (int i = 0; i < out.size(); ++i) {
    const std::span<const int> columns = out.columns(i);
    std::vector<char> used(p.cols, 0);
    double total = 0.0;
    for (int r = 0; r < p.rows; ++r) {
      REQUIRE(columns[r] >= -1);
      REQUIRE(columns[r] < p.cols);
      if (columns[r] >= 0) REQUIRE(used[columns[r]]++ == 0);
      total += p.at(r, columns[r]);
    }
    REQUIRE(total < kInf);
    REQUIRE(out.cost(i) == total);
    REQUIRE(out.cost(i) == all[i].cost);
    REQUIRE(seen.insert({columns.begin(), columns.end()}).second);
  }
}

}  // namespace

TEST_CASE("murty: a hand-ranked 2x2 problem", "[murty]") {
  // Events (row 0, row 1) and costs: (0,1) 3, (0,-) 4, (-,1) 5, (-,-) 6, (-,0) 7, (1,-) 8, (1,0) 9.
  const Problem p{2, 2, {1, 5, 4, 2}, {3, 3}};
  MurtyRanking murty;
  RankedAssignments out;
  solve(murty, p, 100, out);
  REQUIRE(out.size() == 7);
  const std::vector<std::vector<int>> expected{{0, 1}, {0, -1}, {-1, 1}, {-1, -1}, {-1, 0}, {1, -1}, {1, 0}};
  for (int i = 0; i < 7; ++i) {
    CHECK(out.cost(i) == 3.0 + i);
    CHECK(std::vector<int>(out.columns(i).begin(), out.columns(i).end()) == expected[i]);
  }
  // k = 2 stops after the second best; forbidding row 0's miss removes every event where row 0
  // misses: (-,1), (-,-), (-,0).
  solve(murty, p, 2, out);
  CHECK(out.size() == 2);
  CHECK(out.cost(1) == 4.0);
  const Problem no_miss{2, 2, {1, 5, 4, 2}, {kInf, 3}};
  solve(murty, no_miss, 100, out);
  REQUIRE(out.size() == 4);
  CHECK(out.cost(0) == 3.0);
  CHECK(out.cost(1) == 4.0);
  CHECK(out.cost(2) == 8.0);
  CHECK(out.cost(3) == 9.0);
}

TEST_CASE("murty: top-k equals sorted exhaustive enumeration on random problems", "[murty]") {
  MurtyRanking murty;  // one object throughout: state must not leak between solves
  std::uint32_t trial = 0;
  int infeasible = 0;
  for (int rows = 0; rows <= 5; ++rows) {
    for (int cols = 0; cols <= 5; ++cols) {
      for (const double forbid_pair : {0.0, 0.4}) {
        for (const double forbid_miss : {0.0, 0.5, 1.0}) {
          for (const bool integers : {false, true}) {
            RandomStream rng(1968, 2, trial++);
            const Problem p = random_problem(rng, rows, cols, integers, forbid_pair, forbid_miss);
            if (enumerate_events(p).empty()) ++infeasible;
            for (const int k : {1, 2, 7, 40, 100000}) check_against_enumeration(murty, p, k);
          }
        }
      }
    }
  }
  CHECK(infeasible > 10);  // infeasible problems (every miss forbidden, too few columns) were tried
}

TEST_CASE("murty: k above the number of feasible events returns all of them", "[murty]") {
  MurtyRanking murty;
  RankedAssignments out;
  // 3×3, everything allowed: Σ_m C(3,m)·3!/(3-m)! = 1 + 9 + 18 + 6 = 34 events.
  const Problem open{3, 3, {1, 2, 3, 4, 5, 6, 7, 8, 9}, {0, 0, 0}};
  solve(murty, open, 1000, out);
  CHECK(out.size() == 34);
  // Misses forbidden: the 3! permutations, all of cost 15 (c(r, j) = 3r + j + 1 is additive).
  const Problem full{3, 3, {1, 2, 3, 4, 5, 6, 7, 8, 9}, {kInf, kInf, kInf}};
  solve(murty, full, 1000, out);
  REQUIRE(out.size() == 6);
  for (int i = 0; i < 6; ++i) CHECK(out.cost(i) == 15.0);
  // Three rows, two columns, no miss allowed: infeasible, no event.
  const Problem tall{3, 2, {1, 2, 3, 4, 5, 6}, {kInf, kInf, kInf}};
  solve(murty, tall, 5, out);
  CHECK(out.size() == 0);
  // No rows: one empty event of cost 0; rows but no columns: the all-miss event.
  solve(murty, Problem{0, 4, {}, {}}, 3, out);
  REQUIRE(out.size() == 1);
  CHECK(out.cost(0) == 0.0);
  solve(murty, Problem{2, 0, {}, {1.5, 2.0}}, 3, out);
  REQUIRE(out.size() == 1);
  CHECK(out.cost(0) == 3.5);
}

TEST_CASE("murty: ties are ranked deterministically", "[murty]") {
  for (std::uint32_t trial = 0; trial < 20; ++trial) {
    RandomStream rng(1968, 3, trial);
    const Problem p = random_problem(rng, 5, 5, true, 0.2, 0.2);  // costs in {0, 1, 2}: many ties
    MurtyRanking first;
    MurtyRanking reused;
    RankedAssignments a;
    RankedAssignments b;
    solve(first, p, 30, a);
    solve(reused, random_problem(rng, 4, 6, false, 0.3, 0.3), 30, b);  // dirty the second object
    solve(reused, p, 30, b);
    REQUIRE(a.size() == b.size());
    for (int i = 0; i < a.size(); ++i) {
      CHECK(a.cost(i) == b.cost(i));
      CHECK(std::equal(a.columns(i).begin(), a.columns(i).end(), b.columns(i).begin()));
    }
    check_against_enumeration(first, p, 30);
  }
}

TEST_CASE("murty: independent clusters ranked apart and merged equal one Murty", "[murty]") {
  MurtyRanking murty;
  RankedListMerge merger;
  for (std::uint32_t trial = 0; trial < 40; ++trial) {
    RandomStream rng(1968, 4, trial);
    // 1-4 clusters of 1-3 rows and 0-3 columns, interleaved in the whole problem by random
    // permutations of rows and columns; pairs across clusters are +inf.
    const int clusters = 1 + static_cast<int>(rng.uniform() * 4);
    std::vector<Problem> parts;
    std::vector<int> row_cluster;
    std::vector<int> col_cluster;
    for (int c = 0; c < clusters; ++c) {
      const int rows = 1 + static_cast<int>(rng.uniform() * 3);
      const int cols = static_cast<int>(rng.uniform() * 4);
      parts.push_back(random_problem(rng, rows, cols, false, 0.3, 0.3));
      row_cluster.insert(row_cluster.end(), rows, c);
      col_cluster.insert(col_cluster.end(), cols, c);
    }
    const auto shuffle = [&](std::vector<int>& v) {
      for (std::size_t i = v.size(); i > 1; --i) std::swap(v[i - 1], v[static_cast<std::size_t>(rng.uniform() * static_cast<double>(i))]);
    };
    shuffle(row_cluster);
    shuffle(col_cluster);
    const int rows = static_cast<int>(row_cluster.size());
    const int cols = static_cast<int>(col_cluster.size());
    std::vector<int> local_row(rows);
    std::vector<int> local_col(cols);
    std::vector<std::vector<int>> global_col(clusters);
    std::vector<int> next_row(clusters, 0);
    for (int r = 0; r < rows; ++r) local_row[r] = next_row[row_cluster[r]]++;
    for (int j = 0; j < cols; ++j) {
      local_col[j] = static_cast<int>(global_col[col_cluster[j]].size());
      global_col[col_cluster[j]].push_back(j);
    }
    Problem whole{rows, cols, std::vector<double>(static_cast<std::size_t>(rows) * cols, kInf), std::vector<double>(rows)};
    for (int r = 0; r < rows; ++r) {
      const Problem& part = parts[row_cluster[r]];
      whole.miss[r] = part.miss[local_row[r]];
      for (int j = 0; j < cols; ++j) {
        if (col_cluster[j] == row_cluster[r]) whole.cost[static_cast<std::size_t>(r) * cols + j] = part.at(local_row[r], local_col[j]);
      }
    }

    const int k = 25;
    std::vector<RankedAssignments> ranked(clusters);
    std::vector<std::span<const double>> lists;
    for (int c = 0; c < clusters; ++c) {
      solve(murty, parts[c], k, ranked[c]);
      lists.push_back(ranked[c].costs());
    }
    std::vector<double> total;
    std::vector<int> choices;
    merger.merge(lists, k, total, choices);
    RankedAssignments big;
    solve(murty, whole, k, big);
    if (std::pow(cols + 1.0, rows) <= 2e4) check_against_enumeration(murty, whole, k);  // small enough to enumerate

    REQUIRE(static_cast<int>(total.size()) == big.size());
    for (int i = 0; i < big.size(); ++i) {
      CHECK(total[i] == Approx(big.cost(i)).margin(1e-12));
      // The merged event in the whole problem's indices (random real costs: no ties).
      for (int r = 0; r < rows; ++r) {
        const int c = row_cluster[r];
        const int local = ranked[c].columns(choices[static_cast<std::size_t>(i) * clusters + c])[local_row[r]];
        CHECK((local < 0 ? -1 : global_col[c][local]) == big.columns(i)[r]);
      }
    }
  }
}

TEST_CASE("ranked list merge: hand-checked sums and edge cases", "[murty]") {
  RankedListMerge merger;
  std::vector<double> total;
  std::vector<int> choices;
  const std::vector<double> a{0, 1, 5};
  const std::vector<double> b{0, 2};
  const std::vector<std::span<const double>> lists{a, b};
  merger.merge(lists, 100, total, choices);
  CHECK(total == std::vector<double>{0, 1, 2, 3, 5, 7});
  CHECK(choices == std::vector<int>{0, 0, 1, 0, 0, 1, 1, 1, 2, 0, 2, 1});
  merger.merge(lists, 3, total, choices);
  CHECK(total == std::vector<double>{0, 1, 2});
  const std::vector<double> empty;
  merger.merge(std::vector<std::span<const double>>{a, empty}, 5, total, choices);
  CHECK(total.empty());
  merger.merge({}, 5, total, choices);
  CHECK(total == std::vector<double>{0});
}

TEST_CASE("murty: bad input is a one-line InputError", "[murty]") {
  MurtyRanking murty;
  RankedAssignments out;
  RankedListMerge merger;
  std::vector<double> total;
  std::vector<int> choices;
  const std::vector<double> cost{1, std::nan(""), 2, 3};
  const std::vector<double> miss{0, 0};
  CHECK(test::input_error_message([&] { murty.solve(cost.data(), miss.data(), 2, 2, 3, out); }) ==
        "murty: cost(0, 1) is NaN (costs must be finite or +inf)");
  const std::vector<double> fine{1, 2, 2, 3};
  const std::vector<double> bad_miss{0, -kInf};
  CHECK(test::input_error_message([&] { murty.solve(fine.data(), bad_miss.data(), 2, 2, 3, out); }) ==
        "murty: miss_cost(1) is -inf (costs must be finite or +inf)");
  CHECK(test::input_error_message([&] { murty.solve(fine.data(), miss.data(), 2, 2, 0, out); }) ==
        "murty: k must be at least 1 (got 0)");
  CHECK(test::input_error_message([&] { murty.solve(fine.data(), miss.data(), -1, 2, 1, out); }) ==
        "murty: negative problem size (-1 x 2)");
  CHECK(test::input_error_message([&] { merger.merge({}, -2, total, choices); }) ==
        "ranked list merge: k must be at least 1 (got -2)");
}

}  // namespace DABENCH_TEST_FILE
