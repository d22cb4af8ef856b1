// Tests of harness/core/random_stream.hpp: Philox4x32-10 against the known-answer vectors of
// Random123 (tests/kat_vectors, "philox4x32 10" lines; columns CTR[4] KEY[2] -> OUT[4]), the
// (seed, point, trial) stream layout, and the distributions' moments (each within 5 standard
// errors, fixed seeds).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>
#include <tuple>
#include <vector>

#include "harness/core/random_stream.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench;

namespace {

struct Moments {
  double n = 0, sum = 0, sum2 = 0, sum3 = 0, sum4 = 0;
  void add(double x) {
    n += 1;
    sum += x;
    sum2 += x * x;
    sum3 += x * x * x;
    sum4 += x * x * x * x;
  }
  double mean() const { return sum / n; }
  double raw2() const { return sum2 / n; }
  double raw3() const { return sum3 / n; }
  double raw4() const { return sum4 / n; }
  double variance() const { return sum2 / n - mean() * mean(); }  // fine for the sizes used
};

// |estimate - expected| <= 5 standard errors.
void check_within_5se(double estimate, double expected, double standard_error, const char* what) {
  INFO(what << ": estimate " << estimate << ", expected " << expected << ", SE " << standard_error
            << ", z = " << (estimate - expected) / standard_error);
  CHECK(std::fabs(estimate - expected) <= 5.0 * standard_error);
}

}  // namespace

TEST_CASE("random: Philox4x32-10 known-answer vectors (Random123 kat_vectors)", "[random]") {
  struct Kat {
    Philox4x32::Block counter;
    Philox4x32::Key key;
    Philox4x32::Block expected;
  };
  const Kat kats[] = {
      {{0x00000000u, 0x00000000u, 0x00000000u, 0x00000000u}, {0x00000000u, 0x00000000u},
       {0x6627e8d5u, 0xe169c58du, 0xbc57ac4cu, 0x9b00dbd8u}},
      {{0xffffffffu, 0xffffffffu, 0xffffffffu, 0xffffffffu}, {0xffffffffu, 0xffffffffu},
       {0x408f276du, 0x41c83b0eu, 0xa20bc7c6u, 0x6d5451fdu}},
      {{0x243f6a88u, 0x85a308d3u, 0x13198a2eu, 0x03707344u}, {0xa4093822u, 0x299f31d0u},
       {0xd16cfe09u, 0x94fdccebu, 0x5001e420u, 0x24126ea1u}},
  };
  for (const Kat& kat : kats) {
    const Philox4x32::Block out = Philox4x32::generate(kat.counter, kat.key);
    INFO("counter " << std::hex << kat.counter[0] << " " << kat.counter[1] << " " << kat.counter[2] << " "
                    << kat.counter[3]);
    for (int w = 0; w < 4; ++w) CHECK(out[w] == kat.expected[w]);
  }
}

TEST_CASE("random: stream layout is pinned - seed gives the key and block/point/trial the counter", "[random]") {
  // Changing this layout changes every published trial: it must be a deliberate decision.
  const std::uint64_t seed = 0x0123456789abcdefULL;
  const Philox4x32::Key key{0x89abcdefu, 0x01234567u};
  RandomStream stream(seed, 17, 4242);
  for (std::uint32_t block = 0; block < 3; ++block) {
    const Philox4x32::Block out = Philox4x32::generate({block, 0u, 17u, 4242u}, key);
    CHECK(stream.next_u64() == ((std::uint64_t{out[0]} << 32) | out[1]));
    CHECK(stream.next_u64() == ((std::uint64_t{out[2]} << 32) | out[3]));
  }
}

TEST_CASE("random: streams are reproducible and distinct per seed/point/trial", "[random]") {
  const auto first = [](std::uint64_t seed, std::uint32_t point, std::uint32_t trial, int count) {
    RandomStream stream(seed, point, trial);
    std::vector<std::uint64_t> values(count);
    for (auto& v : values) v = stream.next_u64();
    return values;
  };
  CHECK(first(1, 2, 3, 1000) == first(1, 2, 3, 1000));
  // Interleaving other streams does not disturb one (no shared state).
  {
    RandomStream a(1, 2, 3), b(1, 2, 4);
    std::vector<std::uint64_t> values;
    for (int k = 0; k < 1000; ++k) {
      values.push_back(a.next_u64());
      b.next_u64();
      b.uniform();
    }
    CHECK(values == first(1, 2, 3, 1000));
  }
  // Different seed, point or trial: no value in common in the first 10000 of each (for
  // independent 64-bit streams a collision has probability ~1e-11).
  const std::vector<std::uint64_t> base = first(1, 2, 3, 10000);
  const std::set<std::uint64_t> base_set(base.begin(), base.end());
  CHECK(base_set.size() == base.size());
  for (const auto& [seed, point, trial] :
       {std::tuple{2ull, 2u, 3u}, std::tuple{1ull, 3u, 3u}, std::tuple{1ull, 2u, 4u}, std::tuple{1ull, 3u, 2u},
        std::tuple{1ull + (1ull << 32), 2u, 3u}, std::tuple{1ull, 0u, 0u}}) {
    INFO("seed " << seed << " point " << point << " trial " << trial);
    int common = 0;
    for (const std::uint64_t v : first(seed, point, trial, 10000)) common += static_cast<int>(base_set.count(v));
    CHECK(common == 0);
  }
  // (point, trial) = (2, 3) and (3, 2) must not be the same stream.
  CHECK(first(9, 2, 3, 4) != first(9, 3, 2, 4));
}

