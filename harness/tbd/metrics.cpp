#include "harness/core/special_values.hpp"
#include "harness/tbd/metrics.hpp"

#include <cmath>

namespace dabench {

std::string TbdMetricsOptions::validate() const {
  if (!(gospa_cutoff > 0.0) || !std::isfinite(gospa_cutoff)) return "gospa_cutoff must be finite and > 0";
  if (!(gospa_order >= 1.0) || !std::isfinite(gospa_order)) return "gospa_order must be finite and >= 1";
  if (!(gospa_alpha > 0.0 && gospa_alpha <= 2.0)) return "gospa_alpha must be in (0, 2]";
  return {};
}

TbdStepMetrics TbdScorer::score(const TbdTruth& truth, int k, const std::vector<TbdEstimate>& estimates) {
  truth_points_.clear();
  for (const TbdTruth::Object& object : truth.objects) {
    if (object.alive[k]) truth_points_.emplace_back(object.states(0, k), object.states(1, k));
  }
  estimate_points_.clear();
  for (const TbdEstimate& estimate : estimates) estimate_points_.emplace_back(estimate.state(0), estimate.state(1));

  TbdStepMetrics m;
  m.objects = static_cast<int>(truth_points_.size());
  m.estimates = static_cast<int>(estimate_points_.size());
  const GospaResult main = gospa_.compute(truth_points_, estimate_points_, options_.gospa(options_.gospa_order));
  m.gospa = main.distance;
  m.gospa_p2 = gospa_.compute(truth_points_, estimate_points_, options_.gospa(2.0)).distance;
  const bool parts = options_.gospa_alpha == 2.0;
  m.localisation = parts ? main.localisation : kNaN;
  m.missed = parts ? main.missed_count : kNaN;
  m.false_objects = parts ? main.false_count : kNaN;
  return m;
}

}  // namespace dabench
