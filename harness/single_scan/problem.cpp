#include "harness/single_scan/problem.hpp"

#include <algorithm>

#include <fmt/format.h>

namespace dabench {

std::string SingleScanProblem::validate() const {
  for (Eigen::Index i = 0; i < psi.rows(); ++i) {
    for (Eigen::Index j = 0; j < psi.cols(); ++j) {
      const double w = psi(i, j);
      if (!std::isfinite(w) || w < 0.0) {
        return fmt::format("weight psi[{}][{}] = {} (must be finite and >= 0)", i + 1, j + 1, w);
      }
    }
  }
  if (miss_weight.size() != 0 && miss_weight.size() != psi.rows()) {
    return fmt::format("{} missed-detection weights for {} targets", miss_weight.size(), psi.rows());
  }
  if (clutter_weight.size() != 0 && clutter_weight.size() != psi.cols()) {
    return fmt::format("{} clutter weights for {} measurements", clutter_weight.size(), psi.cols());
  }
  for (Eigen::Index i = 0; i < miss_weight.size(); ++i) {
    if (!std::isfinite(miss_weight[i]) || miss_weight[i] < 0.0) {
      return fmt::format("missed-detection weight w[{}][0] = {} (must be finite and >= 0)", i + 1, miss_weight[i]);
    }
  }
  for (Eigen::Index j = 0; j < clutter_weight.size(); ++j) {
    if (!std::isfinite(clutter_weight[j]) || clutter_weight[j] <= 0.0) {
      return fmt::format("clutter weight w[0][{}] = {} (must be finite and > 0)", j + 1, clutter_weight[j]);
    }
  }
  return {};
}

double SingleScanProblem::largest_weight_sum() const {
  double largest = 0.0;  // two passes over ψ rather than a column buffer: no allocation per solve
  for (int i = 0; i < targets(); ++i) {
    double row = 1.0;
    for (int j = 0; j < measurements(); ++j) row += normalized_weight(i, j);
    largest = std::max(largest, row);
  }
  for (int j = 0; j < measurements(); ++j) {
    double column = 1.0;
    for (int i = 0; i < targets(); ++i) column += normalized_weight(i, j);
    largest = std::max(largest, column);
  }
  return largest;
}

}  // namespace dabench