TEST_CASE("random: uniform on the unit interval with 53 random bits", "[random]") {
  RandomStream stream(2024, 1, 1);
  const int count = 1000000;
  Moments moments;
  int odd_last_bit = 0;
  double lowest = 1.0, highest = 0.0;
  for (int k = 0; k < count; ++k) {
    const double u = stream.uniform();
    REQUIRE(u >= 0.0);
    REQUIRE(u < 1.0);
    const double scaled = std::ldexp(u, 53);
    REQUIRE(scaled == std::floor(scaled));  // a multiple of 2^-53
    odd_last_bit += static_cast<int>(std::fmod(scaled, 2.0));
    lowest = std::min(lowest, u);
    highest = std::max(highest, u);
    moments.add(u - 0.5);
  }
  check_within_5se(moments.mean(), 0.0, std::sqrt(1.0 / 12.0 / count), "uniform mean - 1/2");
  // Var((U - 1/2)^2) = 1/80 - 1/144 = 1/180.
  check_within_5se(moments.raw2(), 1.0 / 12.0, std::sqrt(1.0 / 180.0 / count), "uniform variance");
  check_within_5se(odd_last_bit / double(count), 0.5, std::sqrt(0.25 / count), "lowest of 53 bits");
  CHECK(lowest < 1e-5);
  CHECK(highest > 1.0 - 1e-5);

  // uniform(lo, hi): range and mean.
  Moments shifted;
  for (int k = 0; k < 100000; ++k) {
    const double x = stream.uniform(-3.0, 5.0);
    REQUIRE(x >= -3.0);
    REQUIRE(x < 5.0);
    shifted.add(x);
  }
  check_within_5se(shifted.mean(), 1.0, std::sqrt(64.0 / 12.0 / 100000), "uniform(-3, 5) mean");
}

TEST_CASE("random: normal has the moments of a standard normal", "[random]") {
  RandomStream stream(77, 3, 9);
  const int count = 1000000;
  Moments moments;
  int inside_one = 0;
  double previous = 0.0, lag_product = 0.0;
  for (int k = 0; k < count; ++k) {
    const double x = stream.normal();
    REQUIRE(std::isfinite(x));
    moments.add(x);
    inside_one += std::fabs(x) < 1.0;
    if (k > 0) lag_product += x * previous;
    previous = x;
  }
  const double n = count;
  check_within_5se(moments.mean(), 0.0, std::sqrt(1.0 / n), "normal mean");
  check_within_5se(moments.raw2(), 1.0, std::sqrt(2.0 / n), "normal E[x^2]");        // Var(x^2) = 3 - 1
  check_within_5se(moments.raw3(), 0.0, std::sqrt(15.0 / n), "normal E[x^3]");       // E x^6 = 15
  check_within_5se(moments.raw4(), 3.0, std::sqrt(96.0 / n), "normal E[x^4]");       // 105 - 9
  const double p1 = 0.6826894921370859;  // P(|X| < 1)
  check_within_5se(inside_one / n, p1, std::sqrt(p1 * (1 - p1) / n), "normal P(|x| < 1)");
  // The polar method returns its two values in turn: consecutive draws must be uncorrelated.
  check_within_5se(lag_product / (n - 1), 0.0, std::sqrt(1.0 / (n - 1)), "normal lag-1 correlation");
}

TEST_CASE("random: poisson mean and variance and pmf on both branches", "[random]") {
  CHECK(RandomStream(1, 1, 1).poisson(0.0) == 0);
  CHECK(RandomStream(1, 1, 1).poisson(-2.0) == 0);

  // 0.5, 5, 11.9: inversion; 12.1, 50, 1000: PTRS (Hörmann 1993).
  std::uint32_t point = 0;
  for (const double mean : {0.5, 5.0, 11.9, 12.1, 50.0, 1000.0}) {
    RandomStream stream(31337, ++point, 0);
    const int count = 200000;
    Moments moments;
    std::vector<int> histogram(static_cast<std::size_t>(mean + 10.0 * std::sqrt(mean) + 20.0), 0);
    for (int k = 0; k < count; ++k) {
      const std::int64_t x = stream.poisson(mean);
      REQUIRE(x >= 0);
      moments.add(static_cast<double>(x) - mean);  // centred: keeps the sums well conditioned
      if (x < static_cast<std::int64_t>(histogram.size())) ++histogram[static_cast<std::size_t>(x)];
    }
    INFO("mean " << mean);
    const double n = count;
    check_within_5se(moments.mean() + mean, mean, std::sqrt(mean / n), "poisson mean");
    // Sample variance: Var(s^2) ≈ (μ4 - σ^4)/n with μ4 = λ(1 + 3λ), σ^4 = λ^2.
    check_within_5se(moments.variance(), mean, std::sqrt((mean + 2.0 * mean * mean) / n), "poisson variance");
    // pmf at every k within two standard deviations of the mean.
    const int lo = std::max(0, static_cast<int>(std::ceil(mean - 2.0 * std::sqrt(mean))));
    const int hi = static_cast<int>(std::floor(mean + 2.0 * std::sqrt(mean)));
    for (int k = lo; k <= hi; ++k) {
      const double p = std::exp(-mean + k * std::log(mean) - std::lgamma(k + 1.0));
      INFO("k = " << k);
      check_within_5se(histogram[static_cast<std::size_t>(k)] / n, p, std::sqrt(p * (1 - p) / n), "poisson pmf");
    }
  }
}

}  // namespace DABENCH_TEST_FILE
