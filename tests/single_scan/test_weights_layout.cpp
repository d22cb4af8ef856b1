// Weight layouts of other tracking code (harness/single_scan/weights_layout.hpp): each layout of
// one problem, in weights and in logs, gives dabench's ψ; MATLAB's documented jpdaEvents example
// gives its documented event probabilities; malformed matrices are one-line errors; and
// `dabench solve --layout` reads them.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "harness/single_scan/weights_layout.hpp"
#include "tests/support/cli_runner.hpp"
#include "tests/support/input_error.hpp"

namespace DABENCH_TEST_FILE {

using dabench::RowMatrix;
using dabench::Vector;
using dabench::WeightsFormat;
using dabench::WeightsLayout;

namespace {

// One problem in every layout: ψ (n × m, some entries 0) with missed-detection weights w_i0 and
// clutter weights w_0j that the layouts carry (those without clutter weights fold them into w_ij).
struct LayoutCase {
  RowMatrix psi, stonesoup, tcl, matlab;
};

LayoutCase random_case(std::mt19937_64& rng, int n, int m) {
  std::uniform_real_distribution<double> weight(0.05, 40.0), side(0.1, 3.0), coin(0.0, 1.0);
  LayoutCase c;
  c.psi.resize(n, m);
  Vector miss(n), clutter(m);
  for (int i = 0; i < n; ++i) miss[i] = side(rng);
  for (int j = 0; j < m; ++j) clutter[j] = side(rng);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) c.psi(i, j) = coin(rng) < 0.25 ? 0.0 : weight(rng);
  }
  c.stonesoup.resize(n, m + 1);
  c.tcl = RowMatrix::Zero(n, m + n);
  c.matlab.resize(m + 1, n + 1);
  c.matlab(0, 0) = 7.0;  // ignored
  for (int i = 0; i < n; ++i) {
    c.stonesoup(i, 0) = miss[i];
    c.tcl(i, m + i) = miss[i];
    c.matlab(0, i + 1) = miss[i];
    for (int j = 0; j < m; ++j) {
      c.stonesoup(i, j + 1) = c.psi(i, j) * miss[i];
      c.tcl(i, j) = c.psi(i, j) * miss[i];
      c.matlab(j + 1, i + 1) = c.psi(i, j) * miss[i] * clutter[j];
    }
  }
  for (int j = 0; j < m; ++j) c.matlab(j + 1, 0) = clutter[j];
  return c;
}

RowMatrix logs(const RowMatrix& weights) { return weights.array().log().matrix(); }

void check_same_psi(const RowMatrix& ours, const RowMatrix& expected) {
  REQUIRE(ours.rows() == expected.rows());
  REQUIRE(ours.cols() == expected.cols());
  for (Eigen::Index i = 0; i < ours.rows(); ++i) {
    for (Eigen::Index j = 0; j < ours.cols(); ++j) {
      INFO("psi(" << i << ", " << j << ") = " << ours(i, j) << ", expected " << expected(i, j));
      CHECK(std::abs(ours(i, j) - expected(i, j)) <= 1e-13 * expected(i, j));
    }
  }
}

}  // namespace

TEST_CASE("weights layouts: every layout of a problem, in weights or logs, gives its psi", "[layout]") {
  std::mt19937_64 rng(29);
  for (int trial = 0; trial < 60; ++trial) {
    const int n = 1 + trial % 4, m = (trial / 4) % 5;
    const LayoutCase c = random_case(rng, n, m);
    INFO("n " << n << ", m " << m << ", trial " << trial);
    const auto psi_of = [](const RowMatrix& matrix, WeightsLayout layout, bool log) {
      return dabench::problem_from_weights(matrix, WeightsFormat{layout, log}, "test").psi;
    };
    CHECK(psi_of(c.psi, WeightsLayout::psi, false) == c.psi);  // bit for bit
    check_same_psi(psi_of(c.stonesoup, WeightsLayout::stonesoup, false), c.psi);
    check_same_psi(psi_of(c.tcl, WeightsLayout::tcl, false), c.psi);
    check_same_psi(psi_of(c.matlab, WeightsLayout::matlab, false), c.psi);
    check_same_psi(psi_of(logs(c.psi), WeightsLayout::psi, true), c.psi);
    check_same_psi(psi_of(logs(c.stonesoup), WeightsLayout::stonesoup, true), c.psi);
    check_same_psi(psi_of(logs(c.tcl), WeightsLayout::tcl, true), c.psi);
    check_same_psi(psi_of(logs(c.matlab), WeightsLayout::matlab, true), c.psi);
  }
}

