#include "damped_bp.hpp"

#include <algorithm>
#include <cmath>

#include "harness/single_scan/registry.hpp"

namespace outside {

std::string DampedBpOptions::validate() const {
  if (!(damping >= 0.0 && damping < 1.0)) return "damping must be in [0, 1)";
  if (!(tolerance > 0.0)) return "tolerance must be > 0";
  if (max_iterations < 1) return "max_iterations must be >= 1";
  return {};
}

void DampedBp::solve(const dabench::SingleScanProblem& problem, dabench::MarginalTable& marginals,
                     dabench::SolveReport& report) {
  report.reset();
  const int n = problem.targets();
  const int m = problem.measurements();
  psi_.resize(n, m);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) psi_(i, j) = problem.normalized_weight(i, j);
  }
  report.w_star = n > 0 && m > 0 ? psi_.rowwise().sum().maxCoeff() : 0.0;  // W* of Lemma 2
  mu_.resize(n, m);
  nu_.setOnes(n, m);  // ν = 1 at the start (Fig. 3)

  const double d = options_.damping;
  int iterations = 0;
  bool converged = n == 0 || m == 0;
  while (!converged && iterations < options_.max_iterations) {
    for (int i = 0; i < n; ++i) {  // eq (20)
      const double s = 1.0 + psi_.row(i).dot(nu_.row(i));
      for (int j = 0; j < m; ++j) mu_(i, j) = psi_(i, j) / (s - psi_(i, j) * nu_(i, j));
    }
    double change = 0.0;
    for (int j = 0; j < m; ++j) {  // eq (21), damped
      const double t = 1.0 + mu_.col(j).sum();
      for (int i = 0; i < n; ++i) {
        const double next = (1.0 - d) / (t - mu_(i, j)) + d * nu_(i, j);
        change = std::max(change, std::fabs(next - nu_(i, j)) / nu_(i, j));
        nu_(i, j) = next;
      }
    }
    ++iterations;
    converged = change < options_.tolerance;
  }
  report.iterations = iterations;
  report.converged = converged;

  marginals.reshape(n, m);  // eq (22)
  for (int i = 0; i < n; ++i) {
    const double s = 1.0 + psi_.row(i).dot(nu_.row(i));
    marginals(i, 0) = 1.0 / s;
    for (int j = 0; j < m; ++j) marginals(i, j + 1) = psi_(i, j) * nu_(i, j) / s;
  }
}

// One line makes `damped-bp` a SPEC like any built-in algorithm's (dabench list, run, solve).
DABENCH_REGISTER_SINGLE_SCAN_ALGORITHM(DampedBp);

}  // namespace outside
