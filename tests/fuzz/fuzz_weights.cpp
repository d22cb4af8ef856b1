// libFuzzer target: the weights CSV of `dabench solve --weights FILE` (harness/single_scan/
// weights_csv.hpp), and, when the matrix it gives is small, the solvers on it, as the library
// entry point runs them (a table that is not a distribution is recorded as skipped:numerical
// there). Findings: parsing gives neither a problem nor an InputError; two exact methods
// (enumeration, EHM, the junction tree, the permanent, k-best JPDA with k beyond every cluster's
// event count) that both solve disagree by more than 1e-9; an exact method solves a problem on
// which an approximation (BP, fractional BP, BAA, correlation decay, MAP, cheap and modified cheap
// JPDA, k-best JPDA with few events) reports skipped:numerical, unless a row or column sum of ψ
// reaches SingleScanProblem::kOutOfRangeSum (2^1020), where sums of messages can overflow.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstdio>
#include <iterator>
#include <sstream>
#include <string>

#include "harness/core/errors.hpp"
#include "harness/run/library.hpp"
#include "harness/single_scan/weights_csv.hpp"

namespace {

[[noreturn]] void finding(const std::string& what) {
  std::fprintf(stderr, "fuzz_weights: %s\n", what.c_str());
  std::abort();
}

// A 6 × 6 problem has Σ_k C(6,k)² k! = 13327 joint events, so k = 20000 keeps them all.
constexpr const char* kExact[] = {"exact", "ehm", "jt", "permanent", "kbest-jpda:k=20000"};
constexpr const char* kApproximate[] = {"bp", "fbp", "baa", "cd", "map", "cheap-jpda", "modified-cheap-jpda", "kbest-jpda:k=3"};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace dabench;
  SingleScanProblem problem;
  try {
    std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
    problem = parse_weights_csv("fuzz.csv", in);
  } catch (const InputError&) {
    return 0;
  }
  const int targets = problem.targets(), measurements = problem.measurements();
  if (targets > 6 || measurements > 6) return 0;  // enumeration stays cheap
  const SingleScanResult* first = nullptr;
  const char* first_name = nullptr;
  SingleScanResult exact[std::size(kExact)];
  for (std::size_t k = 0; k < std::size(kExact); ++k) {
    exact[k] = solve_single_scan(kExact[k], problem);
    if (!exact[k].report.skipped.empty()) continue;
    if (!first) {
      first = &exact[k], first_name = kExact[k];
      continue;
    }
    for (int i = 0; i < targets; ++i) {
      for (int j = 0; j <= measurements; ++j) {
        if (std::abs(exact[k].marginals(i, j) - first->marginals(i, j)) > 1e-9) {
          finding(std::string(first_name) + " and " + kExact[k] + " disagree");
        }
      }
    }
  }
  if (!first) return 0;
  if (!(problem.largest_weight_sum() < SingleScanProblem::kOutOfRangeSum)) return 0;
  for (const char* name : kApproximate) {
    if (solve_single_scan(name, problem).report.skipped == "numerical") {
      finding(std::string(name) + ": skipped:numerical where " + first_name + " solves");
    }
  }
  return 0;
}
