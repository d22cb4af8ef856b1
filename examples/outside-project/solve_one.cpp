// Solves one single-scan problem through dabench's library entry point (harness/run/library.hpp):
// this project's damped-bp by SPEC and by typed options, dabench's bp by typed options, and
// exact marginals by SPEC. Prints the marginals; exits 1 if the SPEC and typed results of
// damped-bp differ in any bit, or if damped-bp has not reached BP's fixed point.
#include <cmath>
#include <cstdio>
#include <string>

#include "algorithms/single_scan/bp.hpp"
#include "damped_bp.hpp"
#include "harness/run/library.hpp"

namespace {

void print(const std::string& title, const dabench::SingleScanResult& result) {
  std::printf("%s: %d iterations, converged %d\n", title.c_str(), result.report.iterations,
              result.report.converged ? 1 : 0);
  for (int i = 0; i < result.marginals.targets(); ++i) {
    std::printf("  target %d:", i + 1);
    for (int j = 0; j <= result.marginals.measurements(); ++j) std::printf(" %.6f", result.marginals(i, j));
    std::printf("\n");
  }
}

double max_difference(const dabench::MarginalTable& a, const dabench::MarginalTable& b) {
  return (a.view() - b.view()).cwiseAbs().maxCoeff();
}

}  // namespace

int main() {
  try {
    // Three targets, three measurements, every pair gated: a loopy graph, where BP is approximate.
    dabench::RowMatrix psi(3, 3);
    psi << 2.0, 0.5, 1.0,
           1.5, 3.0, 0.2,
           0.7, 1.1, 4.0;
    const dabench::SingleScanProblem problem = dabench::make_single_scan_problem(psi);
    std::printf("marginals p(a_i = j), columns j = 0 (missed) .. 3\n");

    const auto exact = dabench::solve_single_scan("exact", problem);
    const auto by_spec = dabench::solve_single_scan("damped-bp:damping=0.5", problem);
    const auto typed = dabench::solve_single_scan<outside::DampedBp>(problem, {.damping = 0.5});
    const auto bp = dabench::solve_single_scan<dabench::BeliefPropagation>(problem, {.delta = 1e-12});
    for (const auto* result : {&exact, &by_spec, &typed, &bp}) {
      if (!result->report.skipped.empty()) {
        std::fprintf(stderr, "outside-solve: skipped:%s\n", result->report.skipped.c_str());
        return 1;
      }
    }
    print("exact (SPEC \"exact\")", exact);
    print("damped-bp (SPEC \"damped-bp:damping=0.5\")", by_spec);
    print("damped-bp (typed, DampedBp::Options{.damping = 0.5})", typed);
    print("bp (typed, BeliefPropagation::Options{.delta = 1e-12})", bp);

    const double spec_vs_typed = max_difference(by_spec.marginals, typed.marginals);
    const double damped_vs_bp = max_difference(by_spec.marginals, bp.marginals);
    std::printf("max |SPEC - typed| = %g (damped-bp)\n", spec_vs_typed);
    std::printf("max |damped-bp - bp| = %.2g (the same fixed point)\n", damped_vs_bp);
    std::printf("max |damped-bp - exact| = %.4f (BP is approximate on a loopy graph)\n",
                max_difference(by_spec.marginals, exact.marginals));
    if (spec_vs_typed != 0.0 || by_spec.report.iterations != typed.report.iterations || !(damped_vs_bp < 1e-9)) {
      std::fprintf(stderr, "outside-solve: FAILED: the checks above do not hold\n");
      return 1;
    }
    return 0;
  } catch (const dabench::InputError& error) {
    std::fprintf(stderr, "outside-solve: %s\n", error.what());
    return 2;
  }
}
