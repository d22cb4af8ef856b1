#include "harness/multi_scan/particle_metrics.hpp"

#include <cmath>
#include <limits>

namespace dabench {

ParticleBeliefMetrics particle_belief_metrics(const Vector& belief, const Vector& density_scale, const Vector& prior,
                                              int probe) {
  const double truth_density = belief[probe] * density_scale[probe];
  const double truth_likelihood = belief[probe] / prior[probe];
  double mass = 0.0, above = 0.0, above_likelihood = 0.0, weighted_log = 0.0;
  for (Eigen::Index p = 0; p < belief.size(); ++p) {
    const double q = belief[p];
    if (p == probe || !(q > 0.0)) continue;
    const double density = q * density_scale[p];
    mass += q;
    if (density >= truth_density) above += q;
    if (q / prior[p] >= truth_likelihood) above_likelihood += q;
    weighted_log += q * std::log(density);
  }
  if (!(mass > 0.0)) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return {nan, nan, nan};
  }
  // q̃ = q/mass: −Σ q̃ log(q̃ s) = −(Σ q log(q s))/mass + log mass.
  return {above / mass, -(weighted_log / mass - std::log(mass)), above_likelihood / mass};
}

}  // namespace dabench