TEST_CASE("weights layouts: MATLAB's jpdaEvents example gives its three best events' probabilities", "[layout]") {
  // jpdaEvents' documentation: four detections, two tracks, likeMatrix below; the three most
  // probable feasible joint events have normalised probabilities 0.4286, 0.2857, 0.2857.
  RowMatrix like(5, 3);
  like << 0.1, 0.1, 0.1,  //
      0.1, 0.3, 0.2,      //
      0.1, 0.4, 0.1,      //
      0.1, 0.6, 0.1,      //
      0.1, 0.5, 0.3;
  const RowMatrix psi = dabench::problem_from_weights(like, {WeightsLayout::matlab, false}, "jpdaEvents").psi;
  REQUIRE(psi.rows() == 2);
  REQUIRE(psi.cols() == 4);
  // Every joint event of two targets (0 = missed) by brute force, the weight Π ψ_i(a_i).
  std::vector<double> events;
  for (int a = 0; a <= 4; ++a) {
    for (int b = 0; b <= 4; ++b) {
      if (a != 0 && a == b) continue;
      events.push_back((a ? psi(0, a - 1) : 1.0) * (b ? psi(1, b - 1) : 1.0));
    }
  }
  std::sort(events.begin(), events.end(), std::greater<>());
  const double top3 = events[0] + events[1] + events[2];
  CHECK(events[0] / top3 == Approx(0.4286).margin(5e-5));
  CHECK(events[1] / top3 == Approx(0.2857).margin(5e-5));
  CHECK(events[2] / top3 == Approx(0.2857).margin(5e-5));
}

TEST_CASE("weights layouts: malformed matrices are one-line errors naming row and column", "[layout]") {
  using dabench::test::input_error_message;
  const auto error = [](RowMatrix matrix, WeightsLayout layout, bool log = false) {
    return input_error_message([&] { dabench::problem_from_weights(matrix, {layout, log}, "w.csv"); });
  };
  const double inf = std::numeric_limits<double>::infinity();
  RowMatrix stonesoup(1, 3);
  stonesoup << 0.0, 1.0, 2.0;
  // A missed-detection weight of 0 is a target that must be detected (test_must_detect.cpp).
  CHECK(dabench::problem_from_weights(stonesoup, {WeightsLayout::stonesoup, false}, "w.csv").must_detect(0));
  RowMatrix tcl(2, 3);
  tcl << 1.0, 0.5, 0.3, 1.0, 0.0, 0.5;
  CHECK_THAT(error(tcl, WeightsLayout::tcl), Catch::Contains("w.csv:1: column 3") && Catch::Contains("off-diagonal"));
  CHECK_THAT(error(RowMatrix::Ones(3, 2), WeightsLayout::tcl), Catch::Contains("2 columns for 3 targets"));
  RowMatrix matlab(2, 2);
  matlab << 1.0, 0.5, 0.0, 2.0;
  CHECK_THAT(error(matlab, WeightsLayout::matlab), Catch::Contains("w.csv:2: column 1") && Catch::Contains("clutter weight is 0"));
  CHECK_THAT(error(RowMatrix::Ones(2, 1), WeightsLayout::matlab), Catch::Contains("no target"));
  RowMatrix negative(1, 2);
  negative << 1.0, -2.0;
  CHECK_THAT(error(negative, WeightsLayout::psi), Catch::Contains("w.csv:1: column 2: weight -2 is negative"));
  CHECK_NOTHROW(dabench::problem_from_weights(negative, {WeightsLayout::psi, true}, "w.csv"));  // log 2 below 1
  RowMatrix log_inf(1, 2);
  log_inf << 0.0, inf;
  CHECK_THAT(error(log_inf, WeightsLayout::psi, true), Catch::Contains("column 2: log weight inf is not finite"));
  log_inf(0, 1) = -inf;  // a weight of 0: not gated
  CHECK(dabench::problem_from_weights(log_inf, {WeightsLayout::psi, true}, "w.csv").psi(0, 1) == 0.0);
  RowMatrix nan(1, 1);
  nan << std::nan("");
  CHECK_THAT(error(nan, WeightsLayout::psi, true), Catch::Contains("not finite"));
  RowMatrix overflow(1, 2);
  overflow << 1e-300, 1e300;
  CHECK_THAT(error(overflow, WeightsLayout::stonesoup), Catch::Contains("column 2") && Catch::Contains("overflows"));
  CHECK_THAT(input_error_message([] { dabench::parse_weights_layout("pyehm"); }),
             Catch::Contains("'pyehm'") && Catch::Contains("stonesoup"));
}

