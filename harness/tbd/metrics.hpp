#pragma once
// Per-step metrics of a track-before-detect run (tbd-bp-supplement, Figs 3-4; the letter's
// Fig. 2): GOSPA (harness/tbd/gospa.hpp) between the true positions of the objects that exist
// at step k and the positions a tracker reports at k, with its parts, in the options' order p
// and, since the letter's order is not known (docs/models/track-before-detect.md §5.1), also in order 2.
#include <string>
#include <vector>

#include "harness/core/params.hpp"
#include "harness/tbd/gospa.hpp"
#include "harness/tbd/problem.hpp"

namespace dabench {

struct TbdMetricsOptions {
  // Defaults (docs/models/track-before-detect.md §5.1, inferred from supplement Fig. 3, where TBD-BP reads exactly
  // 1.00 while one object is missed: (c^p/α)^{1/p} = 1).
  double gospa_cutoff = 2.0;  // c, m
  double gospa_order = 1.0;   // p (the second GOSPA column is always p = 2)
  double gospa_alpha = 2.0;   // α (the parts localisation/missed/false need α = 2)

  void bind(ParamList& p) {
    p.add("gospa_cutoff", gospa_cutoff, "GOSPA cut-off c, m");
    p.add("gospa_order", gospa_order, "GOSPA order p of the `gospa` column (`gospa_p2` is order 2)");
    p.add("gospa_alpha", gospa_alpha, "GOSPA alpha in (0, 2]; the parts need alpha = 2");
  }
  std::string validate() const;  // "" if valid
  GospaOptions gospa(double order) const { return {gospa_cutoff, order, gospa_alpha}; }
};

struct TbdStepMetrics {
  int objects = 0;            // true objects existing at k
  int estimates = 0;          // objects the tracker reports at k
  double gospa = 0.0;         // order p
  double gospa_p2 = 0.0;      // order 2
  double localisation = 0.0;  // order-p parts (α = 2; NaN otherwise): Σ d^p over assigned pairs,
  double missed = 0.0;        //   missed objects (count),
  double false_objects = 0.0; //   false estimates (count)
};

// Scores one step; keeps its workspace, so repeated calls do not allocate once grown.
class TbdScorer {
 public:
  explicit TbdScorer(const TbdMetricsOptions& options) : options_(options) {}
  TbdStepMetrics score(const TbdTruth& truth, int k, const std::vector<TbdEstimate>& estimates);

 private:
  TbdMetricsOptions options_;
  Gospa gospa_;
  std::vector<Eigen::Vector2d> truth_points_;
  std::vector<Eigen::Vector2d> estimate_points_;
};

}  // namespace dabench
