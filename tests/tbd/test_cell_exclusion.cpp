// Tests of TBD-MB's exclusivity sum-product (algorithms/tbd/cell_exclusion.hpp):
//  - On tree-shaped graphs (any two nodes share at most one cell, no cycle through the cells)
//    the beliefs equal the exact marginals by enumeration of every node's particle or absence
//    under "each cell covered by at most one present object": existence and particle weights,
//    random weights and existences, a certain node among them.
//  - A loopy case (two nodes sharing a block of cells) converges and stays a probability
//    assignment that respects exclusivity better than the nodes alone.
//  - The messages at a particle's position are what its posterior weight carries:
//    posterior_p ∝ a_p exp(log_message_at(x_p)).
//  - A lone node is its own Bayes update (ν ≡ 1).
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "algorithms/tbd/cell_exclusion.hpp"
#include "harness/core/random_stream.hpp"
#include "harness/tbd/problem.hpp"

namespace DABENCH_TEST_FILE {

namespace {

using dabench::CellExclusion;
using dabench::RandomStream;
using dabench::TbdSensor;

struct TestNode {
  std::vector<double> x, y, log_weight;
  double existence = 0.5;
};

TbdSensor row_sensor(int columns, int rows) {
  TbdSensor s;
  s.columns = columns;
  s.rows = rows;
  return s;
}

// Cells whose centre is within `radius` of (px, py), by scanning every cell.
std::vector<int> support(const TbdSensor& s, double radius, double px, double py) {
  std::vector<int> cells;
  for (int row = 0; row < s.rows; ++row) {
    for (int column = 0; column < s.columns; ++column) {
      const double dx = s.centre_x(column) - px, dy = s.centre_y(row) - py;
      if (dx * dx + dy * dy <= radius * radius) cells.push_back(row * s.columns + column);
    }
  }
  return cells;
}

// Exact marginals: every node absent or at one of its particles, configurations where a cell
// is covered twice excluded. existence[i] and weights[i][p] (normalised given presence).
void enumerate(const TbdSensor& s, double radius, const std::vector<TestNode>& nodes, std::vector<double>& existence,
               std::vector<std::vector<double>>& weights) {
  const int n = static_cast<int>(nodes.size());
  existence.assign(n, 0.0);
  weights.assign(n, {});
  for (int i = 0; i < n; ++i) weights[i].assign(nodes[i].x.size(), 0.0);
  std::vector<int> choice(n, -1);  // −1: absent
  double normaliser = 0.0;
  while (true) {
    std::vector<int> count(s.cells(), 0);
    double w = 1.0;
    bool valid = true;
    for (int i = 0; i < n && valid; ++i) {
      if (choice[i] < 0) {
        w *= 1.0 - nodes[i].existence;
        continue;
      }
      w *= nodes[i].existence * std::exp(nodes[i].log_weight[choice[i]]);
      for (const int c : support(s, radius, nodes[i].x[choice[i]], nodes[i].y[choice[i]])) valid &= ++count[c] <= 1;
    }
    if (valid && w > 0.0) {
      normaliser += w;
      for (int i = 0; i < n; ++i) {
        if (choice[i] >= 0) {
          existence[i] += w;
          weights[i][choice[i]] += w;
        }
      }
    }
    int i = 0;
    while (i < n && ++choice[i] == static_cast<int>(nodes[i].x.size())) choice[i++] = -1;
    if (i == n) break;
  }
  for (int i = 0; i < n; ++i) {
    for (double& v : weights[i]) v /= existence[i];
    existence[i] /= normaliser;
  }
}

void load(CellExclusion& exclusion, const TbdSensor& s, double radius, const std::vector<TestNode>& nodes) {
  exclusion.reset(s, radius);
  for (const TestNode& node : nodes) {
    exclusion.add(node.x.data(), node.y.data(), node.log_weight.data(), static_cast<int>(node.x.size()),
                  node.existence);
  }
}

// A node on a row of cells (y = 0.5): particles at the centre of cell a, the midpoint of cells
// a and a + 1, and the centre of cell a + 1 (with radius 0.6 they cover {a}, {a, a+1}, {a+1}).
TestNode chain_node(int a, RandomStream& rng, double existence) {
  TestNode node;
  for (const double px : {a + 0.5, a + 1.0, a + 1.5}) {
    node.x.push_back(px);
    node.y.push_back(0.5);
    node.log_weight.push_back(std::log(0.05 + rng.uniform()) + 1.0);  // w_p ℓ_p, ℓ around e
  }
  node.existence = existence;
  return node;
}

}  // namespace

TEST_CASE("cell exclusion: on a tree the sum-product beliefs are the exact marginals", "[tbd][cell_exclusion]") {
  const double radius = 0.6;
  const TbdSensor s = row_sensor(8, 1);
  RandomStream rng(77, 0, 0);
  for (int trial = 0; trial < 20; ++trial) {
    INFO("trial " << trial);
    // A–cell1–B–cell2–C: nodes on cells {0,1}, {1,2}, {2,3}; sometimes a fourth on {4,5} alone.
    std::vector<TestNode> nodes;
    for (int i = 0; i < 3; ++i) nodes.push_back(chain_node(i, rng, 0.05 + 0.9 * rng.uniform()));
    if (trial % 4 == 1) nodes[1].existence = 1.0;  // a certain object in the middle
    if (trial % 2 == 0) nodes.push_back(chain_node(4, rng, 0.5));
    CellExclusion exclusion;
    load(exclusion, s, radius, nodes);
    exclusion.solve(200, 1e-13);
    REQUIRE(exclusion.converged());
    std::vector<double> existence;
    std::vector<std::vector<double>> weights;
    enumerate(s, radius, nodes, existence, weights);
    std::vector<double> posterior;
    for (int i = 0; i < static_cast<int>(nodes.size()); ++i) {
      CHECK(exclusion.existence(i) == Approx(existence[i]).margin(1e-10));
      exclusion.posterior_weights(i, posterior);
      for (std::size_t p = 0; p < posterior.size(); ++p) CHECK(posterior[p] == Approx(weights[i][p]).margin(1e-10));
    }
  }
}

TEST_CASE("cell exclusion: a loopy pair converges to a distribution that respects exclusivity",
          "[tbd][cell_exclusion]") {
  // Two nodes with every particle near cell (2, 2), radius 1: they share the whole block.
  const TbdSensor s = row_sensor(6, 6);
  RandomStream rng(78, 0, 0);
  std::vector<TestNode> nodes(2);
  for (TestNode& node : nodes) {
    for (int p = 0; p < 6; ++p) {
      node.x.push_back(2.5 + 0.4 * (rng.uniform() - 0.5));
      node.y.push_back(2.5 + 0.4 * (rng.uniform() - 0.5));
      node.log_weight.push_back(std::log(rng.uniform() + 0.1));
    }
    double mass = 0.0;  // Σ_p w_p ℓ_p = 1: the data neither for nor against presence
    for (const double l : node.log_weight) mass += std::exp(l);
    for (double& l : node.log_weight) l -= std::log(mass);
    node.existence = 0.9;
  }
  CellExclusion exclusion;
  load(exclusion, s, 1.0, nodes);
  exclusion.solve(500, 1e-12);
  CHECK(exclusion.converged());
  // Both always cover cell (2, 2): exactly, P(both) = 0, P(A) = P(B) = 0.9·0.1/(0.9·0.1·2 + 0.01).
  std::vector<double> existence;
  std::vector<std::vector<double>> weights;
  enumerate(s, 1.0, nodes, existence, weights);
  CHECK(existence[0] == Approx(0.09 / 0.19).epsilon(1e-12));
  for (int i = 0; i < 2; ++i) {
    CHECK(exclusion.existence(i) < 0.9);
    CHECK(exclusion.existence(i) == Approx(existence[i]).margin(0.1));  // loopy: approximate
  }
  CHECK(exclusion.existence(0) + exclusion.existence(1) < 1.05);
}

TEST_CASE("cell exclusion: posterior weights carry the messages at the particles; a lone node is Bayes",
          "[tbd][cell_exclusion]") {
  const double radius = 0.6;
  const TbdSensor s = row_sensor(8, 1);
  RandomStream rng(79, 0, 0);
  std::vector<TestNode> nodes{chain_node(0, rng, 0.7), chain_node(1, rng, 0.6), chain_node(2, rng, 0.8)};
  CellExclusion exclusion;
  load(exclusion, s, radius, nodes);
  exclusion.solve(200, 1e-13);
  std::vector<double> posterior;
  for (int i = 0; i < 3; ++i) {
    exclusion.posterior_weights(i, posterior);
    double sum = 0.0;
    std::vector<double> expected(posterior.size());
    for (std::size_t p = 0; p < posterior.size(); ++p) {
      sum += expected[p] = std::exp(nodes[i].log_weight[p] + exclusion.log_message_at(i, nodes[i].x[p], nodes[i].y[p]));
    }
    for (std::size_t p = 0; p < posterior.size(); ++p) CHECK(posterior[p] == Approx(expected[p] / sum).epsilon(1e-12));
  }
  CHECK(exclusion.log_message_at(1, 1.5, 0.5) < 0.0);  // cell 1 is contested by node 0
  CHECK(exclusion.log_message_at(0, 7.5, 0.5) == 0.0);  // outside its window: ν = 1

  // One node: ν ≡ 1, r̃ = r Σ a / (r Σ a + 1 − r).
  CellExclusion lone;
  load(lone, s, radius, {nodes[0]});
  CHECK(lone.solve(10, 1e-13) == 2);  // its π, then the sweep that finds nothing changed
  double mass = 0.0;
  for (const double l : nodes[0].log_weight) mass += std::exp(l);
  CHECK(lone.existence(0) == Approx(0.7 * mass / (0.7 * mass + 0.3)).epsilon(1e-14));
}

}  // namespace DABENCH_TEST_FILE