TEST_CASE("weights layouts: dabench solve --layout and --log read them", "[layout][cli]") {
  namespace cli = dabench::test::cli;
  cli::TempDir dir;
  dir.write("psi.csv", "2,0.5\n1,3\n");
  dir.write("stonesoup.csv", "0.5,1,0.25\n2,2,6\n");             // missed detection first, ×0.5 and ×2
  dir.write("tcl.csv", "1,0.25,0.5,0\n2,6,0,2\n");               // ×0.5 and ×2, missed on the diagonal block
  dir.write("matlab.csv", "0,0.5,2\n1,1,2\n0.5,0.125,3\n");       // transposed, clutter 1 and 0.5
  dir.write("log.csv", fmt::format("{},{}\n{},{}\n", std::log(2.0), std::log(0.5), 0.0, std::log(3.0)));
  const cli::CliResult psi = cli::run_dabench(dir, {"solve", "--algorithm", "exact", "--weights", "psi.csv"});
  REQUIRE(psi.status == 0);
  for (const auto& [file, layout] : {std::pair{"stonesoup.csv", "stonesoup"}, std::pair{"tcl.csv", "tcl"},
                                     std::pair{"matlab.csv", "matlab"}, std::pair{"psi.csv", "psi"}}) {
    const cli::CliResult other = cli::run_dabench(dir, {"solve", "--algorithm", "exact", "--weights", file, "--layout", layout});
    INFO(file << ": " << other.err);
    REQUIRE(other.status == 0);
    CHECK(other.out == psi.out);
  }
  const cli::CliResult log = cli::run_dabench(dir, {"solve", "--algorithm", "exact", "--weights", "log.csv", "--log"});
  REQUIRE(log.status == 0);
  const cli::CsvTable from_log = cli::parse_csv(log.out), from_psi = cli::parse_csv(psi.out);
  REQUIRE(from_log.rows.size() == from_psi.rows.size());
  for (std::size_t r = 0; r < from_psi.rows.size(); ++r) {  // exp(log ψ) is ψ to rounding
    CHECK(cli::to_double(from_log.at(r, "probability")) == Approx(cli::to_double(from_psi.at(r, "probability"))).epsilon(1e-14));
  }
  const cli::CliResult bad = cli::run_dabench(dir, {"solve", "--algorithm", "exact", "--weights", "psi.csv", "--layout", "pyehm"});
  CHECK(bad.status == 2);
  CHECK(cli::contains(bad.err, "unknown weights layout 'pyehm'"));
}

}  // namespace DABENCH_TEST_FILE
