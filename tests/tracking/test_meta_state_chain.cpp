// Tests of JDT-VB Module 2 (algorithms/tracking/meta_state_chain.hpp): forward–backward against brute-force
// enumeration of all 2^K meta-state sequences, the free-energy identity at the optimum, the
// filter step against the forward pass, and bad input.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "algorithms/tracking/meta_state_chain.hpp"
#include "harness/core/errors.hpp"

namespace DABENCH_TEST_FILE {

namespace {

using Evidence = std::vector<std::array<double, 2>>;

struct Enumerated {
  std::vector<double> active;
  std::vector<std::array<double, 4>> pairwise;
  double log_partition = 0.0;
};

// Sums eq (38) over every sequence s_{1:K}.
Enumerated enumerate(const Evidence& xi, double initial_active, double stay) {
  const int scans = static_cast<int>(xi.size());
  Enumerated e;
  e.active.assign(scans, 0.0);
  e.pairwise.assign(scans - 1, {0, 0, 0, 0});
  double total = 0.0;
  for (int mask = 0; mask < (1 << scans); ++mask) {
    auto s = [&](int k) { return (mask >> k) & 1; };
    double weight = (s(0) ? initial_active : 1.0 - initial_active) * std::exp(xi[0][s(0)]);
    for (int k = 1; k < scans; ++k) weight *= (s(k) == s(k - 1) ? stay : 1.0 - stay) * std::exp(xi[k][s(k)]);
    total += weight;
    for (int k = 0; k < scans; ++k) e.active[k] += s(k) * weight;
    for (int k = 0; k + 1 < scans; ++k) e.pairwise[k][2 * s(k) + s(k + 1)] += weight;
  }
  for (auto& a : e.active) a /= total;
  for (auto& p : e.pairwise)
    for (auto& v : p) v /= total;
  e.log_partition = std::log(total);
  return e;
}

Evidence random_evidence(std::mt19937_64& rng, int scans, bool with_impossible) {
  std::uniform_real_distribution<double> u(-6.0, 2.0);
  Evidence xi(scans);
  for (int k = 0; k < scans; ++k) {
    xi[k] = {u(rng), u(rng)};
    if (with_impossible && k % 3 == 1) xi[k][k % 2] = -HUGE_VAL;  // one state ruled out
  }
  return xi;
}

double xlogx(double p) { return p > 0.0 ? p * std::log(p) : 0.0; }

}  // namespace

TEST_CASE("meta-state chain: forward-backward equals enumeration of all sequences", "[meta_state]") {
  std::mt19937_64 rng(7);
  for (int scans : {1, 2, 3, 5, 8}) {
    for (double initial : {0.0, 0.25, 1.0}) {
      for (double stay : {0.85, 0.5, 0.1}) {
        const Evidence xi = random_evidence(rng, scans, scans >= 3);
        const Enumerated want = enumerate(xi, initial, stay);
        dabench::MetaStateChain got;
        dabench::meta_state_forward_backward(xi, initial, stay, got);
        REQUIRE(got.active.size() == static_cast<std::size_t>(scans));
        CHECK(got.log_partition == Approx(want.log_partition).epsilon(1e-12));
        for (int k = 0; k < scans; ++k) CHECK(got.active[k] == Approx(want.active[k]).margin(1e-12));
        for (int k = 0; k + 1 < scans; ++k)
          for (int c = 0; c < 4; ++c) CHECK(got.pairwise[k][c] == Approx(want.pairwise[k][c]).margin(1e-12));
      }
    }
  }
}

TEST_CASE("meta-state chain: huge evidence neither overflows nor loses the posterior", "[meta_state]") {
  // ξ of thousands of nats (e.g. many paths, tiny dormant p_d) would overflow e^ξ.
  const Evidence xi{{-3000.0, -2990.0}, {-4000.0, -4005.0}, {800.0, 790.0}};
  const Enumerated shifted = enumerate({{-10.0, 0.0}, {0.0, -5.0}, {10.0, 0.0}}, 0.4, 0.85);
  dabench::MetaStateChain got;
  dabench::meta_state_forward_backward(xi, 0.4, 0.85, got);
  for (int k = 0; k < 3; ++k) CHECK(got.active[k] == Approx(shifted.active[k]).margin(1e-12));
  CHECK(got.log_partition == Approx(shifted.log_partition - 2990.0 - 4000.0 + 790.0).epsilon(1e-13));
}

TEST_CASE("meta-state chain: at the optimum E[log p(S) + sum xi] + H(q) equals log Z", "[meta_state]") {
  std::mt19937_64 rng(11);
  const double stay = 0.85, initial = 0.3;
  const Evidence xi = random_evidence(rng, 12, false);
  dabench::MetaStateChain q;
  dabench::meta_state_forward_backward(xi, initial, stay, q);
  // Markov-chain entropy from pairwise and single marginals; expected log prior and evidence.
  double energy = (1.0 - q.active[0]) * std::log(1.0 - initial) + q.active[0] * std::log(initial);
  double entropy = 0.0;
  for (int k = 0; k < 12; ++k) energy += (1.0 - q.active[k]) * xi[k][0] + q.active[k] * xi[k][1];
  for (int k = 0; k < 11; ++k) {
    for (int c = 0; c < 4; ++c) {
      energy += q.pairwise[k][c] * std::log((c == 0 || c == 3) ? stay : 1.0 - stay);
      entropy -= xlogx(q.pairwise[k][c]);
    }
    if (k > 0) entropy += xlogx(q.active[k]) + xlogx(1.0 - q.active[k]);
  }
  CHECK(energy + entropy == Approx(q.log_partition).epsilon(1e-12));
}

TEST_CASE("meta-state chain: the filter step is the forward pass", "[meta_state]") {
  std::mt19937_64 rng(3);
  const Evidence xi = random_evidence(rng, 6, false);
  double filtered = 0.6;
  Evidence prefix;
  for (int k = 0; k < 6; ++k) {
    prefix.push_back(xi[k]);
    dabench::MetaStateChain q;
    dabench::meta_state_forward_backward(prefix, 0.6, 0.85, q);
    // The last scan's smoothed marginal is the filtered one.
    if (k == 0) {
      const double p1 = 0.6 * std::exp(xi[0][1]), p0 = 0.4 * std::exp(xi[0][0]);
      filtered = p1 / (p0 + p1);
    } else {
      filtered = dabench::meta_state_filter_step(filtered, 0.85, xi[k]);
    }
    CHECK(filtered == Approx(q.active[k]).margin(1e-13));
  }
}

TEST_CASE("meta-state chain: bad input is an InputError", "[meta_state]") {
  dabench::MetaStateChain q;
  CHECK_THROWS_AS(dabench::meta_state_forward_backward({{0.0, 0.0}}, 1.5, 0.85, q), dabench::InputError);
  CHECK_THROWS_AS(dabench::meta_state_forward_backward({{0.0, 0.0}}, 0.5, 1.0, q), dabench::InputError);
  CHECK_THROWS_AS(dabench::meta_state_forward_backward({{NAN, 0.0}}, 0.5, 0.85, q), dabench::InputError);
  CHECK_THROWS_AS(dabench::meta_state_forward_backward({{-HUGE_VAL, -HUGE_VAL}}, 0.5, 0.85, q), dabench::InputError);
  // p(s_1 = 1) = 1 with the active state ruled out at scan 1: no sequence is possible.
  CHECK_THROWS_AS(dabench::meta_state_forward_backward({{0.0, -HUGE_VAL}}, 1.0, 0.85, q), dabench::InputError);
}

}  // namespace DABENCH_TEST_FILE
