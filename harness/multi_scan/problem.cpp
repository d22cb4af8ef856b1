#include "harness/multi_scan/problem.hpp"

#include <cmath>

#include <fmt/format.h>

namespace dabench {

std::string MultiScanProblem::validate() const {
  for (int i = 0; i < tracks(); ++i) {
    const Vector& weights = prior[i];
    if (weights.size() == 0) return fmt::format("track {} has no hypotheses", i + 1);
    bool positive = false;
    for (Eigen::Index h = 0; h < weights.size(); ++h) {
      if (!std::isfinite(weights[h]) || weights[h] < 0.0) {
        return fmt::format("prior weight of track {} hypothesis {} = {} (must be finite and >= 0)", i + 1, h + 1,
                           weights[h]);
      }
      positive = positive || weights[h] > 0.0;
    }
    if (!positive) return fmt::format("track {} has an all-zero prior", i + 1);
  }
  for (int t = 0; t < scan_count(); ++t) {
    const ScanFactors& scan = scans[t];
    if (scan.measurements < 0) return fmt::format("scan {} has {} measurements", t + 1, scan.measurements);
    if (static_cast<int>(scan.factor.size()) != tracks()) {
      return fmt::format("scan {} has factors for {} tracks, expected {}", t + 1, scan.factor.size(), tracks());
    }
    for (int i = 0; i < tracks(); ++i) {
      const RowMatrix& factor = scan.factor[i];
      if (factor.rows() != hypotheses(i) || factor.cols() != scan.measurements + 1) {
        return fmt::format("scan {} track {}: factor is {}x{}, expected {}x{}", t + 1, i + 1, factor.rows(),
                           factor.cols(), hypotheses(i), scan.measurements + 1);
      }
      for (Eigen::Index h = 0; h < factor.rows(); ++h) {
        for (Eigen::Index j = 0; j < factor.cols(); ++j) {
          if (!std::isfinite(factor(h, j)) || factor(h, j) < 0.0) {
            return fmt::format("scan {} track {} factor[{}][{}] = {} (must be finite and >= 0)", t + 1, i + 1, h + 1,
                               j, factor(h, j));
          }
        }
      }
    }
  }
  return {};
}

}  // namespace dabench
