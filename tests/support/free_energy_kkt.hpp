#pragma once
// An independent optimality check of the multiple-scan convex free energy (63)
// (multiscan-convex-variational): at a point (q^i(A), q^i_t(A, a)) with every factor > 0 the
// point is interior, so the KKT conditions reduce to a vanishing gradient of (63) projected
// onto the null space of each track's equality constraints (57)–(58). It shares no formula with
// either solver: the gradient is written from (63) term by term, with q^{i,j}_t = Σ_A q_t(A, j)
// (59) and the clutter beliefs q^{0,j}_t given by the caller (the column constraint (61) is
// checked separately, so that cancellation in 1 − Σ_i q^{i,j} does not enter the gradient).
#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include "harness/multi_scan/problem.hpp"

namespace dabench::test {

struct FreeEnergyPoint {
  std::vector<Vector> track;                  // q^i(A)
  std::vector<std::vector<RowMatrix>> pair;   // [scan][track]: q^i_t(A, a)
  std::vector<Vector> clutter;                // [scan]: q^{0,j}_t, j = 1..m_t
};

// Largest component of the projected gradient of (63) with coefficients γ_t, β_t.
inline double projected_gradient(const MultiScanProblem& problem, const FreeEnergyPoint& point,
                                 const std::vector<double>& gamma, const std::vector<double>& beta) {
  const int n = problem.tracks();
  const int scans = problem.scan_count();
  std::vector<RowMatrix> association(scans);
  for (int t = 0; t < scans; ++t) {
    association[t].resize(n, problem.scans[t].measurements + 1);
    for (int i = 0; i < n; ++i) association[t].row(i) = point.pair[t][i].colwise().sum();
  }
  double largest = 0.0;
  for (int i = 0; i < n; ++i) {
    const int h_count = problem.hypotheses(i);
    std::vector<int> offset(scans + 1, h_count);
    for (int t = 0; t < scans; ++t) offset[t + 1] = offset[t] + h_count * (problem.scans[t].measurements + 1);
    const int size = offset[scans];
    Vector gradient(size);
    const Vector& q = point.track[i];
    for (int h = 0; h < h_count; ++h) gradient[h] = (1.0 - scans) * (std::log(q[h]) + 1.0) - std::log(problem.prior[i][h]);
    for (int t = 0; t < scans; ++t) {
      const int columns = problem.scans[t].measurements + 1;
      for (int h = 0; h < h_count; ++h) {
        for (int a = 0; a < columns; ++a) {
          double g = std::log(point.pair[t][i](h, a)) + 1.0 - std::log(problem.scans[t].factor[i](h, a));
          if (a > 0) {
            g += -beta[t] * (std::log(point.clutter[t][a - 1]) + 1.0) + gamma[t] * (std::log1p(-association[t](i, a)) + 1.0);
          }
          gradient[offset[t] + h * columns + a] = g;
        }
      }
    }
    // Constraints: Σ_A q(A) = 1; Σ_a q_t(A, a) − q(A) = 0 for every t, A.
    Eigen::MatrixXd constraint = Eigen::MatrixXd::Zero(1 + scans * h_count, size);
    constraint.row(0).head(h_count).setOnes();
    for (int t = 0; t < scans; ++t) {
      const int columns = problem.scans[t].measurements + 1;
      for (int h = 0; h < h_count; ++h) {
        const int row = 1 + t * h_count + h;
        constraint(row, h) = -1.0;
        constraint.block(row, offset[t] + h * columns, 1, columns).setOnes();
      }
    }
    const Eigen::MatrixXd gram = constraint * constraint.transpose();
    const Vector projected = gradient - constraint.transpose() * gram.ldlt().solve(constraint * gradient);
    largest = std::max(largest, projected.cwiseAbs().maxCoeff());
  }
  return largest;
}

// Largest |Σ_i q^{i,j}_t + q^{0,j}_t − 1| (61) and |Σ_a q_t(A, a) − q(A)| (58).
inline double constraint_violation(const FreeEnergyPoint& point) {
  double largest = 0.0;
  for (std::size_t t = 0; t < point.pair.size(); ++t) {
    Vector column = point.clutter[t];
    for (std::size_t i = 0; i < point.track.size(); ++i) {
      const RowMatrix& pair = point.pair[t][i];
      column += pair.colwise().sum().tail(pair.cols() - 1).transpose();
      largest = std::max(largest, (pair.rowwise().sum() - point.track[i]).cwiseAbs().maxCoeff());
    }
    if (column.size() > 0) largest = std::max(largest, (column.array() - 1.0).abs().maxCoeff());
  }
  return largest;
}

}  // namespace dabench::test
