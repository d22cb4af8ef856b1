#include "algorithms/tracking/meta_state_chain.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "harness/core/errors.hpp"

namespace dabench {

namespace {

// e^{ξ(s) − max ξ} for s = 0, 1, and max ξ.
struct ScaledEvidence {
  std::array<double, 2> weight;
  double offset;
};

ScaledEvidence scaled(const std::array<double, 2>& xi) {
  const double top = std::max(xi[0], xi[1]);
  return {{std::exp(xi[0] - top), std::exp(xi[1] - top)}, top};
}

void check(const std::vector<std::array<double, 2>>& evidence, double initial_active, double stay) {
  if (!(initial_active >= 0.0 && initial_active <= 1.0))
    throw InputError(fmt::format("meta-state chain: p(s_1 = 1) = {} must be in [0, 1]", initial_active));
  if (!(stay > 0.0 && stay < 1.0)) throw InputError(fmt::format("meta-state chain: stay = {} must be in (0, 1)", stay));
  for (std::size_t k = 0; k < evidence.size(); ++k) {
    const auto& xi = evidence[k];
    const bool valid = !std::isnan(xi[0]) && !std::isnan(xi[1]) && xi[0] != HUGE_VAL && xi[1] != HUGE_VAL &&
                       std::max(xi[0], xi[1]) > -HUGE_VAL;
    if (!valid) throw InputError(fmt::format("meta-state chain: evidence of scan {} is not finite or −∞ (or both −∞)", k));
  }
}

}  // namespace

void meta_state_forward_backward(const std::vector<std::array<double, 2>>& evidence, double initial_active,
                                 double stay, MetaStateChain& result) {
  check(evidence, initial_active, stay);
  const int scans = static_cast<int>(evidence.size());
  const double move = 1.0 - stay;
  result.active.assign(scans, 0.0);
  result.pairwise.assign(std::max(0, scans - 1), {0.0, 0.0, 0.0, 0.0});
  result.log_partition = 0.0;
  if (scans == 0) return;

  // Forward pass (Module 2, steps 5–8), normalised: forward[k] = α_k / Σ α_k, scale[k] the norm.
  std::vector<std::array<double, 2>> forward(scans);
  std::vector<double> scale(scans);
  std::array<double, 2> predicted{1.0 - initial_active, initial_active};
  for (int k = 0; k < scans; ++k) {
    if (k > 0) {
      const auto& f = forward[k - 1];
      predicted = {stay * f[0] + move * f[1], move * f[0] + stay * f[1]};
    }
    const ScaledEvidence b = scaled(evidence[k]);
    const double a0 = predicted[0] * b.weight[0], a1 = predicted[1] * b.weight[1];
    scale[k] = a0 + a1;
    if (!(scale[k] > 0.0))
      throw InputError(fmt::format("meta-state chain: the evidence of scan {} excludes every state the prior allows", k));
    forward[k] = {a0 / scale[k], a1 / scale[k]};
    result.log_partition += std::log(scale[k]) + b.offset;
  }

  // Backward pass (Module 2, steps 9–12) in the same normalisation, and the marginals (step 13).
  std::array<double, 2> backward{1.0, 1.0};
  result.active[scans - 1] = forward[scans - 1][1];
  for (int k = scans - 2; k >= 0; --k) {
    const ScaledEvidence b = scaled(evidence[k + 1]);
    const double next0 = b.weight[0] * backward[0] / scale[k + 1];
    const double next1 = b.weight[1] * backward[1] / scale[k + 1];
    const auto& f = forward[k];
    result.pairwise[k] = {f[0] * stay * next0, f[0] * move * next1, f[1] * move * next0, f[1] * stay * next1};
    backward = {stay * next0 + move * next1, move * next0 + stay * next1};
    const double q0 = f[0] * backward[0], q1 = f[1] * backward[1];
    result.active[k] = q1 / (q0 + q1);
  }
}

double meta_state_filter_step(double previous_active, double stay, const std::array<double, 2>& evidence) {
  check({evidence}, previous_active, stay);
  const double move = 1.0 - stay;
  const ScaledEvidence b = scaled(evidence);
  const double p0 = (stay * (1.0 - previous_active) + move * previous_active) * b.weight[0];
  const double p1 = (move * (1.0 - previous_active) + stay * previous_active) * b.weight[1];
  return p1 / (p0 + p1);
}

}  // namespace dabench
